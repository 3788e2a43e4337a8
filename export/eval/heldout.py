"""Predictions on held-out people, measured: accuracy against the ground truth (best-of-K ADE/FDE,
root-relative and full positions, at each horizon), spread (APD) and plausibility of the raw outputs
(bone-length error, feet below the floor, the first frame's jump). One window list, one loop, pure
metrics from metrics.py; the results table (issue 18) and the quick `python -m export heldout` both
read it.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

from ..data.clip import Clip
from ..ops.bones import bone_lengths
from . import metrics as M

Predict = Callable[[np.ndarray, int, int, str], np.ndarray]   # (history, frames, seed, action) -> [K, frames, J, 3]


@dataclass
class HeldOutWindow:
    clip: str
    subject: object
    action: str
    history: np.ndarray        # [N, J, 3] world (N may exceed the window's history: earlier context)
    truth: np.ndarray | None   # [H, J, 3] world, the frames after the history (None without a horizon)
    present: int = -1          # the clip frame of the last history frame


def cut_windows(clips: list[Clip], part: str, history: int, horizon: int, stride: int,
                context: int | None = None) -> list[HeldOutWindow]:
    """Windows of history + horizon frames inside each clip's `part` ranges ("test": the held-out people,
    "train": the training people), `stride` apart, straight from the world-frame positions (never padded,
    never loop-repeated). Each keeps up to `context` >= history frames before its present (fewer where
    the range starts later), so a row that reads a longer history sees the same windows."""
    if part not in ("train", "test"):
        raise ValueError(f"part must be 'train' or 'test', got {part!r}")
    context = max(context or history, history)
    out = []
    for c in clips:
        for a, b in (c.split.test if part == "test" else c.split.train):
            for s in range(a, b - history - horizon + 1, stride):
                p = s + history - 1
                out.append(HeldOutWindow(c.name, c.subject, c.action, c.positions[max(a, p + 1 - context):p + 1],
                                         c.positions[p + 1:p + 1 + horizon] if horizon else None, p))
    return out


def heldout_windows(clips: list[Clip], history: int, horizon: int, stride: int) -> list[HeldOutWindow]:
    """Every window of history + horizon frames inside the test ranges (held-out people), `stride` apart."""
    return cut_windows(clips, "test", history, horizon, stride)


def measure(futures: np.ndarray, w: HeldOutWindow, horizons: list[int]) -> dict[str, float]:
    """One window's numbers. Horizons in frames (each at most the truth's length)."""
    out = {}
    for h in horizons:
        for rel, tag in ((True, "rel"), (False, "full")):
            ade, fde = M.ade_fde(futures[:, :h], w.truth[:h], root_relative=rel)
            out[f"ade_{tag}_{h}"], out[f"fde_{tag}_{h}"] = ade, fde
    h = max(horizons)
    out["apd"] = M.apd(M.root_relative(futures[:, :h]))
    ref = bone_lengths(w.history).mean(0)
    out["bone"] = float(np.mean([M.bone_length_error(f[:h], ref) for f in futures]))
    out["foot"] = float(np.mean([M.foot_below_floor(f[:h]) for f in futures]))
    jumps = [M.first_frame_jump(w.history, f) for f in futures]
    out["jump_ok"] = float(np.mean([M.jump_ok(j, s) for j, s in jumps]))
    out["jump_ratio"] = float(np.median([j / max(s, 1e-9) for j, s in jumps]))
    return out


def evaluate(predict: Predict, windows: list[HeldOutWindow], horizons: list[int], seed: int = 0) -> dict[str, float]:
    """Mean over windows of measure(); also per action."""
    rows = [measure(predict(w.history, max(horizons), seed + i, w.action), w, horizons) for i, w in enumerate(windows)]
    keys = rows[0].keys()
    return {k: float(np.mean([r[k] for r in rows])) for k in keys}
