"""Zero-velocity baseline: the future is the last observed pose, held."""
from __future__ import annotations

import torch
from torch import nn


class ZeroVelocity(nn.Module):
    def __init__(self, future_frames: int):
        super().__init__()
        self.future_frames = future_frames

    def forward(self, history: torch.Tensor) -> torch.Tensor:
        """history [B, N, J, 3] -> future [B, T, J, 3]."""
        return history[:, -1:].expand(-1, self.future_frames, -1, -1)
