"""What the predictor says about a history before predicting from it (issue 30): the training envelope
(export/ops/envelope.py) and three findings the envelope cannot express as a range:
- handedness: a body reflected without swapping its left and right labels (export/ops/handedness.py);
- motion: a history that does not move, said in one sentence with its speed (predicted anyway);
- body_scale: a body at another size, brought to the model's size for predicting (canonical.py).
A refusal that comes with warnings leads with the one that most likely caused it (`refusal_with_warnings`).
TypeScript twin: web/src/predictor/history.ts; contract/vectors/envelope.json ties them.
"""
from __future__ import annotations

import numpy as np

from ..ops.envelope import check
from ..ops.handedness import MESSAGE as HANDEDNESS_MESSAGE, THRESHOLD as HANDEDNESS_THRESHOLD, handedness
from .canonical import SCALE_TOLERANCE, body_scale, rescale, scale_anchor, to_canonical

STILL_SPEED = 0.05   # m/s: a history whose fastest joint is slower than this does not move
# Findings that are not ranges come first when they occur: each alone explains odd futures.
CATEGORICAL = ("handedness", "motion")


def still_speed(world: np.ndarray, fps: float) -> float:
    """The fastest joint speed between any two frames of a world history (m/s)."""
    w = np.asarray(world, dtype=np.float64)
    return float(np.linalg.norm(np.diff(w, axis=0), axis=-1).max() * fps) if len(w) > 1 else 0.0


def history_warnings(recent: np.ndarray, canonical: np.ndarray, env: dict | None, fps: float,
                     scale: float) -> list[dict]:
    """The warnings for a history: `recent` its last N frames as given (world), `canonical` the same
    frames as the model sees them (at the model's size), `scale` its body size against the model's."""
    out = []
    reflected, score = handedness(recent)
    if reflected:
        out.append({"quantity": "handedness", "value": round(score, 4), "min": HANDEDNESS_THRESHOLD, "max": 1.0,
                    "unit": "", "message": HANDEDNESS_MESSAGE})
    speed = still_speed(recent, fps)
    if speed < STILL_SPEED:
        top = env["joint_speed"][1] if env and "joint_speed" in env else 100.0
        out.append({"quantity": "motion", "value": round(speed, 4), "min": STILL_SPEED, "max": top, "unit": "m/s",
                    "message": f"The history does not move: its fastest joint moves at {speed:.3f} m/s, so the "
                               f"futures start from rest."})
    if abs(scale - 1) > SCALE_TOLERANCE:
        out.append({"quantity": "body_scale", "value": round(scale, 4), "min": round(1 - SCALE_TOLERANCE, 4),
                    "max": round(1 + SCALE_TOLERANCE, 4), "unit": "x",
                    "message": f"The body is {scale:.2f} times the model's size (bone lengths): it was brought to "
                               f"the model's size for predicting, and the futures scaled back."})
    if env:
        out += check(canonical, env, fps)
    return ordered(out)


def warnings_for(recent: np.ndarray, env: dict | None, fps: float) -> list[dict]:
    """The warnings for the last N frames of a world history, as the predictor gives them: the
    envelope measured on the history brought to the model's size (predictor.py does the same)."""
    scale = body_scale(recent)
    work = rescale(recent, 1 / scale, scale_anchor(recent)) if abs(scale - 1) > SCALE_TOLERANCE else recent
    return history_warnings(recent, to_canonical(work)[0], env, fps, scale)


def excess(w: dict) -> float:
    """How far a range warning lies outside its range, in widths of the range (categorical: infinite)."""
    if w["quantity"] in CATEGORICAL:
        return float("inf")
    lo, hi = w["min"], w["max"]
    span = max(hi - lo, 1e-9)
    return max(lo - w["value"], w["value"] - hi, 0.0) / span


def ordered(warnings: list[dict]) -> list[dict]:
    """Most likely cause first: categorical findings, then the range farthest outside (stable)."""
    return sorted(warnings, key=lambda w: (-excess(w), CATEGORICAL.index(w["quantity"]) if w["quantity"] in CATEGORICAL else 0))


def refusal_with_warnings(message: str, warnings: list[dict]) -> str:
    """A refusal that has warnings leads with the most likely cause, says why, then gives the refusal."""
    if not warnings:
        return message
    first, *rest = ordered(warnings)
    why = ("" if first["quantity"] in CATEGORICAL
           else ", the quantity farthest outside the training range")
    out = f"{first['message']} That is the most likely cause of this refusal{why}: {message}."
    if rest:
        out += " Also outside the training range: " + " ".join(w["message"] for w in rest)
    return out
