"""The autoregressive GRU decoder that WAT's RNN (Fig. 3a) and LCP-VAE's DecodeData share, described
by its weights so the exporter can write it as one fused ONNX GRU node per step.

    h_{t+1} = GRU([context, x_t], h_t)        x_{t+1} = base_t + W_out h_{t+1} + b_out

with base_t = x_t (residual) or x_0 (offsets from the seed), for t < steps, in raw metres. torch's
exporter writes each step of such a loop as about 20 small nodes; onnxruntime then took 1.1-2.7 s
to create the session of WAT's 90 steps (docs/PERFORMANCE.md). A graph is the torch `setup` (the
encoders: context, seed x_0, h_0) followed by this recurrence; its `forward` stays the reference
the exported file is checked against.
"""
from __future__ import annotations

from dataclasses import dataclass

import torch
from torch import nn


@dataclass
class GruRollout:
    w_input: torch.Tensor     # [3H, C + K] on [context, x_t]; gate rows in torch's order [r, z, n]
    b_input: torch.Tensor     # [3H]
    w_hidden: torch.Tensor    # [3H, H]
    b_hidden: torch.Tensor    # [3H]
    w_out: torch.Tensor       # [K, H]
    b_out: torch.Tensor       # [K]
    steps: int
    frame_shape: tuple[int, ...]   # one output frame, e.g. (J, 3); K is its product
    residual: bool = True

    @property
    def context_size(self) -> int:
        return self.w_input.shape[1] - self.w_out.shape[0]

    def run(self, seed: torch.Tensor, h0: torch.Tensor, context: torch.Tensor | None = None) -> torch.Tensor:
        """The recurrence in torch (for tests): seed [B, K], h0 [B, H] -> [B, steps, *frame_shape]."""
        hidden = h0.shape[-1]
        x, h, frames = seed, h0, []
        for _ in range(self.steps):
            inp = x if context is None else torch.cat([context, x], -1)
            gi = inp @ self.w_input.T + self.b_input
            gh = h @ self.w_hidden.T + self.b_hidden
            r = torch.sigmoid(gi[:, :hidden] + gh[:, :hidden])
            z = torch.sigmoid(gi[:, hidden:2 * hidden] + gh[:, hidden:2 * hidden])
            n = torch.tanh(gi[:, 2 * hidden:] + r * gh[:, 2 * hidden:])
            h = (1 - z) * n + z * h
            x = (x if self.residual else seed) + h @ self.w_out.T + self.b_out
            frames.append(x)
        return torch.stack(frames, 1).reshape(seed.shape[0], self.steps, *self.frame_shape)


class RolloutGraph(nn.Module):
    """An exported graph made of `setup` (exported by torch) and `rollout()` (written as ONNX)."""

    def setup(self, *inputs: torch.Tensor) -> tuple[torch.Tensor, ...]:
        """The graph's inputs -> (seed x_0 [B, K], h_0 [B, H][, context [B, C]][, anchor]): the anchor
        (what `finish` needs besides the frames, e.g. the history's last two frames) only when
        `finish()` gives a module."""
        raise NotImplementedError

    def rollout(self) -> GruRollout:
        raise NotImplementedError

    def finish(self) -> nn.Module | None:
        """A module (frames [B, steps, *frame_shape], anchor) -> the graph's output (models/finish.py),
        or None."""
        return None


class RolloutSetup(nn.Module):
    """`setup` as a module of its own, for the exporter."""

    def __init__(self, graph: RolloutGraph):
        super().__init__()
        self.parts = graph

    def forward(self, *inputs):
        return self.parts.setup(*inputs)
