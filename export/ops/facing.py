"""Canonical facing of a window, decided at its last history frame, and the root channel beside it.

Yaw is not removed frame by frame (that would erase spins and turns). Instead a whole window is
rotated about the vertical axis so that, at one chosen frame, the body faces +z, and moved so that
the root stands above the origin there.

Poses stay root-relative, as in both papers: every joint is measured from the point on the ground
below the root (height kept), so Eq. 4, Eq. 8, keypose extraction, k-means and the primary metrics
see the same poses wherever the body stands. The horizontal root trajectory travels in a separate
*root channel*: the root's (x, z) relative to its position at the chosen frame, in the same turned
frame. Heading needs no channel of its own: poses keep their yaw within the window.

The models' tensors [frames, J, 3] carry both at once: joints 1.. hold the root-relative pose, and
the root joint, whose x and z are always 0 in a root-relative pose, holds the root channel there.
`root_relative` and `root_channel` take them apart. Rotation about +y and mirroring act on both
parts alike, so turning or mirroring a canonical window needs no special case.
The TypeScript twin is web/src/predictor/canonical.ts; contract/vectors/facing.json ties them.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..data.skeleton import Skeleton

# Flat indices of the root channel (the root joint's x and z) in a frame flattened to [J * 3].
ROOT_CHANNEL = (0, 2)


@dataclass(frozen=True)
class Placement:
    """Where a canonical window sits in the world: the turn undone and the root's ground point."""
    angle: float
    x: float
    z: float


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


def split_root(world: np.ndarray, origin: tuple[float, float] = (0.0, 0.0)) -> np.ndarray:
    """World positions [..., F, J, 3] -> root-relative poses with the root channel (the root's x, z
    minus `origin`) in the root joint's x and z."""
    out = np.array(world, dtype=np.float64)
    ground = out[..., :1, :].copy()
    ground[..., 1] = 0.0
    out[..., 1:, :] -= ground
    out[..., 0, 0] -= origin[0]
    out[..., 0, 2] -= origin[1]
    return out


def join_root(motion: np.ndarray, origin: tuple[float, float] = (0.0, 0.0)) -> np.ndarray:
    """The inverse of split_root: root-relative poses + root channel -> world positions."""
    out = np.array(motion, dtype=np.float64)
    out[..., 0, 0] += origin[0]
    out[..., 0, 2] += origin[1]
    ground = out[..., :1, :].copy()
    ground[..., 1] = 0.0
    out[..., 1:, :] += ground
    return out


def root_relative(motion):
    """The poses of a motion that carries the root channel (split_root or canonicalise output), without
    it: the root above the origin. numpy arrays or torch tensors (differentiable). For world
    positions: root_relative(split_root(world))."""
    out = motion.clone() if hasattr(motion, "clone") else np.array(motion, dtype=np.float64)
    out[..., 0, 0] = 0.0
    out[..., 0, 2] = 0.0
    return out


def root_channel(motion: np.ndarray) -> np.ndarray:
    """[..., F, J, 3] canonical motion -> [..., F, 2]: the root's (x, z) relative to the canonical frame."""
    return np.asarray(motion, dtype=np.float64)[..., 0, [0, 2]]


def canonicalise(window: np.ndarray, at_frame: int, skeleton: Skeleton) -> tuple[np.ndarray, Placement]:
    """A world window [F, J, 3] as the models see it: root-relative poses and the root channel, turned
    so the pose at `at_frame` faces +z with the root above the origin there; and its placement."""
    window = np.asarray(window, dtype=np.float64)
    angle = facing_angle(window[at_frame], skeleton)
    x, z = float(window[at_frame, 0, 0]), float(window[at_frame, 0, 2])
    return rotate_about_y(split_root(window, (x, z)), -angle), Placement(angle, x, z)


def place(motion: np.ndarray, placement: Placement) -> np.ndarray:
    """A canonical motion back in the world: turned back and moved to the placement's root point."""
    return join_root(rotate_about_y(np.asarray(motion, dtype=np.float64), placement.angle),
                     (placement.x, placement.z))
