"""WAT's smoothness prior (Eq. 4): how far a transition is from its low-frequency DCT approximation.

Z = [x_{N-L+1}, ..., x_N, y_1, ..., y_L] (the last L history poses and the first L predicted
ones, each flattened to K = J*3 coordinates), Z~ = Z D D^T with D the first M orthonormal
DCT-II bases over 2L frames, and L_smooth = 1/(2L) * sum_i ||z_i - z~_i||^2 (square metres).
Twin: web/src/sampling/dct-smoothness.ts.
"""
from __future__ import annotations

from functools import lru_cache

import numpy as np
import torch

from .dct import dct_basis

L_FRAMES = 10   # supplement section 11
M_BASES = 5


@lru_cache(maxsize=None)
def _projector(frames: int, bases: int) -> np.ndarray:
    d = dct_basis(frames, bases)
    return d @ d.T


def smoothness(history_tail: np.ndarray, future_head: np.ndarray, bases: int = M_BASES) -> float:
    """history_tail [L, J, 3] and future_head [L, J, 3] (metres) -> Eq. 4 in square metres."""
    if history_tail.shape != future_head.shape:
        raise ValueError(f"history tail {history_tail.shape} and future head {future_head.shape} differ")
    z = np.concatenate([history_tail, future_head]).reshape(2 * len(history_tail), -1).astype(np.float64)
    residual = z - _projector(len(z), bases) @ z
    return float((residual ** 2).sum(axis=1).mean())


def smoothness_loss(history_tail: torch.Tensor, future_head: torch.Tensor, bases: int = M_BASES) -> torch.Tensor:
    """Batched, differentiable Eq. 4: [B, L, J, 3] and [B, L, J, 3] -> [B]."""
    z = torch.cat([history_tail, future_head], dim=1).flatten(2)
    p = torch.as_tensor(_projector(z.shape[1], bases), dtype=z.dtype, device=z.device)
    residual = z - torch.einsum("ts,bsk->btk", p, z)
    return residual.pow(2).sum(-1).mean(-1)
