"""Guards that hold whatever a model does (issue 19): never draw an exploding figure.

Every future frame is checked against the history it continues:
- every value is finite;
- every bone is within BONE_RATIO of its length in the history (a factor, either way);
- every joint is within REACH_RATIO x the history's largest root-to-joint distance of the root
  (at least MIN_REACH metres);
- the root moves at most MAX_ROOT_STEP metres per frame (15 m/s at 30 fps: faster than any sprint)
  and stays within MAX_ROOT_HEIGHT of the floor.
A sample that breaks a bound is cut at its last good frame: its length becomes that frame count, the
frames after it hold the last good pose, and the sample says `cut` with its own reason, separate from
Eq. 8's `stopped`. Twin: web/src/predictor/guard.ts (same bounds, same first bad frame).
"""
from __future__ import annotations

import numpy as np

from ..data.skeleton import SKELETON, Skeleton
from ..ops.bones import bone_lengths

BONE_RATIO = 1.5
REACH_RATIO = 1.5
MIN_REACH = 1.5
MAX_ROOT_STEP = 0.5
MAX_ROOT_HEIGHT = 3.0
CUT_REASON = "cut: out of bounds"


def first_bad_frame(future: np.ndarray, history: np.ndarray, skeleton: Skeleton = SKELETON) -> tuple[int, str] | None:
    """(index of the first future frame [T, J, 3] that breaks a bound, which bound) or None; world frame."""
    f = np.asarray(future, dtype=np.float64)
    h = np.asarray(history, dtype=np.float64)
    rest = bone_lengths(h, skeleton).mean(0)
    reach = max(REACH_RATIO * float(np.linalg.norm(h - h[:, :1], axis=-1).max()), MIN_REACH)
    checks = []
    finite = np.isfinite(f).all(axis=(1, 2))
    checks.append((~finite, "a value is not finite"))
    with np.errstate(invalid="ignore", over="ignore", divide="ignore"):
        ratio = bone_lengths(f, skeleton) / rest
        bad_bone = ~((ratio <= BONE_RATIO) & (ratio >= 1 / BONE_RATIO)).all(axis=1)
        far = ~(np.linalg.norm(f - f[:, :1], axis=-1) <= reach).all(axis=1)
        prev = np.concatenate([h[-1:, 0], f[:-1, 0]])
        step = ~(np.linalg.norm((f[:, 0] - prev)[:, [0, 2]], axis=-1) <= MAX_ROOT_STEP)
        high = ~(np.abs(f[:, 0, 1]) <= MAX_ROOT_HEIGHT)
    checks += [(bad_bone, f"a bone is more than {BONE_RATIO}x off its length in the history"),
               (far, f"a joint is more than {reach:.2f} m from the root"),
               (step, f"the root moves more than {MAX_ROOT_STEP} m in one frame"),
               (high, f"the root is more than {MAX_ROOT_HEIGHT} m from the floor")]
    hits = [(int(np.argmax(bad)), why) for bad, why in checks if bad.any()]
    return min(hits, key=lambda x: x[0]) if hits else None


def cut_out_of_bounds(futures: np.ndarray, lengths: np.ndarray, samples: list[dict], history: np.ndarray,
                      skeleton: Skeleton = SKELETON) -> None:
    """Cut, in place, every sample at its first bad frame (within its length)."""
    for i in range(len(futures)):
        bad = first_bad_frame(futures[i, :lengths[i]], history, skeleton)
        if bad is None:
            continue
        frame, why = bad
        last = futures[i, frame - 1] if frame > 0 else history[-1]
        futures[i, frame:] = last
        lengths[i] = frame
        s = samples[i]
        s["length"] = frame
        s["cut"] = {"frame": frame, "reason": CUT_REASON, "detail": why}
        s["segments"] = [dict(g, length=min(g["length"], frame - g["start"])) for g in s["segments"] if g["start"] < frame]
        if "marks" in s:
            s["marks"] = [m for m in s["marks"] if m < frame]
        if "labels" in s:
            s["labels"] = s["labels"][:len(s.get("marks", s["labels"]))]
