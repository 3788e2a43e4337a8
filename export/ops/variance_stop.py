"""WAT's variance stopping (Eq. 8): a sample ends where its prediction has become static.

v_i = 1/Q * sum_{j=i}^{i+Q-1} ||y_j - mean(y_i..y_{i+Q-1})||_2, each y_j a whole pose (K = J*3
coordinates, metres). The prediction stops at the first frame i >= T_min with v_i < delta and keeps
frames 1..i, i.e. it ends on the first pose of the static window. Twin: web/src/sampling/variance-stop.ts.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np


def variance_curve(frames: np.ndarray, q: int) -> np.ndarray:
    """frames [T, J, 3] (or [T, K]) -> v [T - q + 1]; v[f] is v_i for the window starting at 0-based frame f.

    Eq. 8 as printed sums j = i..i+Q (Q+1 terms) but divides by Q; we use the Q frames i..i+Q-1,
    so the window is exactly Q frames as the issue states.
    """
    y = np.asarray(frames, dtype=np.float64).reshape(len(frames), -1)
    if q < 1 or len(y) < q:
        raise ValueError(f"need at least q={q} frames for a variance window, got {len(y)}")
    win = np.lib.stride_tricks.sliding_window_view(y, q, axis=0)      # [T-q+1, K, q]
    mean = win.mean(axis=2, keepdims=True)
    return np.linalg.norm(win - mean, axis=1).mean(axis=1)


@dataclass
class Stop:
    length: int          # frames kept (1-based index of the stop frame), or T_max
    stopped: bool        # False: no window fell below delta; the sample keeps T_max frames
    margin: float        # smallest |v_i - delta| over the windows tested (i = T_min .. length)


def first_stop(curve: np.ndarray, delta: float, min_frames: int, max_frames: int) -> Stop:
    """The stop rule on one curve (from variance_curve over max_frames predicted frames)."""
    # Windows are tested from i = T_min (1-based), i.e. 0-based f = T_min - 1.
    tested = np.asarray(curve[min_frames - 1:], dtype=np.float64)
    below = np.flatnonzero(tested < delta)
    if len(below):
        f = int(below[0])
        return Stop(min_frames + f, True, float(np.abs(tested[:f + 1] - delta).min()))
    margin = float(np.abs(tested - delta).min()) if len(tested) else float("inf")
    return Stop(max_frames, False, margin)
