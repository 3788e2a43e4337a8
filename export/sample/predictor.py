"""The Python predictor: the same contract and the same steps as the TypeScript one.

Evaluation predicts through it, and the shared end-to-end vectors tie it to the browser,
so what is evaluated is what the browser runs.
"""
from __future__ import annotations

import importlib
from pathlib import Path

import numpy as np

from ..manifest import entry as find_entry, read_manifest
from ..paths import MODELS_DIR
from ..ops.foot_plant import plant_feet
from .canonical import SCALE_LIMITS, SCALE_TOLERANCE, body_scale, rescale, scale_anchor
from .ghosts import follow_roots
from .guard import cut_out_of_bounds
from .history import refusal_with_warnings, warnings_for
from .request import Prediction, PredictError, Request, check_history, check_request
from .runner import GraphRunner


class Predictor:
    def __init__(self, entry: dict, manifest: dict, models_dir: Path = MODELS_DIR, precision: str = "float32"):
        self.entry, self.manifest = entry, manifest
        self.params = entry["params"]
        self.runner = GraphRunner(entry, models_dir, precision)

    def predict(self, history: np.ndarray, req: Request) -> Prediction:
        """history [frames, J, 3] in the world frame -> K futures in the same frame, each cut at its
        first out-of-bounds frame (guard.py), the root carried by the feet on the floor unless
        req.plant_feet is False (ops/foot_plant.py), with warnings for the history (history.py): outside the
        training envelope, reflected, still, or at another body size. A body at another size is brought
        to the model's size for predicting and the futures are scaled back (canonical.py)."""
        joints = len(self.manifest["skeleton"]["joints"])
        n = self.params["history_frames"]
        history = check_history(history, n, joints)
        check_request(req, self.entry, self.manifest["actions"], self.manifest["fps"])
        scale = body_scale(history[-n:])
        lo, hi = SCALE_LIMITS
        if not lo <= scale <= hi:
            raise PredictError(f"the body is {scale:.2f} times the model's size (bone lengths); this model predicts "
                               f"bodies {lo}-{hi} times its size: retarget the history to the skeleton first")
        scaled = abs(scale - 1) > SCALE_TOLERANCE
        anchor = scale_anchor(history)
        work = rescale(history, 1 / scale, anchor) if scaled else history
        warnings = warnings_for(history[-n:], self.params.get("envelope"), self.manifest["fps"])
        try:
            pred = self._predict(work, req)
        except PredictError as e:   # a refusal leads with the warning that most likely caused it
            raise PredictError(refusal_with_warnings(str(e), warnings)) from None
        if req.plant_feet:               # feet on the floor carry the root (ops/foot_plant.py), and the ghosts with it
            planted = plant_feet(work[-1], pred.futures).astype(np.float32)
            if pred.ghosts is not None:
                follow_roots(pred.ghosts, pred.futures, planted)
            pred.futures = planted
        cut_out_of_bounds(pred.futures, pred.lengths, pred.samples, work[-n:])
        if pred.ghosts is not None:      # keypose ghosts past a cut go with it
            for i, s in enumerate(pred.samples):
                keep = len(s.get("marks", pred.ghosts["frames"][i]))
                pred.ghosts["frames"][i] = pred.ghosts["frames"][i][:keep]
                pred.ghosts["poses"][i] = pred.ghosts["poses"][i][:keep]
        if scaled:                       # back to the history's size
            pred.futures = rescale(pred.futures, scale, anchor).astype(np.float32)
            if pred.ghosts is not None:
                pred.ghosts["poses"] = [rescale(p, scale, anchor).astype(np.float32) for p in pred.ghosts["poses"]]
        pred.warnings = warnings
        return pred

    def _predict(self, history: np.ndarray, req: Request) -> Prediction:
        raise NotImplementedError


# The one place that knows which predictor runs which method (twin of web/src/predictor/factory.ts).
PREDICTORS: dict[str, str] = {
    "zero_velocity": "export.sample.direct:DirectPredictor",
    "regression": "export.sample.direct:DirectPredictor",
    "wat": "export.sample.wat:WatPredictor",
    "wat_transformer": "export.sample.wat:WatPredictor",      # same graphs' signatures as "wat"
    "lcp_vae": "export.sample.lcp_vae:LcpVaePredictor",
    "keyposes": "export.sample.keyposes:KeyposesPredictor",
}


def predictor_for(entry: dict, manifest: dict, models_dir: Path, precision: str = "float32") -> Predictor:
    module, name = PREDICTORS[entry["method"]].split(":")
    return getattr(importlib.import_module(module), name)(entry, manifest, models_dir, precision)


def load_predictor(model_id: str, models_dir: Path = MODELS_DIR, precision: str = "float32") -> Predictor:
    """precision="float64" runs the same graphs widened to float64 (the float32 error reference)."""
    manifest = read_manifest(Path(models_dir) / "manifest.json")
    return predictor_for(find_entry(manifest, model_id), manifest, Path(models_dir), precision)
