"""Ghost poses move with their future: a step that moves a future's root after the method (planted feet,
ops/foot_plant.py) moves each ghost by its future's root shift at the ghost's frame, so a ghost stands
where the drawn figure stands. Twin of web/src/predictor/ghosts.ts (same float64 sums, float32 out)."""
from __future__ import annotations

import numpy as np


def follow_roots(ghosts: dict, before: np.ndarray, after: np.ndarray) -> None:
    """In place: ghosts {"frames": [K][n], "poses": [K][n, J, 3]} of futures [K, T, J, 3] that went from
    `before` to `after`; each ghost pose moves by its future's root change at its frame."""
    shift = np.asarray(after, np.float64)[:, :, 0] - np.asarray(before, np.float64)[:, :, 0]   # [K, T, 3]
    frames = shift.shape[1]
    for i, marks in enumerate(ghosts["frames"]):
        if any(not 0 <= m < frames for m in marks):
            raise ValueError(f"future {i} has a ghost outside its {frames} frames: {marks}")
        at = shift[i, np.asarray(marks, dtype=np.int64)][:, None]                          # [n, 1, 3]
        ghosts["poses"][i] = (np.asarray(ghosts["poses"][i], np.float64) + at).astype(np.float32)
