"""LCP-VAE as a Method: windows -> CS-VAE + LCP-VAE losses (Eq. 9) -> condition and decoder graphs.

The same method trains the Table 4 baselines (config `model.variant`: "cvae_h" row 2,
"cvae_zc" row 3); their graphs and manifest params tell the predictor how to sample.
"""
from __future__ import annotations

import numpy as np
import torch
from torch import nn

from ..data.clip import Clip
from ..data.skeleton import SKELETON
from ..data.sources import FPS
from ..data.windows import window_weights, windows
from ..models.lcp_vae import VARIANTS, ConditionGraph, DecoderGraph, LcpVae
from ..ops.floor import floor_penalty
from ..ops.skate_term import skate_term
from ..ops.speed_term import per_second_speed_term, speed_term
from ..ops.time_scale import slow_settings, slow_share
from ..ops.kl import kl_lcp, kl_standard_normal
from ..ops.kl_annealing import kl_weight
from .base import GraphDef, Method, TensorSpec, TrainingData

J = SKELETON.num_joints


class LcpVaeMethod(Method):
    name = "lcp_vae"

    def __init__(self, cfg: dict):
        super().__init__(cfg)
        m, t = cfg.get("model", {}), cfg.get("train", {})
        self.variant = m.get("variant", "lcp")
        # The served sigma scale s of z_c = mu_c + s * sigma_c * eps: 1 is the paper's reparameterisation
        # (Table 4 row 4); a larger s is a labelled variant, a sampling temperature on the CS-VAE's
        # posterior. Chosen on the training people's 2 s windows (in-sample table, K = 10), never on
        # held-out ones: best-of-10 ADE 0.596 / 0.586 / 0.585 m at s = 1 / 1.5 / 2, truth outside every
        # sample 95% / 81% / 67%, pose spread 5.5 / 8.0 / 10.3 cm: 2, the control's top then (superseded below).
        # The sampling control s (z = mu_c + s*sigma_c*eps; the paper samples at s = 1) served at 6 (was 2),
        # issue 28: the truth sat outside every sample because CS-VAE's posterior is narrow (its Eq. 5 KL ends
        # near 35 nats a window), and sampling draws z = z_c from it. A retrain with free bits on Eq. 6 (0.25
        # nats a dimension, tried as the cure for a collapsed data VAE) ended with the same training KLs as
        # without (Eq. 6 15.2 against 15.3 nats on the last batch) and, sampled at s = 2, the same held-out
        # spread and truth-outside (1 s: 5.2 against 5.6 cm, 93% both); not kept.
        # Chosen on the training people's 2 s windows (K = 10; best-of-10 ADE / zero-velocity's, truth
        # outside every sample, pose spread at the last frame): s = 2: 0.566, 75%, 7.7 cm; 4: 0.567, 35%,
        # 13.7 cm; 6: 0.602, 14%, 18.1 cm; 8: 0.645, 12%, 21.5 cm. 6 is the first scale whose truth-outside is
        # within twice the calibrated 9% at K = 10 (eval/realism/coverage.py). Held-out, looked at
        # afterwards (1 s / 2 s): s = 2: 0.684 / 0.782, 93 / 84%; s = 6: 0.684 / 0.788, 29 / 15%, with feet
        # below the floor in 0.3 / 0.5% of frames and foot skating 0.54 / 0.63x the captures'.
        self.sigma_scale_default = float(cfg.get("sampling", {}).get("sigma_scale", 1.0))
        if self.variant not in VARIANTS:
            raise ValueError(f"model.variant must be one of {sorted(VARIANTS)}, got {self.variant!r}")
        steps = int(t.get("steps", 1000))
        # configs/lcp_vae.json trains 9000 steps (was 3000; Appendix C trains 100 epochs at lr 0.005, kept
        # at 0.002), as both WAT models now train longer. Chosen on the training people's 2 s windows
        # (K = 10): best-of-10 ADE 0.585 -> 0.532 m, joint speed 0.69 / 0.42 -> 0.73 / 0.53 of the truth's
        # in seconds 1 / 2, truth outside 67 -> 51%, follow rho 0.66 -> 0.63.
        # Appendix C decays teacher forcing linearly to fully autoregressive "after a certain
        # number of epochs"; here after a fraction of the steps, then trains autoregressively.
        self.teacher_forcing_steps = int(round(float(t.get("teacher_forcing_fraction", 0.5)) * steps))
        # Eq. 9's lambda rises 0 -> 1 along a logistic curve, then stays at 1 (Section 4.2).
        self.kl_anneal_steps = int(round(float(t.get("kl_anneal_fraction", 0.4)) * steps))
        self.rec_units = t.get("rec_units", "normalised")
        if self.rec_units not in ("normalised", "metres"):
            raise ValueError(f"train.rec_units must be 'normalised' or 'metres', got {self.rec_units!r}")
        self.rec_weight = torch.ones(J * 3)
        # Issue 28, this pass, as WAT's (methods/wat.py): the root channel as steps and the history's steps
        # (models/inputs.py: the condition encoder reads the steps, the data encoder the root's steps, the data
        # decoder root-relative poses), slowed windows (ops/time_scale.py) and the prior-speed term on a future
        # decoded from z = z_c (loss.prior_speed 20, this model's speed weight; no grid). Measured as WAT's
        # table (K = 10 at sigma scale 2, 2 s): in 0.561, 0.77 / 0.67, follow 0.51, outside 80%, spread 7.8 cm;
        # out 0.784, 0.65 / 0.50, 0.69, 83%, 7.6 cm; the evaluation before this pass (docs/RESULTS.md of stop
        # 37) had out 0.926, - / 0.51, -0.01, 77%, 10.4 cm. Closer and following the history, but the samples
        # spread less (the data VAE's KL fell to 0.05 nats: z is z_c).
        self.slow = slow_settings(cfg)

    def prepare(self, clips: list[Clip]) -> TrainingData:
        t = self.cfg.get("train", {})
        n, f = self.history_frames, self.future_frames
        ws = windows(clips, "train", n + f, n, stride=int(t.get("stride", 1)), mirror=bool(t.get("mirror", True)))
        if not ws:
            raise ValueError(f"no training windows: every clip's training part is shorter than {n + f} frames")
        motion = torch.from_numpy(np.stack([w.positions for w in ws])).float()   # [W, N+T, J, 3]
        flat = motion.reshape(-1, J * 3)
        steps = motion.reshape(len(motion), n + f, J * 3).diff(dim=1).reshape(-1, J * 3)
        stats = {"pose_mean": flat.mean(0), "pose_std": flat.std(0).clamp_min(1e-2),
                 "step_std": steps.std(0).clamp_min(1e-4)}
        return TrainingData({"history": motion[:, :n], "future": motion[:, n:]}, stats, {"windows": len(ws)},
                            window_weights(ws))

    def build(self, data: TrainingData) -> nn.Module:
        m = self.cfg.get("model", {})
        # Eq. 8 sums squared errors in the data's units. The model works in per-coordinate
        # normalised units; "metres" weighs each coordinate by its variance to undo that. The
        # served config uses metres: in normalised units the reconstruction outweighs Eq. 5 so
        # much that sigma_c settled near 0.1 and the K = 10 diversity halved (measured).
        if self.rec_units == "metres":
            self.rec_weight = data.stats["pose_std"].square()
        return LcpVae(self.variant, J, self.history_frames, self.future_frames, int(m.get("hidden", 64)),
                      int(m.get("embed", 64)), int(m.get("latent", 16)), data.stats["pose_mean"],
                      data.stats["pose_std"], bool(m.get("keep_bones", True)), bool(m.get("seam", True)),
                      data.stats.get("step_std"), str(m.get("root_input", "position")),
                      bool(m.get("history_steps", False)))

    def schedule(self, step: int) -> tuple[float, float]:
        """(teacher-forcing probability, KL weight lambda) at a training step."""
        tf = max(0.0, 1.0 - step / self.teacher_forcing_steps) if self.teacher_forcing_steps > 0 else 0.0
        return tf, kl_weight(step, self.kl_anneal_steps)

    def loss(self, model, batch, step):
        teacher_forcing, lam = self.schedule(step)
        # a share of the windows replayed slowly (ops/time_scale.py, a labelled variant; as WAT's, methods/wat.py)
        s = self.slow
        history, future = slow_share(batch["history"], batch["future"], s["fraction"], s["min"], s["log"])
        batch = {**batch, "history": history, "future": future}
        out = model(batch["history"], batch["future"], teacher_forcing)
        terms = components(self.variant, out, self.rec_weight)
        kl = terms["kl_c"] + terms["kl"]
        # feet may not sink (ops/floor.py), on the future in metres; a term beside Eq. 9
        terms["floor"] = floor_penalty(model.denormalise(out["future_hat"]))
        w_floor = float(self.cfg.get("loss", {}).get("floor", 1000.0))
        # Eq. 9's lambda ends at loss.kl (1 by default): Eq. 8 sums squared errors in the data's units, so how
        # strongly the two KLs weigh against it depends on those units (quaternions in the paper, metres here).
        # The served 0.1, measured on held-out people at 2 s against 1: best-of-10 ADE 0.728 -> 0.702 m,
        # joint speed in the 2nd second 0.24 -> 0.28 of the truth's; the data VAE's KL had fallen to 2 nats.
        lam = lam * float(self.cfg.get("loss", {}).get("kl", 1.0))
        total = lam * kl + terms["rec_history"] + terms["rec_future"] + w_floor * terms["floor"]   # Eq. 9 + floor
        # labelled variant terms beside Eq. 9 (0: the paper's loss), as WAT's (methods/wat.py): the speed
        # term keeps the decoded future moving (held-out, 2 s: joint speed 0.67 / 0.28 of the truth's
        # per second without it), the skate term keeps a foot on the floor still. Eq. 8 sums over the 60
        # frames where WAT's Eq. 7 averages, so the weights are about half of WAT's.
        w_speed, w_skate = (float(self.cfg.get("loss", {}).get(k, 0.0)) for k in ("speed", "skate"))
        if w_speed or w_skate:
            future = model.denormalise(out["future_hat"])
            if w_speed:
                terms["speed"] = speed_term(batch["history"], future, batch["future"])
                total = total + w_speed * terms["speed"]
            if w_skate:
                terms["skate"] = skate_term(batch["history"], future)
                total = total + w_skate * terms["skate"]
        w_prior = float(self.cfg.get("loss", {}).get("prior_speed", 0.0))
        if w_prior and model.has_cs_vae:
            # the per-second speed term on a future sampled as the predictor samples it, z_c ~ N(mu_c, sigma_c)
            # (ops/speed_term.py; WAT's, methods/wat.py): the freeze lives in sampled futures
            core = getattr(model, "module", model)
            z_c = out["mu_c"] + out["sigma_c"] * torch.randn_like(out["mu_c"])
            # row 4 decodes z = z_c; row 3 decodes a standard normal z with c = z_c (sample/lcp_vae.py)
            z, c = (torch.randn_like(z_c), z_c) if core.decoder_condition == "z_c" else (z_c, None)
            last = batch["history"][:, -2:]
            sample = core.finish(core.denormalise(core.decode(z, last, c)), last)
            mask = torch.ones(sample.shape[:2], dtype=torch.bool)
            terms["prior_speed"] = per_second_speed_term(batch["history"], sample, batch["future"], mask)
            total = total + w_prior * terms["prior_speed"]
        logs = {k: float(v.detach()) for k, v in terms.items()}
        logs.update(lam=lam, tf=teacher_forcing)
        return total, logs

    def graphs(self, model: nn.Module) -> dict[str, GraphDef]:
        n, d = self.history_frames, model.latent
        gen = torch.Generator().manual_seed(0)
        mean_pose = model.pose_mean.reshape(1, J, 3)
        history = mean_pose.expand(2, n, J, 3) + 0.05 * torch.randn(2, n, J, 3, generator=gen)
        cond = ConditionGraph(model)
        cond_outputs = [TensorSpec(name, ["batch", model.hidden if name == "h_t" else d]) for name in cond.outputs]
        z = torch.randn(2, d, generator=gen)
        last_poses = mean_pose.expand(2, 2, J, 3) + 0.05 * torch.randn(2, 2, J, 3, generator=gen)
        inputs = [TensorSpec("z", ["batch", d]), TensorSpec("last_poses", ["batch", 2, J, 3])]
        examples = (z, last_poses)
        if model.decoder_condition:
            c = torch.randn(2, model.decoder_condition_size, generator=gen)
            inputs.append(TensorSpec("c", ["batch", model.decoder_condition_size]))
            examples = examples + (c,)
        return {
            "condition": GraphDef(cond, (history,), [TensorSpec("history", ["batch", n, J, 3])], cond_outputs),
            "decoder": GraphDef(DecoderGraph(model), examples, inputs,
                                [TensorSpec("future", ["batch", self.future_frames, J, 3])]),
        }

    def params(self, model: nn.Module) -> dict:
        c = model.decoder_condition
        return {**super().params(model), "latent_size": model.latent, "table4_row": VARIANTS[self.variant],
                # How the predictor samples z: from the condition's posterior N(mu_c, sigma_c^2)
                # (Eq. 4 at inference, Algorithm 2 line 8) or from N(0, I) (rows 2 and 3).
                "prior": "conditional" if self.variant == "lcp" else "standard_normal",
                # The decoder graph's extra input c: h_t (row 2), a sampled z_c (row 3), or none.
                "decoder_condition": {"name": c, "size": model.decoder_condition_size} if c else None}

    def controls(self, actions: list[str]) -> list[dict]:
        return [
            {"id": "k", "type": "int", "label": "Samples (K)", "min": 1, "max": 50, "step": 1, "default": 10,
             "help": "Futures drawn from the same history, decoded in one batch."},
            {"id": "horizon", "type": "number", "label": "Horizon (s)", "min": 0.5, "max": 6, "step": 0.5,
             "default": round(self.future_frames / FPS, 3),
             "help": "How far to predict; past one call each sample recurses on its own last frames with a new z."},
            {"id": "sigma_scale", "type": "number", "label": "Sigma scale", "min": 0, "max": 8, "step": 0.1,
             "default": self.sigma_scale_default,
             "help": "Scales the sampled spread: z = mu_c + s*sigma_c*eps. 0 decodes the most likely "
                     "future z = mu_c (all K samples equal); the diversity read-out grows with s."},
        ]


