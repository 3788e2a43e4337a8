"""The floor of a clip: estimated once per clip, never per history, so real jumps and climbs stay.

The foot is the lower of ankle and toe (either side). Contact frames are those whose lowest foot point
lies within CONTACT_BAND of the floor; the floor is the least-squares plane y = a x + b z + c through
their lowest foot points, found by a few rounds of: fit, re-select contacts. It starts from a low
percentile of the lowest foot height, never the single lowest point, so a T-pose frame or a one-frame
glitch cannot lift every other frame, and a slope (a capture volume whose floor rises 2% along a walk)
is followed instead of floating the far end. A tilt is fitted only where the contacts spread over at
least MIN_SPREAD metres; otherwise the floor is level (an in-place motion says nothing about a slope).
Each frame is then shifted vertically by the floor height under its root, which keeps bone lengths.
"""
from __future__ import annotations

import numpy as np

from ..data.skeleton import SKELETON, Skeleton

FEET = ("right_ankle", "right_toe", "left_ankle", "left_toe")
CONTACT_BAND = 0.03       # metres: a foot this close to the floor is on it
START_PERCENTILE = 10     # of the lowest foot height: the first guess of the floor
MIN_SPREAD = 1.0          # metres of contact spread before a tilt is fitted
MAX_SLOPE = 0.1           # a steeper fitted floor is not a floor: stay level


def foot_height(positions: np.ndarray, skeleton: Skeleton = SKELETON) -> np.ndarray:
    """[..., F, J, 3] -> [..., F]: the height of the lower of ankle and toe, both sides."""
    idx = [skeleton.index(n) for n in FEET]
    return positions[..., idx, 1].min(axis=-1)


def floor_plane(positions: np.ndarray, skeleton: Skeleton = SKELETON) -> tuple[float, float, float]:
    """(a, b, c) of the floor y = a x + b z + c of a clip [F, J, 3] (world frame, y up)."""
    idx = [skeleton.index(n) for n in FEET]
    feet = positions[:, idx]                                       # [F, 4, 3]
    low = feet[np.arange(len(feet)), feet[:, :, 1].argmin(1)]      # lowest foot point per frame
    a = b = 0.0
    c = float(np.percentile(low[:, 1], START_PERCENTILE))
    for _ in range(4):
        height = low[:, 1] - (a * low[:, 0] + b * low[:, 2] + c)
        contact = np.abs(height) <= CONTACT_BAND
        if contact.sum() < 3:
            break
        pts = low[contact]
        spread = np.ptp(pts[:, [0, 2]], axis=0).max()
        if spread >= MIN_SPREAD:
            design = np.column_stack([pts[:, 0], pts[:, 2], np.ones(len(pts))])
            a2, b2, c2 = np.linalg.lstsq(design, pts[:, 1], rcond=None)[0]
            if np.hypot(a2, b2) <= MAX_SLOPE:
                a, b, c = float(a2), float(b2), float(c2)
                continue
        a = b = 0.0
        c = float(np.median(pts[:, 1]))
    return a, b, c


def on_floor(positions: np.ndarray, skeleton: Skeleton = SKELETON) -> np.ndarray:
    """The clip with its floor at y = 0: each frame shifted down by the floor height under its root."""
    a, b, c = floor_plane(positions, skeleton)
    root = positions[:, 0]
    out = positions.copy()
    out[..., 1] -= (a * root[:, 0] + b * root[:, 2] + c)[:, None]
    return out


def floor_penalty(motion):
    """A training term (torch): the mean over frames of relu(-y)^2 of the foot (the lower of ankle and
    toe), square metres. Heights are the same in a canonical motion as in the world (y stays up), so
    it acts on the models' tensors directly: feet may touch and leave the floor, not sink through it."""
    idx = [SKELETON.index(n) for n in FEET]
    feet = motion[..., idx, 1].amin(-1)
    return (-feet).clamp_min(0.0).pow(2).mean()
