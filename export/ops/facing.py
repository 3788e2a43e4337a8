"""Canonical facing of a window, decided at its last history frame.

Yaw is not removed frame by frame (that would erase spins and turns). Instead a whole
window is rotated about the vertical axis so that, at one chosen frame, the body faces +z.
The TypeScript twin is web/src/motion/facing.ts; contract/vectors/facing.json ties them.
"""
from __future__ import annotations

import numpy as np

from ..data.skeleton import Skeleton


def facing_angle(pose: np.ndarray, skeleton: Skeleton) -> float:
    """Angle about +y from +z to the body's forward direction, from the hip line of one pose [J, 3]."""
    across = pose[skeleton.index("right_hip")] - pose[skeleton.index("left_hip")]
    # forward = up x across, restricted to the ground plane: (across_z, 0, -across_x).
    fx, fz = across[2], -across[0]
    if fx * fx + fz * fz < 1e-12:
        return 0.0  # hips vertical (e.g. lying on the side): no defined facing, keep as is
    return float(np.arctan2(fx, fz))


def rotate_about_y(positions: np.ndarray, angle: float) -> np.ndarray:
    """Rotate [..., 3] points about +y by `angle` radians (right-handed)."""
    c, s = np.cos(angle), np.sin(angle)
    out = positions.copy()
    x, z = positions[..., 0], positions[..., 2]
    out[..., 0] = c * x + s * z
    out[..., 2] = -s * x + c * z
    return out


def canonicalise(window: np.ndarray, at_frame: int, skeleton: Skeleton) -> tuple[np.ndarray, float]:
    """Rotate a window [F, J, 3] so the pose at `at_frame` faces +z; returns it and the angle undone."""
    angle = facing_angle(window[at_frame], skeleton)
    return rotate_about_y(window, -angle), angle