def reconstruction(x_hat: torch.Tensor, x: torch.Tensor, weight: torch.Tensor) -> torch.Tensor:
    """Eq. 8 per example: squared errors [B, F, P] summed over frames and coordinates (each
    coordinate weighted), averaged over the batch."""
    return ((x_hat - x).square() * weight).sum((1, 2)).mean()


def components(variant: str, out: dict, rec_weight: torch.Tensor) -> dict[str, torch.Tensor]:
    """The loss terms of Eq. 9 (batch means) for one forward pass."""
    zero = out["future_hat"].new_zeros(())
    terms = {"rec_future": reconstruction(out["future_hat"], out["future_norm"], rec_weight),
             "rec_history": (reconstruction(out["history_hat"], out["history_norm"], rec_weight)
                             if "history_hat" in out else zero),
             "kl_c": kl_standard_normal(out["mu_c"], out["sigma_c"]).mean() if "mu_c" in out else zero}
    if variant == "lcp":
        # CS-VAE is frozen for Eq. 6: no gradient reaches mu_c, sigma_c through this term.
        terms["kl"] = kl_lcp(out["mu"], out["sigma"], out["mu_c"].detach(), out["sigma_c"].detach()).mean()
    else:
        terms["kl"] = kl_standard_normal(out["mu"], out["sigma"]).mean()
    return terms


@torch.no_grad()
def loss_components(method: LcpVaeMethod, model: LcpVae, data: TrainingData, batch_size: int = 256,
                    seed: int = 0) -> dict[str, float]:
    """Each term of Eq. 9 over all training windows, fully autoregressive (as trained at the end),
    plus the future's mean per-joint error in metres: for reporting where training ended."""
    torch.manual_seed(seed)
    model.eval()
    sums: dict[str, float] = {}
    n = len(data)
    for a in range(0, n, batch_size):
        hist, fut = data.tensors["history"][a:a + batch_size], data.tensors["future"][a:a + batch_size]
        out = model(hist, fut, 0.0)
        terms = {k: float(v) for k, v in components(model.variant, out, method.rec_weight).items()}
        err = torch.linalg.vector_norm(model.denormalise(out["future_hat"]) - fut, dim=-1).mean()
        terms["future_mpjpe_m"] = float(err)
        for k, v in terms.items():
            sums[k] = sums.get(k, 0.0) + v * len(hist)
    return {k: v / n for k, v in sums.items()}
