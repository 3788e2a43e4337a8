"""WAT's CVAE (section 3.1, 3.4): posterior q(z|Y,X,a), learned prior p(z|X,a), decoder p(Y|z,X,a).

`WatCVAE` holds what every temporal encoder shares (normalisation, action embedding, prior and
posterior MLPs, the KL of Eq. 2) and the two exported signatures:
  prior graph   (history, action one-hot) -> prior mean, log-variance, history features
  decoder graph (z, history, action one-hot) -> T_max future frames
A variant implements `encode_history`, `encode_future` and `decode`; `WatRNN` does it with GRUs
(Fig. 3a). The Transformer variant (issue 6) subclasses the same base and keeps both graphs.
Poses are raw metres in and out; normalisation lives inside the graphs.
"""
from __future__ import annotations

import torch
from torch import nn

from .gru_rollout import GruRollout, RolloutGraph
from .finish import Finish
from . import inputs

# Log-variances are clamped so exp(logvar / 2) stays finite in float32 in both runtimes.
LOGVAR_MIN, LOGVAR_MAX = -12.0, 6.0



def mlp(sizes: list[int]) -> nn.Sequential:
    layers: list[nn.Module] = []
    for i, (a, b) in enumerate(zip(sizes[:-1], sizes[1:])):
        layers.append(nn.Linear(a, b))
        if i < len(sizes) - 2:
            layers.append(nn.ReLU())
    return nn.Sequential(*layers)


def kl_divergence(mu: torch.Tensor, logvar: torch.Tensor, prior_mu: torch.Tensor, prior_logvar: torch.Tensor) -> torch.Tensor:
    """Eq. 2: KL(N(mu, sigma^2) || N(mu_hat, sigma_hat^2)) summed over the D latent dimensions -> [B]."""
    return 0.5 * (prior_logvar - logvar + (logvar.exp() + (mu - prior_mu).pow(2)) / prior_logvar.exp() - 1).sum(-1)


