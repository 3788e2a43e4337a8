"""Deterministic regression baseline: a GRU over the history, a head for T frames of offsets.

The head predicts the first few DCT coefficients of the offsets from the last pose rather than
every frame: the future stays smooth and the head has 3x fewer weights, which matters for a
model the browser downloads.
"""
from __future__ import annotations

import torch
from torch import nn

from ..ops.dct import dct_basis
from . import inputs
from .finish import Finish


class RegressionGRU(nn.Module):
    def __init__(self, joints: int, future_frames: int, hidden: int, dct_bases: int,
                 pose_mean: torch.Tensor, pose_std: torch.Tensor, offset_std: torch.Tensor, keep_bones: bool = True,
                 seam: bool = True, step_std: torch.Tensor | None = None, history_steps: bool = False):
        super().__init__()
        self.history_steps = history_steps     # the history's steps beside its poses (models/inputs.py)
        # The last layers (models/finish.py): the seam with the history, bones of fixed length.
        self.finish = Finish(future_frames, seam, keep_bones) if (seam or keep_bones) else None
        self.joints, self.future_frames, self.dct_bases = joints, future_frames, dct_bases
        # Normalisation lives inside the graph: the browser passes raw metres.
        self.register_buffer("pose_mean", pose_mean.reshape(1, 1, joints * 3).float())
        self.register_buffer("pose_std", pose_std.reshape(1, 1, joints * 3).float())
        self.register_buffer("offset_std", offset_std.reshape(1, 1, joints * 3).float())
        self.register_buffer("basis", torch.from_numpy(dct_basis(future_frames, dct_bases)).float())
        self.register_buffer("step_std", (pose_std if step_std is None else step_std).reshape(1, 1, joints * 3).float())
        self.encoder = nn.GRU(joints * 3 * (2 if history_steps else 1), hidden, batch_first=True)
        self.head = nn.Sequential(nn.Linear(hidden, hidden), nn.ReLU(), nn.Linear(hidden, dct_bases * joints * 3))

    def forward(self, history: torch.Tensor) -> torch.Tensor:
        """history [B, N, J, 3] metres -> future [B, T, J, 3] metres."""
        b, n = history.shape[:2]
        x = history.reshape(b, n, -1)
        _, h = self.encoder(inputs.history_features(history, self.pose_mean, self.pose_std, self.step_std,
                                                    self.history_steps))
        coeffs = self.head(h[-1]).reshape(b, self.dct_bases, -1)
        offsets = torch.matmul(self.basis, coeffs) * self.offset_std
        future = (x[:, -1:] + offsets).reshape(b, self.future_frames, self.joints, 3)
        return future if self.finish is None else self.finish(future, history[:, -2:])
