"""What the networks read: the motion turned into normalised inputs, shared by WAT and LCP-VAE.

Two choices, each a config switch whose first value is the input as it was (the ablation):

- `root_input` ("position" | "step"). The root channel (ops/facing.py) sits in the root joint's x and z:
  the root's ground position relative to the present. Over a history it spans centimetres, but over a
  future it grows to metres (a 3 s walk travels 4.5 m, z-scores of 30-40 under the history's statistics).
  Fed as it is to the networks that read futures (a posterior's encoder, an autoregressive decoder's
  previous frame), it saturated them where a figure travels. With "step" they read root-relative poses and
  the root's step from the frame before in place of its position, so a gait's input does not depend on
  how far it has walked. Measured on WAT (RNN), 9000-step runs (the table in methods/wat.py): the KL
  between the posterior and the prior on held-out 2 s windows rose from 26 to 72 nats (the encoder now
  tells futures apart), joint speed in the 2nd second on held-out people 0.40 -> 0.47 of the truth's,
  follow rho 0.25 -> 0.39.
- `history_steps` (false | true). Each history frame's step from the frame before (0 for the first),
  beside the pose, in units of the steps' std: the speed of a motion lives in its steps, a few hundredths
  of a pose's std. Read from poses alone, a predicted first second ran at 0.2-0.4 m/s whatever the
  history's speed (0.01-1.4 m/s on held-out windows). On WAT (RNN): best-of-10 ADE / zero-velocity's
  0.613 -> 0.588 on the training people's windows, 0.907 -> 0.884 on held-out ones.

Training and export both call these, so the exported graphs read what training read.
"""
from __future__ import annotations

import torch

from ..ops.facing import ROOT_CHANNEL

ROOT_INPUTS = ("position", "step")


def check_root_input(root_input: str) -> str:
    if root_input not in ROOT_INPUTS:
        raise ValueError(f"root_input must be one of {ROOT_INPUTS}, got {root_input!r}")
    return root_input


def frame_steps(flat: torch.Tensor, first: torch.Tensor | None = None) -> torch.Tensor:
    """[B, F, K] -> each frame minus the frame before; the first frame minus `first` [B, K] (0 without)."""
    before = torch.zeros_like(flat[:, :1]) if first is None else first[:, None]
    return flat - torch.cat([before, flat[:, :-1]], 1)


def history_features(history: torch.Tensor, mean: torch.Tensor, std: torch.Tensor, step_std: torch.Tensor,
                     steps: bool) -> torch.Tensor:
    """history [B, N, J, 3] -> normalised poses [B, N, K]; with `steps` also each frame's step from the
    frame before (0 for the first) over step_std: [B, N, 2K]."""
    flat = history.flatten(2)
    x = (flat - mean) / std
    if not steps:
        return x
    return torch.cat([x, frame_steps(flat, flat[:, 0]) / step_std], -1)


def future_features(future: torch.Tensor, mean: torch.Tensor, std: torch.Tensor, step_std: torch.Tensor,
                    root_input: str) -> torch.Tensor:
    """future [B, T, J, 3] (canonical: the root channel is 0 at the present) -> normalised frames [B, T, K];
    with root_input "step" the root's x and z hold its step from the frame before over step_std."""
    flat = future.flatten(2)
    x = (flat - mean) / std
    if root_input == "position":
        return x
    idx = list(ROOT_CHANNEL)
    root = flat[..., idx]
    x = x.clone()
    x[..., idx] = frame_steps(root) / step_std[..., idx]
    return x


def pose_input_mask(coordinates: int, root_input: str) -> torch.Tensor:
    """[K] ones, zeros at the root channel's x and z when a decoder reads root-relative poses ("step")."""
    mask = torch.ones(coordinates)
    if root_input == "step":
        mask[list(ROOT_CHANNEL)] = 0.0
    return mask
