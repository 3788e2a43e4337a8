"""Into and out of the canonical frame: each graph call sees a history facing +z at its last frame,
with root-relative poses and the root channel (export/ops/facing.py), and its futures go back to the
world where the history stands."""
from __future__ import annotations

import numpy as np

from ..data.skeleton import SKELETON
from ..ops.facing import Placement, canonicalise, place


def to_canonical(history: np.ndarray) -> tuple[np.ndarray, Placement]:
    """history [N, J, 3] (world) -> (canonical float32 [N, J, 3], its placement)."""
    canon, placement = canonicalise(history, len(history) - 1, SKELETON)
    return canon.astype(np.float32), placement


def from_canonical(frames: np.ndarray, placement: Placement) -> np.ndarray:
    """Back to the caller's world frame, as float32 like the graphs' outputs (and the browser's arrays)."""
    return place(np.asarray(frames, dtype=np.float64), placement).astype(np.float32)
