"""From keyposes back to frames (Keyposes paper, Eq. 3): linear interpolation between consecutive
keyposes, P_t1 = C_li + (t1 - t) (C_li+1 - C_li) / d_i+1.

The first segment starts from the present pose (not from its centre), so the future joins the
history without a jump. TypeScript twin: web/src/sampling/keypose-interpolation.ts.
"""
from __future__ import annotations

import numpy as np


def keypose_times(durations) -> np.ndarray:
    """Frame of each keypose after the present (the present is t = 0)."""
    return np.cumsum(np.asarray(durations, dtype=np.int64))


def interpolate(present: np.ndarray, keyposes: np.ndarray, durations, frames: int) -> np.ndarray:
    """present [J, 3], keyposes [n, J, 3] reached after durations [n] frames each -> future frames
    t = 1..frames as [frames, J, 3] float64; past the last keypose its pose is held."""
    keyposes = np.asarray(keyposes, dtype=np.float64)
    durations = np.asarray(durations, dtype=np.int64)
    if len(keyposes) != len(durations):
        raise ValueError(f"{len(keyposes)} keyposes but {len(durations)} durations")
    if len(durations) and durations.min() < 1:
        raise ValueError(f"keypose durations must be at least 1 frame, got {durations.min()}")
    present = np.asarray(present, dtype=np.float64)
    out = np.repeat((keyposes[-1] if len(keyposes) else present)[None], frames, axis=0)  # held past the end
    if not len(durations):
        return out
    ends = keypose_times(durations)
    t = np.arange(1, frames + 1)
    live = t <= ends[-1]
    seg = np.searchsorted(ends, t[live], side="left")          # segment i covers (ends[i] - d_i, ends[i]]
    starts = np.concatenate([present[None], keyposes[:-1]])[seg]
    step = (t[live] - (ends[seg] - durations[seg]))[:, None, None]
    out[live] = starts + step * (keyposes[seg] - starts) / durations[seg][:, None, None]
    return out
