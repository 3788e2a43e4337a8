"""Handedness: is a history's body one a person can have, or its mirror image with the labels kept?

A history reflected through a plane without swapping its left and right joint labels (issue 30) is a
body that cannot exist: the hips say the body faces one way and the feet point the other. The models
then walk it backwards. The sign of a triple product tells them apart, and no rotation changes it:
forward from the hips (spine x the hips' left-to-right axis) against forward from the feet (ankle to
toe). Per frame that is the cosine between the two forwards; the score is its mean over the frames
(about +1 for a real body, about -1 for a reflected one), so a few odd frames do not decide.
The fix is to swap the left and right labels (`swap_left_right`), which turns a reflected body into a
real one. Pure: the predictors' request checks and the import panel call it; export.pipeline does not.
TypeScript twin: web/src/motion/handedness.ts; contract/vectors/envelope.json ties them.
"""
from __future__ import annotations

import numpy as np

from ..data.skeleton import SKELETON, Skeleton

THRESHOLD = 0.0   # below: reflected (every 30-frame window of the clips scores >= +0.22, their mirrors <= -0.22)
MESSAGE = ("Left and right look swapped: the hips face one way and the feet point the other, as in a "
           "mirror image. Swap the left and right joints (or fix the joint map) before predicting.")


def _unit(v: np.ndarray) -> np.ndarray:
    n = np.linalg.norm(v, axis=-1, keepdims=True)
    return np.where(n > 1e-9, v / np.maximum(n, 1e-9), 0.0)


def handedness(positions: np.ndarray, skeleton: Skeleton = SKELETON) -> tuple[bool, float]:
    """World joint positions [F, J, 3] -> (reflected, score in [-1, 1])."""
    p = np.asarray(positions, dtype=np.float64)
    i = skeleton.index
    across = p[:, i("right_hip")] - p[:, i("left_hip")]
    spine = p[:, i("neck")] - p[:, i("root")]
    hips_forward = _unit(np.cross(spine, across))
    feet = (p[:, i("right_toe")] - p[:, i("right_ankle")]) + (p[:, i("left_toe")] - p[:, i("left_ankle")])
    # only the part of the feet's direction across the spine: a foot pointing down says nothing
    up = _unit(spine)
    feet = _unit(feet - (feet * up).sum(-1, keepdims=True) * up)
    score = float((hips_forward * feet).sum(-1).mean()) if len(p) else 0.0
    return score < THRESHOLD, score


def swap_left_right(positions: np.ndarray, skeleton: Skeleton = SKELETON) -> np.ndarray:
    """[..., J, 3] positions with every left joint's position given to its right twin and back."""
    return np.asarray(positions)[..., skeleton.mirror_map, :].copy()
