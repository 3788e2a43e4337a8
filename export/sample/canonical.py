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


# Body scale (issue 30): a history at another body size is brought to the model's size before predicting
# and its futures are scaled back, about the root's ground point at the last history frame, so the floor
# and the root stay where they are and the first predicted frame continues the last one. The predictor
# (predictor.py) does it once per prediction; twin: web/src/predictor/canonical.ts (contract/vectors/bones.json).
SCALE_TOLERANCE = 0.03           # within 3% of the model's bone lengths a body is used as it is
SCALE_LIMITS = (0.5, 2.0)        # outside: refused, the body is not a person at the model's scale


def body_scale(world: np.ndarray, skeleton=SKELETON) -> float:
    """World positions [F, J, 3] -> the body's size against the model's skeleton: the sum of its mean
    bone lengths over the sum of the skeleton's (1 = the model's size)."""
    from ..ops.bones import bone_lengths
    return float(bone_lengths(np.asarray(world, dtype=np.float64), skeleton).mean(0).sum() / skeleton.bone_lengths().sum())


def scale_anchor(world: np.ndarray) -> np.ndarray:
    """The point scaling keeps: the root's ground point at the last frame."""
    return np.array([world[-1, 0, 0], 0.0, world[-1, 0, 2]], dtype=np.float64)


def rescale(world: np.ndarray, factor: float, anchor: np.ndarray) -> np.ndarray:
    """[..., J, 3] positions scaled by `factor` about `anchor` (float64)."""
    return anchor + (np.asarray(world, dtype=np.float64) - anchor) * factor
