"""Planted feet: the root's horizontal travel re-derived from the feet on the floor, so a foot in contact
stays where it is in the world while the body passes over it.

Every method predicts the pose and the root's travel separately (a network's root channel, or Keyposes'
per-segment velocity table, ops/keypose_travel.py), and nothing ties the two: on held-out people the feet
of every served model slid 2.2-4.7 times as fast as the captures' while on the floor (issue 28, target 4).
A walker's root moves because the stance foot pushes it, so while a foot is down the root's step is
the opposite of that foot's step relative to the root; in the air the root keeps the method's own step.

Per future step t -> t+1 (the history's last frame is step 0's start), for each foot joint j (ankles and
toes, both sides) with height y: its contact weight is w_j = min(c(y_j,t), c(y_j,t+1)) * g(s_j), where
c(y) = 1 at or below FULL, 0 at or above NONE, linear between, and g(s) = 1 at or below SLOW, 0 at or
above SLIDING, of the joint's world speed s under the method's own root (ramps, not thresholds: the
decision is continuous in the prediction, so the float32 differences between runtimes and CPUs move it by
as little as they move the poses; a hard 3 cm test would flip whole root paths). g keeps a foot that
swings forward low over the floor (Keyposes' linear interpolation between two keyposes with both feet
down) from pushing the body backwards: without it, planted Keyposes walks on held-out people travelled
backwards in some samples, with g their median contact speed fell further (0.144 -> 0.123 m/s). Then

    planted_t = - sum_j w_j (r_j,t+1 - r_j,t) / sum_j w_j      (r: the joint's x, z minus the root's)
    step_t    = (1 - a_t) * method_step_t + a_t * planted_t,   a_t = max_j w_j

and the whole pose moves with the new root path. Heights, root-relative poses (what ADE, joint speed and
bones read) and lengths are unchanged; only where the body stands changes. FULL = 2 cm and NONE = 4 cm
sit either side of the 3 cm contact band of the floor and of the skating measure (ops/floor.CONTACT_BAND).

This is the product's post-process, not a paper's: the evaluation shows every served learned model also
with `plant_feet` off (the method's own root, export/eval/rows.py). TypeScript twin:
web/src/predictor/foot-plant.ts; shared vectors contract/vectors/foot_plant.json.
"""
from __future__ import annotations

import numpy as np

from ..data.skeleton import SKELETON, Skeleton

FOOT_JOINTS = ("left_ankle", "left_toe", "right_ankle", "right_toe")
FULL = 0.02    # metres: at or below, the joint is planted
NONE = 0.04    # metres: at or above, it carries no weight
SLOW = 1.0     # m/s: a joint moving at most this fast in the world (the method's root) may be planted ...
SLIDING = 2.5  # ... and one this fast is a foot swinging low, not a foot on the floor
FPS = 30


def speed_weight(speed: np.ndarray) -> np.ndarray:
    """A foot joint's world speed under the method's own root (m/s) -> weights in [0, 1]."""
    return np.clip((SLIDING - np.asarray(speed, dtype=np.float64)) / (SLIDING - SLOW), 0.0, 1.0)


def contact_weight(height: np.ndarray) -> np.ndarray:
    """Foot joint heights (m) -> contact weights in [0, 1]."""
    return np.clip((NONE - np.asarray(height, dtype=np.float64)) / (NONE - FULL), 0.0, 1.0)


def plant_feet(present: np.ndarray, futures: np.ndarray, skeleton: Skeleton = SKELETON) -> np.ndarray:
    """present [J, 3] (the history's last frame) and world futures [K, T, J, 3] -> the futures with the
    root's x, z re-derived while feet are on the floor (float64, same shape)."""
    f = np.asarray(futures, dtype=np.float64)
    if f.ndim != 4 or f.shape[1] == 0:
        return f.copy()
    k = f.shape[0]
    m = np.concatenate([np.broadcast_to(np.asarray(present, dtype=np.float64), (k, 1) + f.shape[2:]), f], 1)
    idx = [skeleton.index(n) for n in FOOT_JOINTS]
    root = m[:, :, 0, [0, 2]]                                      # [K, T + 1, 2]
    rel = m[:, :, idx][..., [0, 2]] - root[:, :, None]             # [K, T + 1, 4, 2]
    c = contact_weight(m[:, :, idx, 1])                            # [K, T + 1, 4]
    world = np.linalg.norm(np.diff(m[:, :, idx][..., [0, 2]], axis=1), axis=-1) * FPS   # [K, T, 4] m/s
    w = np.minimum(c[:, :-1], c[:, 1:]) * speed_weight(world)     # [K, T, 4]
    total = w.sum(-1)
    planted = -(w[..., None] * np.diff(rel, axis=1)).sum(-2) / np.maximum(total, 1e-12)[..., None]
    a = w.max(-1)[..., None]
    step = (1.0 - a) * np.diff(root, axis=1) + a * planted
    new_root = root[:, :1] + np.cumsum(step, axis=1)               # [K, T, 2]
    out = f.copy()
    out[..., [0, 2]] += (new_root - root[:, 1:])[:, :, None, :]
    return out
