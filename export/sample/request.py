"""The predictor contract in Python, twin of web/src/predictor/types.ts.

A history (world frame, [frames, J, 3] metres, the root travelling) and a request go in; K futures
with per-sample lengths and diagnostics come out. Requests are checked against the model's
manifest entry, and every problem is a PredictError that says what is wrong.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

MAX_K = 50


class PredictError(ValueError):
    pass


@dataclass
class Request:
    k: int = 1
    seed: int = 0
    actions: list[str] = field(default_factory=list)
    horizon_frames: int | None = None
    controls: dict = field(default_factory=dict)
    # Feet on the floor carry the root (ops/foot_plant.py); False keeps the method's own root travel.
    plant_feet: bool = True

    @classmethod
    def from_json(cls, doc: dict) -> "Request":
        return cls(k=int(doc.get("k", 1)), seed=int(doc.get("seed", 0)), actions=list(doc.get("actions", [])),
                   horizon_frames=doc.get("horizon_frames"), controls=dict(doc.get("controls", {})),
                   plant_feet=doc.get("plant_feet", True))

    def to_json(self) -> dict:
        out = {"k": self.k, "seed": self.seed, "actions": self.actions, "controls": self.controls}
        if self.horizon_frames is not None:
            out["horizon_frames"] = self.horizon_frames
        if self.plant_feet is not True:
            out["plant_feet"] = self.plant_feet
        return out


@dataclass
class Prediction:
    """Twin of the TypeScript Prediction (web/src/predictor/types.ts)."""
    futures: np.ndarray            # [K, T, J, 3] float32, world frame; past a sample's length: its last pose
    lengths: np.ndarray            # [K] frames
    samples: list[dict]            # per sample: {"length", "stopped", "segments": [...], "marks"?, "labels"?}
    notes: list[str] = field(default_factory=list)
    curves: list[dict] = field(default_factory=list)     # {"id", "title", "series": [K][T], "levels", "frames"}
    readouts: list[dict] = field(default_factory=list)   # {"label", "value", "unit"}
    ghosts: dict | None = None                           # {"frames": [K][n], "poses": [K][n, J, 3]}
    # Decisions with their distance to the threshold that made them (stop tests, sampled labels):
    # the end-to-end vectors keep only cases whose smallest margin is at least 1e-3.
    margins: list[float] = field(default_factory=list)
    # History quantities outside the training envelope (ops/envelope.py): predicted anyway, marked.
    warnings: list[dict] = field(default_factory=list)

    def to_json(self) -> dict:
        return {"k": int(self.futures.shape[0]), "frames": int(self.futures.shape[1]),
                "lengths": [int(x) for x in self.lengths], "samples": self.samples, "notes": self.notes,
                "curves": self.curves, "readouts": self.readouts, "warnings": self.warnings,
                **({"ghosts": {"frames": self.ghosts["frames"],
                               "poses": [np.asarray(p, np.float32).tolist() for p in self.ghosts["poses"]]}}
                   if self.ghosts is not None else {}),
                "futures": self.futures.astype(np.float32).tolist()}


def check_history(history: np.ndarray, needed: int, joints: int) -> np.ndarray:
    history = np.asarray(history, dtype=np.float64)
    if history.ndim != 3 or history.shape[1:] != (joints, 3):
        raise PredictError(f"history must be [frames, {joints}, 3], got shape {list(history.shape)}")
    if len(history) < needed:
        raise PredictError(f"history has {len(history)} frames; this model needs at least {needed}")
    if not np.all(np.isfinite(history)):
        bad = int(np.argwhere(~np.isfinite(history))[0][0])
        raise PredictError(f"history contains NaN or infinite values (first at frame {bad})")
    return history


# Controls that are fields of the request rather than entries of `controls`.
REQUEST_FIELDS = ("k", "actions", "horizon")


def control_value(req: Request, entry: dict, cid: str, absent=None):
    """A control's value: the request's, else the manifest's default, else `absent` (a model without it)."""
    spec = next((c for c in entry["controls"] if c["id"] == cid), None)
    return req.controls.get(cid, spec["default"]) if spec else absent


def horizon_frames(req: Request, entry: dict, fps: float) -> int:
    """Frames to predict: the request's, else the `horizon` control's default (seconds), else one call."""
    if req.horizon_frames is not None:
        return int(req.horizon_frames)
    spec = next((c for c in entry["controls"] if c["id"] == "horizon"), None)
    return round(spec["default"] * fps) if spec else int(entry["params"]["future_frames"])


def check_request(req: Request, entry: dict, actions: list[str], fps: float = 30.0) -> None:
    controls = {c["id"]: c for c in entry["controls"]}
    if "k" in controls:
        if not (isinstance(req.k, int) and 1 <= req.k <= MAX_K):
            raise PredictError(f"K must be an integer from 1 to {MAX_K}, got {req.k}")
    elif req.k != 1:
        raise PredictError(f"{entry['label']} is deterministic: it predicts one future (K = 1), got K = {req.k}")
    if not (isinstance(req.seed, int) and 0 <= req.seed <= 0xFFFFFFFF):
        raise PredictError(f"seed must be an integer from 0 to 4294967295, got {req.seed}")
    for a in req.actions:
        if a not in actions:
            raise PredictError(f"unknown action {a!r}; this model knows {', '.join(actions)}")
    if "actions" in controls and not req.actions:
        raise PredictError("the action sequence is empty: add at least one action")
    if req.horizon_frames is not None:
        spec = controls.get("horizon")
        lo, hi = (round(spec["min"] * fps), round(spec["max"] * fps)) if spec else (1, entry["params"]["future_frames"])
        if not (isinstance(req.horizon_frames, int) and lo <= req.horizon_frames <= hi):
            raise PredictError(f"the horizon must be {lo} to {hi} frames, got {req.horizon_frames}")
    if not isinstance(req.plant_feet, bool):
        raise PredictError(f"plant_feet must be true or false, got {req.plant_feet!r}")
    for cid, value in req.controls.items():
        spec = controls.get(cid)
        if cid in REQUEST_FIELDS:
            raise PredictError(f"{cid!r} is a field of the request, not a control value")
        if spec is None:
            raise PredictError(f"{entry['label']} has no control {cid!r}")
        if spec["type"] in ("int", "number"):
            if not isinstance(value, (int, float)) or isinstance(value, bool) or not math.isfinite(value):
                raise PredictError(f"{spec['label']} must be a number, got {value!r}")
            if ("min" in spec and value < spec["min"]) or ("max" in spec and value > spec["max"]):
                raise PredictError(f"{spec['label']} must be between {spec.get('min')} and {spec.get('max')}, got {value}")
