"""Into and out of the canonical frame: each graph call sees a history facing +z at its last frame."""
from __future__ import annotations

import numpy as np

from ..data.skeleton import SKELETON
from ..ops.facing import canonicalise, rotate_about_y


def to_canonical(history: np.ndarray) -> tuple[np.ndarray, float]:
    """history [N, J, 3] -> (canonical float32 [N, J, 3], angle to undo)."""
    canon, angle = canonicalise(history, len(history) - 1, SKELETON)
    return canon.astype(np.float32), angle


def from_canonical(frames: np.ndarray, angle: float) -> np.ndarray:
    """Back to the caller's frame, as float32 like the graphs' outputs (and the browser's arrays)."""
    return rotate_about_y(np.asarray(frames, dtype=np.float64), angle).astype(np.float32)
