"""WAT's Transformer CVAE (section 3.4, Fig. 3b): the second temporal encoder of the paper.

Same base (`WatCVAE`: normalisation, KL of Eq. 2) and the same two exported signatures as the RNN:
  prior graph   (history, action one-hot) -> prior mean, log-variance, history features
  decoder graph (z, history, action one-hot) -> T_max future frames
so the browser runs it with the WAT predictor unchanged.

- Prior p(z|X,a) and posterior q(z|X,Y,a), as in ACTOR [43]: a Transformer encoder over the frames
  with two extra tokens made from the action label prepended; their outputs give mu and log sigma^2.
- Decoder: the history padded with its last pose to N + T_max frames, one Transformer pass (not
  autoregressive, so no unrolled loop in the graph); z and the action enter every self-attention
  layer as extra keys and values (pseudo self-attention, Ziegler et al. 2019 [59]).
Attention is written as plain matrix products (no nn.MultiheadAttention) so the exported graph is
the same few MatMul/Softmax nodes in both runtimes. Poses are raw metres in and out.
"""
from __future__ import annotations

import math

import torch
from torch import nn

from . import inputs
from .wat import WatCVAE


def sinusoid(length: int, dim: int) -> torch.Tensor:
    """The fixed positional encoding of Vaswani et al. [51] -> [length, dim]."""
    pos = torch.arange(length, dtype=torch.float64)[:, None]
    freq = torch.exp(torch.arange(0, dim, 2, dtype=torch.float64) * (-math.log(10000.0) / dim))
    pe = torch.zeros(length, dim, dtype=torch.float64)
    pe[:, 0::2] = torch.sin(pos * freq)
    pe[:, 1::2] = torch.cos(pos * freq)[:, : dim // 2]
    return pe.float()


class Block(nn.Module):
    """One pre-norm Transformer layer. With `conditions` it is pseudo self-attention [59]: the
    condition vectors are projected to extra keys and values that every position may attend to;
    queries come from the sequence only, so the sequence length is unchanged."""

    def __init__(self, d_model: int, heads: int, feedforward: int, conditioned: bool = False):
        super().__init__()
        if d_model % heads:
            raise ValueError(f"d_model {d_model} is not divisible by {heads} heads")
        self.heads = heads
        self.norm1, self.norm2 = nn.LayerNorm(d_model), nn.LayerNorm(d_model)
        self.qkv = nn.Linear(d_model, 3 * d_model)
        self.out = nn.Linear(d_model, d_model)
        self.cond_kv = nn.Linear(d_model, 2 * d_model) if conditioned else None
        self.ff = nn.Sequential(nn.Linear(d_model, feedforward), nn.GELU(), nn.Linear(feedforward, d_model))

    def _heads(self, x: torch.Tensor) -> torch.Tensor:
        b, t, d = x.shape
        return x.reshape(b, t, self.heads, d // self.heads).transpose(1, 2)      # [B, H, T, d/H]

    def forward(self, x: torch.Tensor, conditions: torch.Tensor | None = None,
                key_bias: torch.Tensor | None = None) -> torch.Tensor:
        """x [B, T, d]; conditions [B, C, d] (pseudo self-attention); key_bias [B, T] added to the
        attention logits of each key (-inf masks padding; training only)."""
        b, t, d = x.shape
        h = self.norm1(x)
        q, k, v = self.qkv(h).chunk(3, -1)
        if self.cond_kv is not None and conditions is not None:
            ck, cv = self.cond_kv(conditions).chunk(2, -1)
            k, v = torch.cat([ck, k], 1), torch.cat([cv, v], 1)
        q, k, v = self._heads(q), self._heads(k), self._heads(v)
        logits = q @ k.transpose(-1, -2) * (1.0 / math.sqrt(d // self.heads))
        if key_bias is not None:
            logits = logits + key_bias[:, None, None, :]
        att = torch.softmax(logits, -1) @ v                                        # [B, H, T, d/H]
        x = x + self.out(att.transpose(1, 2).reshape(b, t, d))
        return x + self.ff(self.norm2(x))


class TokenEncoder(nn.Module):
    """ACTOR's encoder [43]: [mu token, sigma token, frame_1, ..., frame_T] -> (mu, log sigma^2, frame
    summary). The two tokens are a linear map of the action one-hot (one learned pair per action)."""

    def __init__(self, k: int, actions: int, latent: int, d_model: int, heads: int, feedforward: int,
                 layers: int, max_len: int):
        super().__init__()
        self.tokens = nn.Linear(actions, 2 * d_model, bias=False)
        self.embed = nn.Linear(k, d_model)
        self.register_buffer("pe", sinusoid(max_len + 2, d_model))
        self.blocks = nn.ModuleList(Block(d_model, heads, feedforward) for _ in range(layers))
        self.norm = nn.LayerNorm(d_model)
        self.mu = nn.Linear(d_model, latent)
        self.logvar = nn.Linear(d_model, latent)

    def forward(self, frames_n: torch.Tensor, action: torch.Tensor, key_bias: torch.Tensor | None = None):
        b, t, _ = frames_n.shape
        tok = self.tokens(action).reshape(b, 2, -1)
        x = torch.cat([tok, self.embed(frames_n)], 1) + self.pe[: t + 2]
        if key_bias is not None:
            key_bias = torch.cat([key_bias.new_zeros(b, 2), key_bias], 1)
        for block in self.blocks:
            x = block(x, key_bias=key_bias)
        x = self.norm(x)
        return self.mu(x[:, 0]), self.logvar(x[:, 1]), x[:, 2:]


class WatTransformer(WatCVAE):
    """Transformer prior / posterior / decoder (Fig. 3b) behind the RNN model's interface.

    `residual` (as in WatRNN): each future position outputs its step from the previous frame and frame
    t is x_N plus the steps so far, so holding a pose (Eq. 7's padding, Eq. 8's stop) is a zero
    output; otherwise each position outputs its offset from x_N.
    """

    def __init__(self, joints: int, actions: int, max_frames: int, history_frames: int = 10, latent: int = 16,
                 d_model: int = 48, heads: int = 4, feedforward: int = 96, prior_layers: int = 2,
                 posterior_layers: int = 2, decoder_layers: int = 3, residual: bool = True,
                 step_std: torch.Tensor | None = None, **stats):
        # The base's action token (a linear layer on the one-hot) is the decoder's action condition;
        # its prior / posterior MLPs are replaced by the token encoders below.
        super().__init__(joints, actions, max_frames, latent, d_model, d_model, d_model, d_model, **stats)
        k = joints * 3
        self.history_frames, self.residual = history_frames, residual
        self.register_buffer("step_std", (step_std if step_std is not None else torch.ones(k)).reshape(1, 1, k).float())
        width = self.history_input_size()          # a frame's inputs: its pose (and its step, history_steps)
        self.prior = TokenEncoder(width, actions, latent, d_model, heads, feedforward, prior_layers, history_frames)
        # The posterior reads X and every second frame of Y (its gist; halves the training cost).
        self.posterior = TokenEncoder(width, actions, latent, d_model, heads, feedforward, posterior_layers,
                                      history_frames + (max_frames + 1) // 2)
        self.z_embed = nn.Linear(latent, d_model)
        self.dec_embed = nn.Linear(width, d_model)
        self.register_buffer("dec_pe", sinusoid(history_frames + max_frames, d_model))
        self.dec_blocks = nn.ModuleList(Block(d_model, heads, feedforward, conditioned=True)
                                        for _ in range(decoder_layers))
        self.dec_norm = nn.LayerNorm(d_model)
        self.dec_out = nn.Linear(d_model, k)
        # Zero output at the start: the untrained decoder predicts the held pose x_N (zero-velocity)
        # instead of a random walk accumulated over T_max steps.
        nn.init.zeros_(self.dec_out.weight)
        nn.init.zeros_(self.dec_out.bias)

    # --- the RNN model's interface ------------------------------------------------------------
    def encode_history(self, history_n: torch.Tensor) -> torch.Tensor:
        raise NotImplementedError("the Transformer prior reads the history with its action tokens: use prior_params")

    def prior_params(self, history: torch.Tensor, action: torch.Tensor):
        """-> prior mean [B, D], prior log-variance [B, D], history features [B, d] (the prior
        encoder's outputs at the history frames, averaged)."""
        mu, logvar, frames = self.prior(self.history_input(history), action)
        mu, logvar = self.split(torch.cat([mu, logvar], -1))
        return mu, logvar, frames.mean(1)

    def posterior_params(self, history: torch.Tensor, action: torch.Tensor, future: torch.Tensor,
                         future_length: torch.Tensor):
        """q(z|X,Y,a) over X and the valid frames of Y (every second one) -> mu, log-variance."""
        y = self.future_input(future)
        if self.history_steps:    # the future's steps beside its frames, as the history has them
            steps = inputs.frame_steps(future.flatten(2), history[:, -1].flatten(1)) / self.step_std
            y = torch.cat([y, steps], -1)
        y = y[:, ::2]
        valid = torch.arange(y.shape[1])[None] < ((future_length.long() + 1) // 2).clamp(min=1)[:, None]
        bias = torch.zeros(valid.shape).masked_fill(~valid, float("-inf"))
        key_bias = torch.cat([bias.new_zeros(len(bias), history.shape[1]), bias], 1)
        mu, logvar, _ = self.posterior(torch.cat([self.history_input(history), y], 1), action, key_bias)
        return self.split(torch.cat([mu, logvar], -1))

    def decode(self, h_x, a, z, history):
        """The history padded with x_N to N + T_max frames, one Transformer pass with [z, action]
        as pseudo self-attention conditions -> raw future [B, T_max, J, 3]. h_x is not used: the
        decoder reads the history itself (Fig. 3b)."""
        b, n = history.shape[:2]
        x_last = history[:, -1].reshape(b, 1, -1)
        padded = torch.cat([history.reshape(b, n, -1), x_last.expand(b, self.max_frames, -1)], 1)
        frames = (padded - self.pose_mean) / self.pose_std
        if self.history_steps:     # the padding holds x_N: its steps are 0
            steps = self.history_input(history)[..., self.joints * 3:]
            frames = torch.cat([frames, torch.cat([steps, steps.new_zeros(b, self.max_frames, steps.shape[-1])], 1)], -1)
        x = self.dec_embed(frames) + self.dec_pe[: n + self.max_frames]
        cond = torch.stack([self.z_embed(z), a], 1)                                # [B, 2, d]
        for block in self.dec_blocks:
            x = block(x, cond)
        out = self.dec_out(self.dec_norm(x[:, n:]))
        if self.residual:
            frames = x_last + (out * self.step_std).cumsum(1)
        else:
            frames = x_last + out * self.offset_std
        return frames.reshape(b, self.max_frames, self.joints, 3)

    def decode_from(self, z, history, action):
        # No history features: keeps the prior encoder out of the decoder graph.
        return self.finish(self.decode(None, self.action_embed(action), z, history), history)

    def forward(self, history, action, future, future_length):
        """Training pass: z from the posterior (reparameterised) -> (prediction, posterior, prior) params."""
        prior_mu, prior_logvar, _ = self.prior_params(history, action)
        mu, logvar = self.posterior_params(history, action, future, future_length)
        z = mu + (0.5 * logvar).exp() * torch.randn_like(mu)
        return self.decode_from(z, history, action), mu, logvar, prior_mu, prior_logvar
