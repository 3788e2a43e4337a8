"""Jump height: the hip's (root joint's) vertical range, max - min of its height y (metres), over a motion or
a slice of its frames. A requested jump that never leaves the ground reads 3-10 cm (the bob of a walk);
captured jumps read 53-68 cm.

TypeScript twin: none.
"""
from __future__ import annotations

import numpy as np


def hip_vertical_range(motion: np.ndarray, start: int | None = None, stop: int | None = None) -> np.ndarray:
    """max - min of the root joint's y over frames [start, stop): [..., T, J, 3] -> [...] (float for one motion)."""
    y = np.asarray(motion, dtype=np.float64)[..., start:stop, 0, 1]
    if y.shape[-1] < 1:
        raise ValueError("the slice holds no frames")
    r = y.max(-1) - y.min(-1)
    return float(r) if np.ndim(r) == 0 else r
