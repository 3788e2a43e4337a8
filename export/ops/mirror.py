"""Left/right mirroring across the body's sagittal plane (the URDF's z = 0 plane).

Mirroring is a valid augmentation: the skeleton is symmetric, so a mirrored motion is one
the same skeleton can perform.
"""
from __future__ import annotations

import numpy as np

from ..data.skeleton import Skeleton


def mirror_positions(positions: np.ndarray, skeleton: Skeleton) -> np.ndarray:
    """[..., J, 3] positions: negate z and swap left and right joints."""
    out = positions[..., skeleton.mirror_map, :].copy()
    out[..., 2] *= -1
    return out


def mirror_rotations(root_pos: np.ndarray, local: np.ndarray, skeleton: Skeleton) -> tuple[np.ndarray, np.ndarray]:
    """The same mirror before forward kinematics: each rotation R becomes M R M, M = diag(1, 1, -1),
    which for an x, y, z, w quaternion negates x and y."""
    pos = root_pos.copy()
    pos[..., 2] *= -1
    q = local[..., skeleton.mirror_map, :].copy()
    q[..., 0] *= -1
    q[..., 1] *= -1
    return pos, q