class WatCVAE(nn.Module):
    def __init__(self, joints: int, actions: int, max_frames: int, latent: int, action_embed: int,
                 history_features: int, future_features: int, mlp_hidden: int,
                 pose_mean: torch.Tensor, pose_std: torch.Tensor, offset_std: torch.Tensor, keep_bones: bool = True,
                 seam: bool = True, root_input: str = "position", history_steps: bool = False):
        super().__init__()
        self.joints, self.actions, self.max_frames, self.latent = joints, actions, max_frames, latent
        # What the networks read (models/inputs.py): the root channel as steps, the history's steps.
        self.root_input = inputs.check_root_input(root_input)
        self.history_steps = history_steps
        # The decoder's last layers (models/finish.py): the seam with the history, bones of fixed length.
        self.finish_layer = Finish(max_frames, seam, keep_bones) if (seam or keep_bones) else None
        k = joints * 3
        self.register_buffer("pose_mean", pose_mean.reshape(1, 1, k).float())
        self.register_buffer("pose_std", pose_std.reshape(1, 1, k).float())
        self.register_buffer("offset_std", offset_std.reshape(1, 1, k).float())
        # The action token of Fig. 3: a fully connected layer on the one-hot label.
        self.action_embed = nn.Linear(actions, action_embed, bias=False)
        self.prior = mlp([history_features + action_embed, mlp_hidden, 2 * latent])
        self.posterior = mlp([history_features + future_features + action_embed, mlp_hidden, 2 * latent])

    # --- what a temporal encoder provides ---------------------------------------------------
    def encode_history(self, history_n: torch.Tensor) -> torch.Tensor:
        """normalised history [B, N, K] -> features [B, F]."""
        raise NotImplementedError

    def encode_future(self, future_n: torch.Tensor, lengths: torch.Tensor) -> torch.Tensor:
        """normalised future [B, T, K] valid up to `lengths` -> features [B, F_y] (training only)."""
        raise NotImplementedError

    def decode(self, h_x: torch.Tensor, a: torch.Tensor, z: torch.Tensor, history: torch.Tensor) -> torch.Tensor:
        """features, action token, z, raw history [B, N, J, 3] -> raw future [B, T_max, J, 3]."""
        raise NotImplementedError

    # --- shared -------------------------------------------------------------------------------
    def normalise(self, poses: torch.Tensor) -> torch.Tensor:
        return (poses.flatten(2) - self.pose_mean) / self.pose_std

    def step_scale(self) -> torch.Tensor:
        """The scale of frame-to-frame steps in the inputs: step_std where the model has it."""
        return self.step_std if hasattr(self, "step_std") else self.pose_std

    def history_input(self, history: torch.Tensor) -> torch.Tensor:
        """A history [B, N, J, 3] as the history encoder reads it (models/inputs.py)."""
        return inputs.history_features(history, self.pose_mean, self.pose_std, self.step_scale(), self.history_steps)

    def history_input_size(self) -> int:
        return self.joints * 3 * (2 if self.history_steps else 1)

    def future_input(self, future: torch.Tensor) -> torch.Tensor:
        """A future [B, T, J, 3] (canonical) as the posterior's encoder reads it (models/inputs.py)."""
        return inputs.future_features(future, self.pose_mean, self.pose_std, self.step_scale(), self.root_input)

    def pose_input_mask(self) -> torch.Tensor:
        """[J * 3]: which coordinates of the previous frame an autoregressive decoder reads."""
        return inputs.pose_input_mask(self.joints * 3, self.root_input)

    @staticmethod
    def split(params: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
        mu, logvar = params.chunk(2, dim=-1)
        return mu, logvar.clamp(LOGVAR_MIN, LOGVAR_MAX)

    def prior_params(self, history: torch.Tensor, action: torch.Tensor):
        """-> prior mean [B, D], prior log-variance [B, D], history features [B, F]."""
        h_x = self.encode_history(self.history_input(history))
        mu, logvar = self.split(self.prior(torch.cat([h_x, self.action_embed(action)], -1)))
        return mu, logvar, h_x

    def finish(self, frames: torch.Tensor, history: torch.Tensor) -> torch.Tensor:
        return frames if self.finish_layer is None else self.finish_layer(frames, history[:, -2:])

    def decode_from(self, z: torch.Tensor, history: torch.Tensor, action: torch.Tensor) -> torch.Tensor:
        h_x = self.encode_history(self.history_input(history))
        return self.finish(self.decode(h_x, self.action_embed(action), z, history), history)

    def forward(self, history: torch.Tensor, action: torch.Tensor, future: torch.Tensor, future_length: torch.Tensor):
        """Training pass: z from the posterior (reparameterised) -> (prediction, posterior, prior) params."""
        h_x = self.encode_history(self.history_input(history))
        a = self.action_embed(action)
        h_y = self.encode_future(self.future_input(future), future_length)
        mu, logvar = self.split(self.posterior(torch.cat([h_x, h_y, a], -1)))
        prior_mu, prior_logvar = self.split(self.prior(torch.cat([h_x, a], -1)))
        z = mu + (0.5 * logvar).exp() * torch.randn_like(mu)
        return self.finish(self.decode(h_x, a, z, history), history), mu, logvar, prior_mu, prior_logvar


class WatRNN(WatCVAE):
    """GRU encoders over X and Y; an autoregressive GRU decoder over [h_x, action, z, previous pose]
    whose frames are offsets from the last observed pose x_N (Fig. 3a).

    `residual` (the served choice): each step outputs the change from the previous frame and frame t
    is x_N plus the offsets accumulated so far; otherwise each step outputs its offset from x_N
    directly. Holding a pose (what the padding of Eq. 7 supervises, and what the stop rule of Eq. 8
    detects) is then a zero output instead of a fixed point of the GRU; at an equal budget it trained
    to a lower reconstruction loss (0.64 vs 0.83 after 2000 steps) and stopped more often.

    One decoder step is a GRU cell on [c, normalise(y_{t-1})], c = [h_x, a, z] fixed for the sequence
    (`decode_reference`, the plain form). `decode` computes the same function with the linear parts
    folded: c's share of the gates once per sequence, y_{t-1}'s share as a matrix on h_{t-1}, the
    outputs in one product at the end. That leaves one matrix product per step, which cuts training
    time on the CPU (tested equal to the plain form).
    """

    def __init__(self, joints: int, actions: int, max_frames: int, latent: int = 16, action_embed: int = 16,
                 history_hidden: int = 48, future_hidden: int = 32, decoder_hidden: int = 80, mlp_hidden: int = 96,
                 residual: bool = True, step_std: torch.Tensor | None = None, **stats):
        super().__init__(joints, actions, max_frames, latent, action_embed, history_hidden, future_hidden,
                         mlp_hidden, **stats)
        k, c, h = joints * 3, history_hidden + action_embed + latent, decoder_hidden
        self.residual = residual
        self.register_buffer("step_std", (step_std if step_std is not None else torch.ones(k)).reshape(1, 1, k).float())
        self.history_gru = nn.GRU(self.history_input_size(), history_hidden, batch_first=True)
        self.future_gru = nn.GRU(k, future_hidden, batch_first=True)
        self.decoder_init = nn.Linear(c, h)
        self.gate_condition = nn.Linear(c, 3 * h)            # GRU input gates [r, u, n] from c ...
        self.gate_pose = nn.Linear(k, 3 * h, bias=False)     # ... and from the previous pose
        self.gate_hidden = nn.Linear(h, 3 * h)               # hidden gates [r, u, n]
        self.decoder_out = nn.Linear(h, k)

    def encode_history(self, history_n):
        _, h = self.history_gru(history_n)
        return h[-1]

    def encode_future(self, future_n, lengths):
        # Every second frame: the posterior only needs the gist of Y, and this GRU would otherwise be a
        # third of the training time. Causal, so the state at the last valid frame ignores the padding.
        out, _ = self.future_gru(future_n[:, ::2])
        idx = ((lengths.long() - 1) // 2).clamp(min=0).view(-1, 1, 1).expand(-1, 1, out.shape[-1])
        return out.gather(1, idx)[:, 0]

    @staticmethod
    def _gru(gi: torch.Tensor, gh: torch.Tensor, h: torch.Tensor) -> torch.Tensor:
        """One GRU update from input gates gi and hidden gates gh, both [B, 3H] ordered [r, u, n]."""
        hidden = h.shape[-1]
        ru = torch.sigmoid(gi[:, :2 * hidden] + gh[:, :2 * hidden])
        r, u = ru[:, :hidden], ru[:, hidden:]
        n = torch.tanh(gi[:, 2 * hidden:] + r * gh[:, 2 * hidden:])
        return n + u * (h - n)

    def decode_reference(self, h_x, a, z, history):
        """The decoder written step by step (for tests): same function as `decode`."""
        b = history.shape[0]
        x_last = history[:, -1].reshape(b, -1)
        c = torch.cat([h_x, a, z], -1)
        h = torch.tanh(self.decoder_init(c))
        prev, frames = x_last, []
        mask = self.pose_input_mask()
        for _ in range(self.max_frames):
            pose_n = (prev - self.pose_mean[0]) / self.pose_std[0] * mask
            h = self._gru(self.gate_condition(c) + self.gate_pose(pose_n), self.gate_hidden(h), h)
            if self.residual:
                prev = prev + self.decoder_out(h) * self.step_std[0]
            else:
                prev = x_last + self.decoder_out(h) * self.offset_std[0]
            frames.append(prev)
        return torch.stack(frames, 1).reshape(b, self.max_frames, self.joints, 3)

    def decode(self, h_x, a, z, history):
        b = history.shape[0]
        x_last = history[:, -1].reshape(b, -1)
        c = torch.cat([h_x, a, z], -1)
        h = torch.tanh(self.decoder_init(c))
        hidden = h.shape[-1]
        mean, std = self.pose_mean[0, 0], self.pose_std[0, 0]
        scale = (self.step_std if self.residual else self.offset_std)[0, 0]
        w_pose = self.gate_pose.weight / std * self.pose_input_mask()         # gates from the raw pose
        w_out = self.decoder_out.weight * scale[:, None]                      # output = b_out + w_out h_t
        b_out = self.decoder_out.bias * scale
        first = self.gate_condition(c) - mean @ w_pose.t() + x_last @ w_pose.t()   # y_0 = x_N
        w_step = torch.cat([w_pose @ w_out, self.gate_hidden.weight], 0)      # h_{t-1} -> [pose gates, hidden gates]
        b_step = torch.cat([b_out @ w_pose.t(), self.gate_hidden.bias])
        states, acc = [], None
        # Unrolled in Python for training; the exported graph writes the same T_max steps as fused GRU
        # nodes (`rollout`, export/onnx/rollout.py), with no Loop operator.
        for t in range(self.max_frames):
            if t == 0:
                gi = first
            else:
                g = torch.addmm(b_step, h, w_step.t())
                # offsets: y_{t-1} = x_N + output_{t-1}; residual: y_{t-1} = x_N + sum of outputs so far
                acc = g[:, :3 * hidden] if acc is None or not self.residual else acc + g[:, :3 * hidden]
                gi = first + acc
            gh = self.gate_hidden(h) if t == 0 else g[:, 3 * hidden:]
            h = self._gru(gi, gh, h)
            states.append(h)
        out = b_out + torch.stack(states, 1) @ w_out.t()
        frames = x_last[:, None] + (out.cumsum(1) if self.residual else out)
        return frames.reshape(b, self.max_frames, self.joints, 3)

    def rollout_setup(self, z, history, action):
        """The decoder's start for the exported rollout: (x_N [B, K], h_0, c = [h_x, a, z][, the history's
        last two frames for the finishing layers])."""
        c = torch.cat([self.encode_history(self.history_input(history)), self.action_embed(action), z], -1)
        start = (history[:, -1].flatten(1), torch.tanh(self.decoder_init(c)), c)
        return start if self.finish_layer is None else start + (history[:, -2:],)

    def rollout(self) -> GruRollout:
        """`decode_reference`'s step with the normalisation folded into the weights (raw metres)."""
        mean, std = self.pose_mean[0, 0], self.pose_std[0, 0]
        scale = (self.step_std if self.residual else self.offset_std)[0, 0]
        w_pose = self.gate_pose.weight / std * self.pose_input_mask()
        return GruRollout(
            w_input=torch.cat([self.gate_condition.weight, w_pose], 1),
            b_input=self.gate_condition.bias - mean @ w_pose.t(),
            w_hidden=self.gate_hidden.weight, b_hidden=self.gate_hidden.bias,
            w_out=self.decoder_out.weight * scale[:, None], b_out=self.decoder_out.bias * scale,
            steps=self.max_frames, frame_shape=(self.joints, 3), residual=self.residual)


class PriorGraph(nn.Module):
    """(history [B, N, J, 3], action [B, A]) -> prior_mean [B, D], prior_logvar [B, D], history_features [B, F]."""

    def __init__(self, model: WatCVAE):
        super().__init__()
        self.model = model

    def forward(self, history, action):
        return self.model.prior_params(history, action)


class DecoderGraph(nn.Module):
    """(z [B, D], history [B, N, J, 3], action [B, A]) -> future [B, T_max, J, 3]."""

    def __init__(self, model: WatCVAE):
        super().__init__()
        self.model = model

    def forward(self, z, history, action):
        return self.model.decode_from(z, history, action)


class RolloutDecoderGraph(DecoderGraph, RolloutGraph):
    """WatRNN's decoder graph, exported with one fused GRU node per step."""

    def setup(self, z, history, action):
        return self.model.rollout_setup(z, history, action)

    def rollout(self) -> GruRollout:
        return self.model.rollout()

    def finish(self) -> nn.Module | None:
        return self.model.finish_layer
