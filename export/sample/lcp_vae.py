"""Predictor for LCP-VAE and its Table 4 baselines: condition graph, sample z, K futures in one decoder call.

Twin of web/src/predictor/lcp-vae.ts. Per graph call (a horizon beyond future_frames recurses on
each sample's own last history_frames frames, re-canonicalised):
  full model (params.prior "conditional"): z = mu_c + s*sigma_c*eps (Eq. 4 at inference with z = z_c,
      Algorithm 2 line 8); s = 0 decodes the most likely future z = mu_c (appendix E);
  row 2 (prior "standard_normal", c = h_t): z = s*eps, c = h_t;
  row 3 (prior "standard_normal", c = z_c): c = mu_c + s*sigma_c*eps_c, z = s*eps.
Draw order: sample i draws from its own stream, streams(seed, K)[i] (export/rng.py); per graph call,
for row 3 first d_c normals (eps_c) then d (eps), otherwise d (eps); two uniforms per normal. Nothing
couples the samples (the decoder and the recursive condition calls run through rows.run_rows), so the
first k samples of K > k are those of K = k. sample_latents also takes one Prng, whose arrays fill
row-major (sample, then latent dimension): the explainer's figures draw so.
Sampling arithmetic is float64 (mu + (s*sigma)*eps, in that order) rounded to float32 for the graph.
"""
from __future__ import annotations

import numpy as np

from ..ops.facing import root_relative, split_root
from ..rng import Prng, row_normals, streams
from .canonical import from_canonical, to_canonical
from .predictor import Predictor
from .request import Prediction, PredictError, Request, control_value, horizon_frames
from .rows import run_rows


def sample_latents(prng: Prng | list[Prng], cond: dict[str, np.ndarray], k: int, scale: float,
                   params: dict) -> tuple[np.ndarray, np.ndarray | None]:
    """Condition-graph outputs (batch 1 or K) -> (z [K, d], c [K, .] or None), float32; draws from one
    Prng row-major or from K streams, one per sample (twin of sampleLatents in web/src/predictor/lcp-vae.ts)."""
    d = params["latent_size"]
    c_spec = params.get("decoder_condition")
    c = None
    if params["prior"] == "conditional":
        eps = row_normals(prng, k, d)
        z = _shift_scale(cond["mu_c"], cond["sigma_c"], scale, eps, k)
    elif params["prior"] == "standard_normal":
        if c_spec and c_spec["name"] == "z_c":
            eps_c = row_normals(prng, k, c_spec["size"])
            c = _shift_scale(cond["mu_c"], cond["sigma_c"], scale, eps_c, k)
        elif c_spec and c_spec["name"] == "h_t":
            c = np.broadcast_to(cond["h_t"].astype(np.float32), (k, c_spec["size"])).copy()
        eps = row_normals(prng, k, d)
        z = (scale * eps).astype(np.float32)
    else:
        raise PredictError(f"unknown LCP-VAE prior {params['prior']!r} in the manifest")
    return z, c


def _shift_scale(mu: np.ndarray, sigma: np.ndarray, scale: float, eps: np.ndarray, k: int) -> np.ndarray:
    mu = np.broadcast_to(mu.astype(np.float64), (k, eps.shape[1]))
    sigma = np.broadcast_to(sigma.astype(np.float64), (k, eps.shape[1]))
    return (mu + scale * sigma * eps).astype(np.float32)


def diversity(futures: np.ndarray) -> float:
    """Average pairwise distance of K futures [K, T, J, 3] (WAT Eq. 10): over all pairs, the mean
    over frames of the L2 norm of the whole-pose difference, in metres, on root-relative poses (each
    frame's root x and z subtracted, as DLow's APD): where the root stands is not pose diversity, and
    planted feet (ops/foot_plant.py) move only the root path. 0 for K = 1."""
    k = len(futures)
    if k < 2:
        return 0.0
    flat = root_relative(split_root(futures)).reshape(k, futures.shape[1], -1)
    total = 0.0
    for i in range(k):
        for j in range(i + 1, k):
            total += float(np.linalg.norm(flat[i] - flat[j], axis=-1).mean())
    return 2.0 * total / (k * (k - 1))


class LcpVaePredictor(Predictor):
    def _predict(self, history: np.ndarray, req: Request) -> Prediction:
        n, step = self.params["history_frames"], self.params["future_frames"]
        horizon = horizon_frames(req, self.entry, self.manifest["fps"])
        k, scale = req.k, float(control_value(req, self.entry, "sigma_scale", 1.0))
        draws = streams(req.seed, k)
        c_spec = self.params.get("decoder_condition")
        # Every sample starts from the same history: the first condition call runs once (batch 1).
        recent = history[-n:].astype(np.float32)[None]         # [1 or K, n, J, 3]
        pieces = []
        done = 0
        while done < horizon:
            canon, placements = zip(*(to_canonical(h) for h in recent))
            canon = np.stack(canon)
            # the first call is batch 1 at every K; the recursive ones are batch K
            cond = run_rows(self.runner, "condition", {"history": canon})
            z, c = sample_latents(draws, cond, k, scale, self.params)
            last_poses = np.broadcast_to(canon[:, -2:], (k, 2) + canon.shape[2:]).copy()   # the seam needs two
            feeds = {"z": z, "last_poses": last_poses}
            if c_spec:
                feeds["c"] = c
            future = run_rows(self.runner, "decoder", feeds)["future"]
            placements = placements * k if len(placements) == 1 else placements
            future = np.stack([from_canonical(f, a) for f, a in zip(future, placements)])
            pieces.append(future)
            done += step
            joined = np.concatenate([np.broadcast_to(recent, (k,) + recent.shape[1:]), future], 1)
            recent = joined[:, -n:]
        futures = np.concatenate(pieces, 1)[:, :horizon].astype(np.float32)
        samples = [{"length": horizon, "stopped": False, "segments": [{"start": 0, "length": horizon}]}
                   for _ in range(k)]
        notes = ["sigma scale 0: every sample is the most likely future"] if scale == 0 and k > 1 else []
        return Prediction(futures, np.full(k, horizon), samples, notes=notes,
                          readouts=[{"label": "diversity", "value": diversity(futures), "unit": "m"}])
