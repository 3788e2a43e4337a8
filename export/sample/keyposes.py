"""Keyposes predictor, twin of web/src/predictor/keyposes.ts: extract the history's keyposes,
feed them to the KP-GRU step graph, sample K label and duration sequences with the shared PRNG,
interpolate the centres from the present pose (Eq. 3) and optionally refine.

Draw order (both languages): sample i draws from its own stream, streams(seed, K)[i] (export/rng.py):
after the observed keyposes, at each step whose horizon it has not yet covered, one uniform for the
label, then one for the duration class. Each draw is the first index whose cumulative
softmax(logits / temperature) probability exceeds the uniform. A sample's logits come from its own row
of the batched step graph (rows.run_rows), so the first k samples of K > k are those of K = k.
"""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from ..data.skeleton import SKELETON
from ..ops import keyposes as kp
from ..ops.facing import canonicalise, place, root_relative, rotate_about_y, split_root
from ..ops.bones import keep_bones
from ..ops.keypose_travel import pace, travel
from ..ops.seam import continue_history
from ..ops.keypose_interpolation import interpolate, keypose_times
from ..ops.proximity import face_forward, proximity, sample_index, softmax
from ..paths import MODELS_DIR
from ..rng import streams
from .predictor import Predictor
from .request import PredictError, Prediction, Request, control_value, horizon_frames
from .rows import run_rows


def read_centres(path: Path, clusters: int, joints: int) -> tuple[np.ndarray, np.ndarray]:
    """The centres file: centres [K][J][3] and the root velocity table [K][2], checked against the
    manifest's cluster count."""
    if not path.exists():
        raise FileNotFoundError(f"{path}: keypose centres file missing; run `make models`")
    try:
        doc = json.loads(path.read_text())
        centres = np.asarray(doc["centres"], dtype=np.float64)
        velocity = np.asarray(doc["root_velocity"], dtype=np.float64)
    except (ValueError, KeyError, TypeError) as e:
        raise ValueError(f"{path}: not a keypose centres file ({e})") from e
    if centres.shape != (clusters, joints, 3):
        raise ValueError(f"{path}: centres must be [{clusters}][{joints}][3], got {list(centres.shape)}")
    if velocity.shape != (clusters, 2):
        raise ValueError(f"{path}: root_velocity must be [{clusters}][2], got {list(velocity.shape)}")
    return centres, velocity


