"""Resampling by time: root positions linearly, joint rotations by slerp."""
from __future__ import annotations

import numpy as np

from .rotations import slerp


def resample(times: np.ndarray, root_pos: np.ndarray, local: np.ndarray,
             new_times: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Sample a motion given at increasing `times` [F] at `new_times` (inside the time range)."""
    times = np.asarray(times, dtype=np.float64)
    if np.any(np.diff(times) <= 0):
        raise ValueError("frame times must increase strictly")
    if new_times[0] < times[0] - 1e-9 or new_times[-1] > times[-1] + 1e-9:
        raise ValueError("resampling outside the clip's time range")
    idx = np.clip(np.searchsorted(times, new_times, side="right") - 1, 0, len(times) - 2)
    t = np.clip((new_times - times[idx]) / (times[idx + 1] - times[idx]), 0.0, 1.0)
    pos = root_pos[idx] * (1 - t)[:, None] + root_pos[idx + 1] * t[:, None]
    rot = slerp(local[idx], local[idx + 1], np.broadcast_to(t[:, None], (len(t), local.shape[1])))
    return pos, rot
