"""The skate term: a loss beside a paper's reconstruction that keeps a predicted foot still while it is on
the floor (a labelled variant of WAT's Eq. 6 and LCP-VAE's Eq. 9; weight 0 is the paper's loss).

The evaluation's foot skating (export/eval/realism/skating.py) is the horizontal speed of a foot within
3 cm of the floor; the captures give 0.07-0.12 m/s, the decoders 0.3-1.1. The term asks each predicted
foot for what a planted foot does, judged by the prediction's own foot height (not the truth's, whose
steps fall at other times than a sample's):

    term = mean over frames and feet of w(y_hat) * |xz_hat_t - xz_hat_{t-1}|^2 * fps^2,
    w(y) = sigmoid((BAND - y) / SOFTNESS)

with xz the foot's place on the floor in the canonical frame (the root channel plus the joint's
root-relative x and z) and the history's last frame prepended. TypeScript twin: none (training only).
"""
from __future__ import annotations

import torch

from ..data.skeleton import SKELETON

FEET = ("left_ankle", "left_toe", "right_ankle", "right_toe")
BAND = 0.03            # metres: the evaluation's contact band
SOFTNESS = 0.01        # metres: how soft the band's edge is, so the weight has a gradient
FPS = 30.0
_FEET = [SKELETON.index(n) for n in FEET]


def floor_places(canonical: torch.Tensor) -> torch.Tensor:
    """Where each foot is on the floor: the root channel plus its root-relative x and z -> [B, T, 4, 2]."""
    feet = canonical[:, :, _FEET][..., [0, 2]]
    return feet + canonical[:, :, :1, [0, 2]]


def skate_term(history: torch.Tensor, pred: torch.Tensor, mask: torch.Tensor | None = None) -> torch.Tensor:
    """The term above for canonical history [B, N, J, 3] and prediction [B, T, J, 3] over the frames in
    `mask` ([B, T] bool; all when None) -> a scalar (m/s)^2."""
    seq = torch.cat([history[:, -1:], pred], 1)
    places = floor_places(seq)
    speed2 = (places[:, 1:] - places[:, :-1]).pow(2).sum(-1) * FPS ** 2          # [B, T, 4]
    weight = torch.sigmoid((BAND - seq[:, 1:, _FEET, 1]) / SOFTNESS)              # [B, T, 4]
    term = weight * speed2
    if mask is None:
        return term.mean()
    m = mask[:, :, None].to(term.dtype)
    return (term * m).sum() / (m.sum() * term.shape[-1]).clamp(min=1.0)
