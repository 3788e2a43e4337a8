"""The refinement network (Keyposes paper, appendix 6.4, Fig. 7): a small GCN in the style of Mao et
al. over the 3J joint trajectories of an interpolated future, one node per trajectory.

The paper's network (5 blocks, 512 channels, 125 frames as features) is far larger than a web page
can carry; this one works on the trajectories' lowest DCT coefficients and adds a low-frequency
correction to its input, so the detail of the interpolation passes through unchanged.
"""
from __future__ import annotations

import numpy as np
import torch
from torch import nn

from ..ops.dct import dct_basis
from .keep_bones import KeepBones


class GraphConv(nn.Module):
    """y = A x W + b with a learnt node adjacency A [N, N] (Mao et al.)."""

    def __init__(self, nodes: int, fin: int, fout: int):
        super().__init__()
        self.adjacency = nn.Parameter(torch.eye(nodes) + 0.01 * torch.randn(nodes, nodes))
        self.weight = nn.Parameter(torch.randn(fin, fout) / np.sqrt(fin))
        self.bias = nn.Parameter(torch.zeros(fout))

    def forward(self, x):
        return self.adjacency @ (x @ self.weight) + self.bias


class RefineGCN(nn.Module):
    def __init__(self, joints: int, frames: int, bases: int, hidden: int, blocks: int, ramp_frames: int,
                 keep_bones: bool = True):
        """`frames` includes the present pose at index 0; the output is the frames after it."""
        super().__init__()
        # The last layer (models/keep_bones.py): refined bones keep the skeleton's lengths. (The seam with
        # the history is the predictor's, ops/seam.py: the interpolation it refines is made there too.)
        self.keep_bones = KeepBones() if keep_bones else None
        nodes = 3 * joints
        self.register_buffer("dct", torch.from_numpy(dct_basis(frames, bases)).float())   # [frames, bases]
        # The correction grows from 0 at the present over `ramp_frames`, so the refined future still
        # starts exactly at the present pose (section 3.2.2: no jump).
        ramp = np.minimum(np.arange(frames) / ramp_frames, 1.0)
        self.register_buffer("ramp", torch.from_numpy(ramp).float())
        self.inp = GraphConv(nodes, bases, hidden)
        self.blocks = nn.ModuleList(nn.ModuleList([GraphConv(nodes, hidden, hidden), GraphConv(nodes, hidden, hidden)])
                                    for _ in range(blocks))
        self.out = GraphConv(nodes, hidden, bases)
        nn.init.zeros_(self.out.weight)   # starts as the identity: refinement can only learn to help

    def forward(self, sequence: torch.Tensor) -> torch.Tensor:
        """[B, frames, J, 3] (present + interpolated future) -> refined future [B, frames - 1, J, 3]."""
        b, f, j, _ = sequence.shape
        x = sequence.reshape(b, f, j * 3).transpose(1, 2)            # [B, 3J, frames]
        h = torch.tanh(self.inp(x @ self.dct))
        for g1, g2 in self.blocks:
            h = h + torch.tanh(g2(torch.tanh(g1(h))))
        correction = self.out(h) @ self.dct.T                         # [B, 3J, frames]
        y = (x + correction * self.ramp).transpose(1, 2).reshape(b, f, j, 3)[:, 1:]
        return y if self.keep_bones is None else self.keep_bones(y)
