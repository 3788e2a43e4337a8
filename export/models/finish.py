"""The decoders' last layers: the seam with the history (export/ops/seam.py) and bodies that keep
their shape (export/models/keep_bones.py), in that order, on the canonical tensors."""
from __future__ import annotations

import torch
from torch import nn

from ..ops.seam import SEAM_FRAMES, seam_weights
from .keep_bones import KeepBones


class Seam(nn.Module):
    """export/ops/seam.py's continue_history in torch: frames [B, T, J, 3], last_two [B, 2, J, 3]."""

    def __init__(self, frames: int, seam: int = SEAM_FRAMES):
        super().__init__()
        self.n = min(frames, seam)                  # frames from `seam` on are the prediction's own
        self.register_buffer("w", torch.from_numpy(seam_weights(self.n, seam)).float()[:, None, None])
        self.register_buffer("steps", torch.arange(1, self.n + 1, dtype=torch.float32)[:, None, None])

    def forward(self, frames: torch.Tensor, last_two: torch.Tensor) -> torch.Tensor:
        x1, x0 = last_two[:, 1:2], last_two[:, 0:1]
        c = x1 + self.steps * (x1 - x0)
        head = c + self.w * (frames[:, :self.n] - c)
        return torch.cat([head, frames[:, self.n:]], 1)


class Finish(nn.Module):
    """Seam, then KeepBones; either may be off (the ablation without shape terms turns both off)."""

    def __init__(self, frames: int, seam: bool = True, keep_bones: bool = True):
        super().__init__()
        self.seam = Seam(frames) if seam else None
        self.keep_bones = KeepBones() if keep_bones else None

    def forward(self, frames: torch.Tensor, last_two: torch.Tensor) -> torch.Tensor:
        if self.seam is not None:
            frames = self.seam(frames, last_two)
        if self.keep_bones is not None:
            frames = self.keep_bones(frames)
        return frames
