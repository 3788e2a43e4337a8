"""Forward kinematics: local joint rotations and a root position to joint positions."""
from __future__ import annotations

import numpy as np
from scipy.spatial.transform import Rotation

from ..data.skeleton import Skeleton


def forward_kinematics(root_pos: np.ndarray, local: np.ndarray, skeleton: Skeleton) -> np.ndarray:
    """root_pos [F, 3] metres, local quaternions [F, J, 4] (x, y, z, w; the root's is its world
    rotation) -> positions [F, J, 3]."""
    frames = root_pos.shape[0]
    if local.shape != (frames, skeleton.num_joints, 4):
        raise ValueError(f"expected quaternions of shape {(frames, skeleton.num_joints, 4)}, got {local.shape}")
    positions = np.zeros((frames, skeleton.num_joints, 3))
    world: list[Rotation] = []
    for j, parent in enumerate(skeleton.parents):
        if parent < 0:
            positions[:, j] = root_pos
            world.append(Rotation.from_quat(local[:, j]))
        else:
            # Parents precede children in the joint order, so world[parent] exists.
            positions[:, j] = positions[:, parent] + world[parent].apply(
                np.tile(skeleton.offsets[j], (frames, 1)))
            world.append(world[parent] * Rotation.from_quat(local[:, j]))
    return positions
