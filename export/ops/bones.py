"""Bone lengths of a motion, and projecting a motion onto given lengths along the kinematic tree.

The projection walks from the root: each joint = its (already placed) parent + the bone's length x
the unit direction from the parent to the joint in the input. Directions are kept, lengths are set.
It acts on world positions (or root-relative poses), never on a motion that carries the root channel
in its root joint (export/ops/facing.py): the root's own position is kept as it is. The models' last
layer does the same in torch (export/models/keep_bones.py); the TypeScript twin is
web/src/motion/bones.ts, tied to this one by contract/vectors/bones.json.
"""
from __future__ import annotations

import numpy as np

from ..data.skeleton import SKELETON, Skeleton


def bone_lengths(motion: np.ndarray, skeleton: Skeleton = SKELETON) -> np.ndarray:
    """[..., J, 3] -> [..., bones] in the order of skeleton.bones."""
    m = np.asarray(motion, dtype=np.float64)
    parents = [p for p, _ in skeleton.bones]
    children = [c for _, c in skeleton.bones]
    return np.linalg.norm(m[..., children, :] - m[..., parents, :], axis=-1)


def project_lengths(motion: np.ndarray, lengths: np.ndarray, skeleton: Skeleton = SKELETON) -> np.ndarray:
    """[..., J, 3] world positions -> the same with every bone given `lengths` [bones] (the order of
    skeleton.bones), directions kept. A zero-length input bone keeps its parent's position."""
    m = np.asarray(motion, dtype=np.float64)
    out = m.copy()
    lengths = np.asarray(lengths, dtype=np.float64)
    for b, (parent, child) in enumerate(skeleton.bones):      # parents precede children
        d = m[..., child, :] - m[..., parent, :]
        norm = np.linalg.norm(d, axis=-1, keepdims=True)
        unit = np.divide(d, norm, out=np.zeros_like(d), where=norm > 1e-12)
        out[..., child, :] = out[..., parent, :] + lengths[b] * unit
    return out


def keep_bones(motion: np.ndarray, skeleton: Skeleton = SKELETON) -> np.ndarray:
    """A canonical motion (root-relative poses, the root channel in the root joint's x and z,
    export/ops/facing.py) with the skeleton's bone lengths: the numpy form of the models' last layer
    (export/models/keep_bones.py), for futures made outside a graph (Keyposes' interpolation)."""
    m = np.asarray(motion, dtype=np.float64)
    pose = m.copy()
    pose[..., 0, 0] = 0.0
    pose[..., 0, 2] = 0.0
    out = project_lengths(pose, skeleton.bone_lengths(), skeleton)
    out[..., 0, 0] = m[..., 0, 0]
    out[..., 0, 2] = m[..., 0, 2]
    return out
