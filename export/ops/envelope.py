"""The training envelope: what the histories a model learned from looked like, and how a new history
compares (issue 19: say so when a history is unlike anything seen, rather than predict in silence).

Measured on each canonical training history (export/ops/facing.py) of the model's N frames, and on
a user's history the same way, so both sides see the same numbers:
- root_height: mean root height (m; the floor is y = 0, export/ops/floor.py);
- root_speed: mean horizontal speed of the root channel (m/s);
- scale: mean root-to-head distance (m), the body's size;
- bone_error: largest relative difference of a bone from the skeleton's length (the models' bones;
  retargeted histories have 0);
- joint_speed: the largest joint speed in the history (m/s, world frame).
The envelope of a quantity is [p0.5, p99.5] of its training values, widened by MARGIN of that span on
each side (and never narrower than FLOOR_SPAN), so that a history at the edge of the training data is
not called unfamiliar. A value outside is a named warning; predicting is still allowed.
TypeScript twin: web/src/predictor/envelope.ts; contract/vectors/envelope.json ties them.
"""
from __future__ import annotations

import numpy as np

from ..data.skeleton import SKELETON, Skeleton
from .bones import bone_lengths
from .facing import root_channel, root_relative

QUANTITIES = {                 # name -> (unit, what it means, for the warning)
    "root_height": ("m", "root height"),
    "root_speed": ("m/s", "walking speed of the root"),
    "scale": ("m", "body size (root to head)"),
    "bone_error": ("", "bone length difference"),
    "joint_speed": ("m/s", "fastest joint speed"),
}
MARGIN = 0.1
FLOOR_SPAN = {"root_height": 0.05, "root_speed": 0.2, "scale": 0.05, "bone_error": 0.05, "joint_speed": 0.5}


def measure(canonical: np.ndarray, fps: float, skeleton: Skeleton = SKELETON) -> dict[str, float]:
    """One canonical history [N, J, 3] -> its quantities."""
    m = np.asarray(canonical, dtype=np.float64)
    poses = root_relative(m)
    path = root_channel(m)
    head = skeleton.index("head")
    rest = skeleton.bone_lengths()
    world = poses.copy()
    world[:, :, [0, 2]] += path[:, None, :]
    steps = np.linalg.norm(np.diff(world, axis=0), axis=-1) if len(m) > 1 else np.zeros((1, 1))
    return {
        "root_height": float(m[:, 0, 1].mean()),
        "root_speed": float(np.linalg.norm(np.diff(path, axis=0), axis=-1).mean() * fps) if len(m) > 1 else 0.0,
        "scale": float(np.linalg.norm(poses[:, head] - poses[:, 0], axis=-1).mean()),
        "bone_error": float((np.abs(bone_lengths(poses, skeleton) - rest) / rest).max()),
        "joint_speed": float(steps.max() * fps),
    }


def envelope(histories: list[np.ndarray] | np.ndarray, fps: float, skeleton: Skeleton = SKELETON) -> dict:
    """Canonical training histories -> {quantity: [low, high]} (rounded to 4 decimals, in the manifest)."""
    values = {q: [] for q in QUANTITIES}
    for h in histories:
        for q, v in measure(h, fps, skeleton).items():
            values[q].append(v)
    out = {}
    for q, vs in values.items():
        lo, hi = np.percentile(vs, [0.5, 99.5])
        pad = max(MARGIN * (hi - lo), (FLOOR_SPAN[q] - (hi - lo)) / 2, 0.0)
        low = max(lo - pad, 0.0)
        out[q] = [round(float(low), 4), round(float(hi + pad), 4)]
    return out


def check(canonical: np.ndarray, env: dict, fps: float, skeleton: Skeleton = SKELETON) -> list[dict]:
    """The named warnings for a history outside `env`: quantity, value, training range, one sentence."""
    out = []
    for q, v in measure(canonical, fps, skeleton).items():
        if q not in env:
            continue
        lo, hi = env[q]
        if not lo <= v <= hi:
            unit, what = QUANTITIES[q]
            u = f" {unit}" if unit else ""
            out.append({"quantity": q, "value": round(v, 4), "min": lo, "max": hi, "unit": unit,
                        "message": f"The history's {what} is {v:.2f}{u}, outside what this model was trained on "
                                   f"({lo:.2f}-{hi:.2f}{u}): the prediction may be unreliable."})
    return out
