"""LCP-VAE (paper Section 4, Algorithms 1-2, appendix C) and the Table 4 CVAE baselines.

One module holds the CS-VAE on the observed motion (the condition) and the VAE on the future
motion (the data). Three ways to condition the data VAE (Table 4):
  "lcp"     row 4: encoder on [h_T, h_t]; decoder from z = mu + sigma*z_c (Eq. 4), no concatenation;
  "cvae_h"  row 2: encoder on [h_T, h_t]; decoder from [z, h_t]; z = mu + sigma*eps, prior N(0, I);
  "cvae_zc" row 3: encoder on [h_T, z_c]; decoder from [z, z_c]; z = mu + sigma*eps, prior N(0, I).
Row 2 is a standard CVAE and has no CS-VAE. Poses are positions (the paper uses quaternions),
normalised per coordinate inside the module so the exported graphs take raw metres.
"""
from __future__ import annotations

import torch
from torch import nn
from torch.nn import functional as F

from .gru_rollout import GruRollout, RolloutGraph
from . import inputs
from .finish import Finish

VARIANTS = {"lcp": 4, "cvae_h": 2, "cvae_zc": 3}   # variant -> row of Table 4
# sigma > 0 strictly: the KLs of Eqs. 5-6 take log sigma.
SIGMA_FLOOR = 1e-4


class MotionEncoder(nn.Module):
    """EncodeCondition / EncodeData: a one-layer GRU; its last hidden state is h_t (or h_T)."""

    def __init__(self, pose: int, hidden: int):
        super().__init__()
        self.gru = nn.GRU(pose, hidden, batch_first=True)

    def forward(self, x: torch.Tensor) -> torch.Tensor:
        _, h = self.gru(x)
        return h[-1]


