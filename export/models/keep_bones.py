"""The models' last layer: bodies that keep their shape.

Issue 17's choice between a bone-length loss and a representation that keeps lengths: the latter.
A decoder's positions are read as bone *directions*; every bone then takes the skeleton's length,
walking the kinematic tree from the root, so no predicted bone can stretch or shrink, whatever the
weights (a loss would only make stretching unlikely on motion like the training data's). Poses stay
root-relative (export/ops/facing.py): the root channel in the root joint's x and z passes through
untouched, and the root's height is the decoder's. All training data is retargeted to the project
skeleton (export/data/retarget.py), so its bone lengths are the lengths every history has.

Written with two constant matrices so that it exports as a handful of ONNX nodes (MatMul, Mul,
ReduceSum, Sqrt, Div) on [batch, frames, J, 3]: bones = D @ pose (child minus parent), and
positions = A @ bones (the sum of the bones on the path from the root). The same walk in numpy,
for histories and the browser's guard, is export/ops/bones.py.
"""
from __future__ import annotations

import numpy as np
import torch
from torch import nn

from ..data.skeleton import SKELETON, Skeleton


def tree_matrices(skeleton: Skeleton = SKELETON) -> tuple[np.ndarray, np.ndarray]:
    """D [bones, J]: bone b = joint child(b) - joint parent(b); A [J, bones]: joint j = the sum of the
    bones from the root to j (the root itself is bone-free)."""
    bones = skeleton.bones
    d = np.zeros((len(bones), skeleton.num_joints))
    child_bone = {}
    for b, (parent, child) in enumerate(bones):
        d[b, child], d[b, parent] = 1.0, -1.0
        child_bone[child] = b
    a = np.zeros((skeleton.num_joints, len(bones)))
    for j in range(skeleton.num_joints):
        k = j
        while skeleton.parents[k] >= 0:
            a[j, child_bone[k]] = 1.0
            k = skeleton.parents[k]
    return d, a


class KeepBones(nn.Module):
    def __init__(self, skeleton: Skeleton = SKELETON):
        super().__init__()
        d, a = tree_matrices(skeleton)
        self.register_buffer("d", torch.from_numpy(d).float())
        self.register_buffer("a", torch.from_numpy(a).float())
        self.register_buffer("lengths", torch.from_numpy(skeleton.bone_lengths()).float()[:, None])
        channel = np.zeros((skeleton.num_joints, 3))
        channel[0, [0, 2]] = 1.0                     # the root channel's two slots
        self.register_buffer("channel", torch.from_numpy(channel).float())

    def forward(self, motion: torch.Tensor) -> torch.Tensor:
        """[..., J, 3] root-relative poses with the root channel -> the same with the skeleton's bone lengths."""
        pose = motion * (1.0 - self.channel)                       # the root above the origin
        bones = torch.matmul(self.d, pose)
        unit = bones / torch.sqrt((bones * bones).sum(-1, keepdim=True) + 1e-12)
        return torch.matmul(self.a, unit * self.lengths) + pose[..., :1, :] + motion * self.channel