class KeyposesPredictor(Predictor):
    def __init__(self, entry: dict, manifest: dict, models_dir: Path = MODELS_DIR, precision: str = "float32"):
        super().__init__(entry, manifest, models_dir, precision)
        self.models_dir = Path(models_dir)
        self._file: tuple[np.ndarray, np.ndarray] | None = None

    def _centres_file(self) -> tuple[np.ndarray, np.ndarray]:
        if self._file is None:
            name = self.entry.get("files", {}).get("centres")
            if not name:
                raise ValueError(f"model {self.entry['id']} names no keypose centres file in the manifest")
            self._file = read_centres(self.models_dir / name, self.params["keyposes"]["clusters"],
                                      len(self.manifest["skeleton"]["joints"]))
        return self._file

    @property
    def centres(self) -> np.ndarray:
        return self._centres_file()[0]

    @property
    def root_velocity(self) -> np.ndarray:
        return self._centres_file()[1]

    def observe(self, history: np.ndarray) -> dict:
        """The history's keyposes: frames, labels after pruning, and the KP-GRU's inputs."""
        p, k = self.params, self.params["keyposes"]
        hist = root_relative(split_root(history[-p["history_frames"]:]))     # keyposes act on poses
        frames = kp.extract(hist, k["threshold"])
        values = face_forward(hist[frames])
        labels, _ = kp.nearest_centre(values, self.centres)
        keep = kp.prune(labels)
        if len(keep) < k["min_observed"]:
            raise PredictError(
                f"the history yields {len(keep)} keypose{'' if len(keep) == 1 else 's'} at the {k['threshold']} m threshold; Keyposes needs at "
                f"least {k['min_observed']}: choose a history with more motion")
        keep = keep[-k["max_observed"]:]
        frames = [frames[i] for i in keep]
        bounds = p["duration_classes"]["bounds"]
        duration = np.zeros((len(frames), len(bounds)), np.float32)
        for i in range(1, len(frames)):          # the first fed keypose has no known duration
            duration[i, kp.duration_class(frames[i] - frames[i - 1], tuple(bounds))] = 1
        dist = softmax(proximity(values[keep], self.centres), p["label_temperature"]).astype(np.float32)
        return {"frames": frames, "labels": labels[keep].tolist(), "label_dist": dist, "duration": duration}

    def _predict(self, history: np.ndarray, req: Request) -> Prediction:
        p = self.params
        temperature = float(control_value(req, self.entry, "temperature"))
        if not temperature > 0:
            raise PredictError(f"the temperature must be above 0, got {temperature}")
        refine = control_value(req, self.entry, "refine")
        if not isinstance(refine, bool):
            raise PredictError(f"Refine must be true or false, got {refine!r}")
        horizon = horizon_frames(req, self.entry, self.manifest["fps"])
        r = p["refine_frames"]
        if horizon > r:
            raise PredictError(f"the horizon must be at most {r} frames, got {horizon}")
        need = r if refine else horizon
        centres = self.centres
        lengths = p["duration_classes"]["lengths"]
        layers, hidden = p["keyposes"]["layers"], p["keyposes"]["hidden"]

        obs = self.observe(history)
        h = np.zeros((1, layers, hidden), np.float32)
        for i in range(len(obs["frames"])):
            out = self.runner.run("step", {"label_dist": obs["label_dist"][i:i + 1],
                                           "duration": obs["duration"][i:i + 1], "hidden": h})
            h = out["next_hidden"]
        k = req.k
        logits = np.repeat(out["label_logits"], k, 0)
        dlogits = np.repeat(out["duration_logits"], k, 0)
        h = np.repeat(h, k, 0)

        # A fed-back label's distribution: its centre's proximity to every centre (3.2.1, case 2).
        centre_dist = softmax(proximity(centres, centres), p["label_temperature"]).astype(np.float32)
        eye = np.eye(len(lengths), dtype=np.float32)
        draws = streams(req.seed, k)
        labels: list[list[int]] = [[] for _ in range(k)]
        classes: list[list[int]] = [[] for _ in range(k)]
        covered = np.zeros(k, np.int64)
        margins: list[float] = []
        while True:
            for s in range(k):
                if covered[s] >= need:
                    continue
                lab, m1 = sample_index(logits[s], temperature, draws[s].uniform())
                dur, m2 = sample_index(dlogits[s], temperature, draws[s].uniform())
                labels[s].append(lab)
                classes[s].append(dur)
                covered[s] += lengths[dur]
                margins += [m for m in (m1, m2) if np.isfinite(m)]
            if covered.min() >= need:
                break
            out = run_rows(self.runner, "step", {"label_dist": centre_dist[[ls[-1] for ls in labels]],
                                                 "duration": eye[[cs[-1] for cs in classes]], "hidden": h})
            logits, dlogits, h = out["label_logits"], out["duration_logits"], out["next_hidden"]

        canon, placement = canonicalise(history[-p["history_frames"]:], p["history_frames"] - 1, SKELETON)
        present = root_relative(canon[-1])
        futures = np.stack([interpolate(present, centres[labels[s]], [lengths[c] for c in classes[s]], need)
                            for s in range(k)])
        if refine:
            seq = np.concatenate([np.repeat(present[None, None], k, 0), futures[:, :r]], 1).astype(np.float32)
            futures = run_rows(self.runner, "refine", {"sequence": seq})["refined"].astype(np.float64)
        futures = futures[:, :horizon]
        # The root channel, per segment (export/ops/keypose_travel.py), in the root joint's x and z; then
        # the seam with the history (ops/seam.py) and the skeleton's bone lengths (ops/bones.py), as the
        # graphs of the other methods end.
        scale = pace(canon[:, 0, [0, 2]], obs["labels"], self.root_velocity)   # the history's own pace
        for s in range(k):
            futures[s, :, 0, [0, 2]] = travel(labels[s], [lengths[c] for c in classes[s]], self.root_velocity,
                                              horizon, scale).T
        if p.get("finish", True):
            futures = keep_bones(continue_history(futures, canon[None, -2:]))
        futures = place(futures, placement).astype(np.float32)

        samples, ghost_frames, ghost_poses = [], [], []
        for s in range(k):
            times = keypose_times([lengths[c] for c in classes[s]])
            shown = int(np.sum(times <= horizon))
            marks = (times[:shown] - 1).tolist()
            samples.append({"length": horizon, "stopped": False, "segments": [{"start": 0, "length": horizon}],
                            "marks": marks, "labels": labels[s][:shown]})
            ghost_frames.append(marks)
            at = futures[s, np.asarray(marks, dtype=np.int64), :1] * np.array([1.0, 0.0, 1.0])   # root's ground point
            ghost_poses.append((rotate_about_y(centres[labels[s][:shown]], placement.angle) + at).astype(np.float32))
        readouts = [{"label": "observed keyposes", "value": len(obs["frames"])},
                    {"label": "keyposes per future", "value": float(np.mean([len(g) for g in ghost_frames]))},
                    {"label": "travel pace (history / training)", "value": round(scale, 4)}]
        return Prediction(futures, np.full(k, horizon), samples, readouts=readouts, margins=margins,
                                  ghosts={"frames": ghost_frames, "poses": ghost_poses})
