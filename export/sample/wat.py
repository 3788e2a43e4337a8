"""Predictor for WAT: K samples per action, each cut at its own stop frame, actions one after another.

Twin of web/src/predictor/wat.ts. For every action of the sequence, with all K samples in one call:
  1. each sample's last N frames (up to its previous stop frame) -> canonical history;
  2. prior graph -> mu, log-variance; z = mu + (temperature * exp(logvar / 2)) * eps (float64, rounded to float32;
     temperature is the served control, 1 = the paper);
  3. decoder graph -> T_max frames; Eq. 8 on the canonical frames gives the sample's stop frame
     (T_max and stopped = false if no window falls below delta);
  4. Eq. 4 over the last L history frames and the first L predicted ones: the transition's smoothness,
     flagged above the manifest's threshold.
Draw order: sample i draws from its own stream, streams(seed, K)[i] (export/rng.py); per action, D
normals, two uniforms each. Nothing else draws, and nothing couples the samples (each stop, each
smoothness is the sample's own; graphs run through rows.run_rows), so the first k samples of K > k
are those of K = k.
"""
from __future__ import annotations

import numpy as np

from ..ops.dct_smoothness import smoothness
from ..ops.facing import root_relative
from ..ops.variance_stop import first_stop, variance_curve
from ..rng import row_normals, streams
from .canonical import from_canonical, to_canonical
from .predictor import Predictor
from .request import Prediction, PredictError, Request, control_value
from .rows import run_rows


def sample_latent(mu: np.ndarray, logvar: np.ndarray, eps: np.ndarray, temperature: float = 1.0) -> np.ndarray:
    """Reparameterisation z = mu + (temperature * exp(logvar / 2)) * eps in float64, rounded to float32 (twin
    of web/src/sampling/gaussian.ts; temperature 1 is the paper's prior sample)."""
    mu, logvar = np.asarray(mu, np.float64), np.asarray(logvar, np.float64)
    return (mu + (float(temperature) * np.exp(logvar / 2)) * np.asarray(eps, np.float64)).astype(np.float32)


class WatPredictor(Predictor):
    def _predict(self, history: np.ndarray, req: Request) -> Prediction:
        p = self.params
        n, t_max, d = p["history_frames"], p["future_frames"], p["latent_size"]
        q, delta, t_min = p["stop"]["q"], p["stop"]["delta"], p["stop"]["min_frames"]
        l, m, flag = p["smoothness"]["l"], p["smoothness"]["m"], p["smoothness"]["flag_threshold"]
        order = p["actions"]
        spec = next(c for c in self.entry["controls"] if c["id"] == "actions")
        if len(req.actions) > spec["max_length"]:
            raise PredictError(f"the action sequence has {len(req.actions)} actions; at most {spec['max_length']} are allowed")
        k = req.k
        temperature = float(control_value(req, self.entry, "temperature", 1.0))   # 1 = the paper's draw
        draws = streams(req.seed, k)
        seqs = [history[-n:].astype(np.float32)] * k          # world frame, grows by each segment
        parts = [[] for _ in range(k)]
        series = [[] for _ in range(k)]
        segments = [[] for _ in range(k)]
        margins = []
        for action in req.actions:
            canon, placements = zip(*(to_canonical(s[-n:]) for s in seqs))
            canon = np.stack(canon)
            onehot = np.zeros((k, len(order)), np.float32)
            onehot[:, order.index(action)] = 1
            prior = run_rows(self.runner, "prior", {"history": canon, "action": onehot})
            z = sample_latent(prior["prior_mean"], prior["prior_logvar"], row_normals(draws, k, d), temperature)
            future = run_rows(self.runner, "decoder", {"z": z, "history": canon, "action": onehot})["future"]
            for i in range(k):
                # Eq. 8 and Eq. 4 act on root-relative poses: a walk that keeps walking is not static.
                curve = variance_curve(root_relative(future[i]), q)
                stop = first_stop(curve, delta, t_min, t_max)
                margins.append(stop.margin)
                s = smoothness(root_relative(canon[i, -l:]), root_relative(future[i, :l]), m)
                start = sum(len(x) for x in parts[i])
                segments[i].append({"start": start, "length": stop.length, "action": action, "stopped": stop.stopped,
                                    "smoothness": s, "flagged": bool(s > flag)})
                # v at each kept frame (window starting there); the last Q-1 frames of a sample that
                # never stopped have no full window and repeat the last value.
                series[i] += [float(curve[min(f, len(curve) - 1)]) for f in range(stop.length)]
                world = from_canonical(future[i, :stop.length], placements[i])
                parts[i].append(world)
                seqs[i] = np.concatenate([seqs[i], world])
        totals = np.asarray([sum(len(x) for x in ps) for ps in parts])
        frames = int(req.horizon_frames) if req.horizon_frames is not None else int(totals.max())
        futures = np.empty((k, frames) + history.shape[1:], np.float32)
        samples = []
        for i in range(k):
            motion = np.concatenate(parts[i])[:frames]
            futures[i, :len(motion)] = motion
            futures[i, len(motion):] = motion[-1]                 # past its length a sample holds its last pose
            series[i] = (series[i] + [series[i][-1]] * frames)[:frames]
            segs = [dict(sg, length=min(sg["length"], frames - sg["start"])) for sg in segments[i] if sg["start"] < frames]
            samples.append({"length": int(min(totals[i], frames)), "stopped": all(sg["stopped"] for sg in segments[i]),
                            "segments": segs, "marks": [sg["start"] for sg in segs[1:]]})
        never = sum(not s["stopped"] for s in samples)
        notes = [f"{never} of {k} samples did not meet the stop rule in every action and kept T_max = {t_max} "
                 "frames there"] if never else []
        flagged = sum(sg["flagged"] for s in samples for sg in s["segments"])
        curves = [{"id": "variance", "title": "Variance of the last Q frames (Eq. 8)", "series": series,
                   "levels": [{"label": "delta", "value": delta}], "frames": [{"label": "T_min", "frame": t_min - 1}],
                   "log": True}]
        readouts = [{"label": "stopped", "value": 100.0 * (k - never) / k, "unit": "%"},
                    {"label": "mean length", "value": float(np.mean([s["length"] for s in samples])) / self.manifest["fps"],
                     "unit": "s"},
                    {"label": "flagged transitions", "value": float(flagged)}]
        return Prediction(futures, np.asarray([s["length"] for s in samples]), samples, notes=notes, curves=curves,
                          readouts=readouts, margins=margins)