class GaussianEncoder(nn.Module):
    """CS-VAE.Encode / LCP-VAE.Encode: FC + ReLU embedding, then a mean and a std branch."""

    def __init__(self, inp: int, embed: int, latent: int):
        super().__init__()
        self.embed = nn.Sequential(nn.Linear(inp, embed), nn.ReLU())
        self.mu = nn.Linear(embed, latent)
        self.sigma = nn.Linear(embed, latent)

    def forward(self, x: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
        e = self.embed(x)
        # Appendix C uses ReLU for sigma; that allows sigma = 0, where log sigma in Eqs. 5-6 is
        # -inf. Softplus is ReLU-like for large inputs and strictly positive.
        return self.mu(e), F.softplus(self.sigma(e)) + SIGMA_FLOOR


class StateDecoder(nn.Module):
    """CS-VAE.Decode / LCP-VAE.Decode: FC layers to a GRU state, tanh like a GRU state (appendix C)."""

    def __init__(self, inp: int, embed: int, hidden: int):
        super().__init__()
        self.net = nn.Sequential(nn.Linear(inp, embed), nn.ReLU(), nn.Linear(embed, hidden), nn.Tanh())

    def forward(self, x: torch.Tensor) -> torch.Tensor:
        return self.net(x)


class PoseDecoder(nn.Module):
    """DecodeCondition / DecodeData: an autoregressive GRU from a state and a seed pose.

    The loop is plain Python; the exported graph writes it as one fused GRU node per step
    (`LcpVae.rollout`). Each step predicts a change of the
    pose fed in (a residual) rather than the pose itself (appendix C maps the GRU output to the
    pose): the first future frame then starts at the last observed pose instead of jumping.
    """

    def __init__(self, pose: int, hidden: int, input_mask: torch.Tensor | None = None):
        super().__init__()
        self.cell = nn.GRUCell(pose, hidden)
        self.out = nn.Linear(hidden, pose)
        # Coordinates the cell does not read (the root channel's position with root_input "step",
        # models/inputs.py); the residual still accumulates them.
        self.register_buffer("input_mask", torch.ones(pose) if input_mask is None else input_mask.float(),
                             persistent=False)
        with torch.no_grad():  # start near zero velocity
            self.out.weight.mul_(0.1)
            self.out.bias.zero_()

    def forward(self, state: torch.Tensor, seed: torch.Tensor, frames: int,
                target: torch.Tensor | None = None, teacher_forcing: float = 0.0) -> torch.Tensor:
        """state [B, H], seed [B, P] -> [B, frames, P]; with `target`, each step feeds the true
        previous pose with probability `teacher_forcing` (appendix C), per example and step."""
        h, x, outs = state, seed, []
        for t in range(frames):
            h = self.cell(x * self.input_mask, h)
            y = x + self.out(h)
            outs.append(y)
            if target is not None and teacher_forcing > 0:
                use = torch.rand(y.shape[0], 1, device=y.device) < teacher_forcing
                x = torch.where(use, target[:, t], y)
            else:
                x = y
        return torch.stack(outs, 1)


class LcpVae(nn.Module):
    def __init__(self, variant: str, joints: int, history_frames: int, future_frames: int,
                 hidden: int, embed: int, latent: int, pose_mean: torch.Tensor, pose_std: torch.Tensor,
                 keep_bones: bool = True, seam: bool = True, step_std: torch.Tensor | None = None,
                 root_input: str = "position", history_steps: bool = False):
        super().__init__()
        # What the networks read (models/inputs.py): the root channel as steps, the history's steps.
        self.root_input, self.history_steps = inputs.check_root_input(root_input), history_steps
        # The data decoder's last layers (models/finish.py): the seam with the history, bones of fixed length.
        self.finish_layer = Finish(future_frames, seam, keep_bones) if (seam or keep_bones) else None
        if variant not in VARIANTS:
            raise ValueError(f"unknown LCP-VAE variant {variant!r}; known: {sorted(VARIANTS)}")
        self.variant, self.joints = variant, joints
        self.history_frames, self.future_frames = history_frames, future_frames
        self.hidden, self.latent = hidden, latent
        pose = joints * 3
        self.register_buffer("pose_mean", pose_mean.reshape(pose).float())
        self.register_buffer("pose_std", pose_std.reshape(pose).float())
        # frame-to-frame steps' std: the scale of the history's steps and of the root's step (models/wat.py)
        self.register_buffer("step_std", (pose_std if step_std is None else step_std).reshape(pose).float())
        self.encode_condition = MotionEncoder(pose * (2 if history_steps else 1), hidden)
        if self.has_cs_vae:
            self.cs_encode = GaussianEncoder(hidden, embed, latent)
            self.cs_decode = StateDecoder(latent, embed, hidden)
            self.decode_condition = PoseDecoder(pose, hidden)
        self.encode_data = MotionEncoder(pose, hidden)
        encoder_condition = latent if variant == "cvae_zc" else hidden
        self.lcp_encode = GaussianEncoder(hidden + encoder_condition, embed, latent)
        self.lcp_decode = StateDecoder(latent + self.decoder_condition_size, embed, hidden)
        self.decode_data = PoseDecoder(pose, hidden, inputs.pose_input_mask(pose, root_input))

    @property
    def has_cs_vae(self) -> bool:
        return self.variant != "cvae_h"

    @property
    def decoder_condition(self) -> str | None:
        """The name of c, the decoder's concatenated condition (None for the full model)."""
        return {"lcp": None, "cvae_h": "h_t", "cvae_zc": "z_c"}[self.variant]

    @property
    def decoder_condition_size(self) -> int:
        return {"lcp": 0, "cvae_h": self.hidden, "cvae_zc": self.latent}[self.variant]

    def normalise(self, poses: torch.Tensor) -> torch.Tensor:
        """[B, F, J, 3] metres -> [B, F, P] normalised coordinates."""
        return (poses.flatten(2) - self.pose_mean) / self.pose_std

    def history_input(self, history: torch.Tensor) -> torch.Tensor:
        """What the condition encoder reads (models/inputs.py)."""
        return inputs.history_features(history, self.pose_mean, self.pose_std, self.step_std, self.history_steps)

    def future_input(self, future: torch.Tensor) -> torch.Tensor:
        """What the data encoder reads (models/inputs.py)."""
        return inputs.future_features(future, self.pose_mean, self.pose_std, self.step_std, self.root_input)

    def denormalise(self, x: torch.Tensor) -> torch.Tensor:
        return (x * self.pose_std + self.pose_mean).reshape(*x.shape[:-1], self.joints, 3)

    def finish(self, future: torch.Tensor, last_poses: torch.Tensor) -> torch.Tensor:
        """Decoded future [B, T, J, 3] metres and the history's last two poses -> the finished future."""
        return future if self.finish_layer is None else self.finish_layer(future, last_poses)

    def condition(self, history: torch.Tensor) -> dict[str, torch.Tensor]:
        """history [B, N, J, 3] metres -> h_t, and mu_c, sigma_c when there is a CS-VAE."""
        out = {"h_t": self.encode_condition(self.history_input(history))}
        if self.has_cs_vae:
            out["mu_c"], out["sigma_c"] = self.cs_encode(out["h_t"])
        return out

    def decode(self, z: torch.Tensor, last_poses: torch.Tensor, c: torch.Tensor | None = None,
               target: torch.Tensor | None = None, teacher_forcing: float = 0.0) -> torch.Tensor:
        """z [B, d], last observed pose [B, J, 3] metres (, c) -> normalised future [B, T, P]."""
        code = z if c is None else torch.cat([z, c], -1)
        seed = (last_poses[:, -1].flatten(1) - self.pose_mean) / self.pose_std
        return self.decode_data(self.lcp_decode(code), seed, self.future_frames, target, teacher_forcing)

    def rollout_setup(self, z: torch.Tensor, last_poses: torch.Tensor, c: torch.Tensor | None = None):
        """The data decoder's start for the exported rollout: (last pose [B, P] metres, its state[, the
        last two poses for the finishing layers])."""
        start = (last_poses[:, -1].flatten(1), self.lcp_decode(z if c is None else torch.cat([z, c], -1)))
        return start if self.finish_layer is None else start + (last_poses,)

    def rollout(self) -> GruRollout:
        """DecodeData's step with the normalisation folded into the weights (raw metres)."""
        cell, out = self.decode_data.cell, self.decode_data.out
        w_in = cell.weight_ih / self.pose_std * self.decode_data.input_mask
        return GruRollout(w_input=w_in, b_input=cell.bias_ih - w_in @ self.pose_mean,
                          w_hidden=cell.weight_hh, b_hidden=cell.bias_hh,
                          w_out=out.weight * self.pose_std[:, None], b_out=out.bias * self.pose_std,
                          steps=self.future_frames, frame_shape=(self.joints, 3))

    def forward(self, history: torch.Tensor, future: torch.Tensor, teacher_forcing: float = 0.0) -> dict:
        """A training pass (Algorithms 1 and 2): reconstructions and posterior parameters."""
        x_hist, x_fut = self.normalise(history), self.normalise(future)
        cond = self.condition(history)
        out = dict(cond)
        if self.has_cs_vae:
            z_c = cond["mu_c"] + cond["sigma_c"] * torch.randn_like(cond["mu_c"])   # Eq. 3
            # The history decoder has no observed pose to start from: it starts from the mean
            # pose (zero in normalised units), so everything it knows comes through z_c.
            out["history_hat"] = self.decode_condition(self.cs_decode(z_c), torch.zeros_like(x_hist[:, 0]),
                                                       self.history_frames, x_hist, teacher_forcing)
            out["history_norm"] = x_hist
        h_T = self.encode_data(self.future_input(future))
        if self.variant == "lcp":
            out["mu"], out["sigma"] = self.lcp_encode(torch.cat([h_T, cond["h_t"]], -1))
            z, c = out["mu"] + out["sigma"] * z_c, None                              # Eq. 4
        elif self.variant == "cvae_h":
            out["mu"], out["sigma"] = self.lcp_encode(torch.cat([h_T, cond["h_t"]], -1))
            z, c = out["mu"] + out["sigma"] * torch.randn_like(out["mu"]), cond["h_t"]
        else:
            out["mu"], out["sigma"] = self.lcp_encode(torch.cat([h_T, z_c], -1))
            z, c = out["mu"] + out["sigma"] * torch.randn_like(out["mu"]), z_c
        decoded = self.decode(z, history[:, -2:], c, x_fut, teacher_forcing)
        out["future_hat"] = self.normalise(self.finish(self.denormalise(decoded), history[:, -2:]))
        out["future_norm"] = x_fut
        return out


class ConditionGraph(nn.Module):
    """Exported: history [B, N, J, 3] -> what sampling needs (mu_c, sigma_c and/or h_t)."""

    def __init__(self, model: LcpVae):
        super().__init__()
        self.model = model

    @property
    def outputs(self) -> list[str]:
        return ["h_t"] if self.model.variant == "cvae_h" else ["mu_c", "sigma_c"]

    def forward(self, history: torch.Tensor):
        cond = self.model.condition(history)
        return tuple(cond[name] for name in self.outputs)


class DecoderGraph(RolloutGraph):
    """Exported: (z, last pose[, c]) -> future [B, T, J, 3] metres, fully autoregressive; the
    recurrence is written as fused GRU nodes (export/onnx/rollout.py)."""

    def __init__(self, model: LcpVae):
        super().__init__()
        self.model = model

    def forward(self, z: torch.Tensor, last_poses: torch.Tensor, c: torch.Tensor | None = None):
        return self.model.finish(self.model.denormalise(self.model.decode(z, last_poses, c)), last_poses)

    def setup(self, z: torch.Tensor, last_poses: torch.Tensor, c: torch.Tensor | None = None):
        return self.model.rollout_setup(z, last_poses, c)

    def rollout(self) -> GruRollout:
        return self.model.rollout()

    def finish(self) -> nn.Module | None:
        return self.model.finish_layer
