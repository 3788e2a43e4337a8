"""The floor of a clip: estimated once per clip, never per history, so real jumps and climbs stay.

The foot is the lower of ankle and toe (either side). Contact frames are those whose lowest foot point
lies within CONTACT_BAND of the floor; the floor is the least-squares plane y = a x + b z + c through
their lowest foot points, found by a few rounds of: fit, re-select contacts. It starts from a low
percentile of the lowest foot height, never the single lowest point, so a T-pose frame or a one-frame
glitch cannot lift every other frame, and a slope (a capture volume whose floor rises 2% along a walk)
is followed instead of floating the far end. A tilt is fitted only along a principal ground axis of the
contacts that spreads over at least MIN_SPREAD metres (a walk's direction; across it the feet are only a
stride apart); otherwise the floor is level (an in-place motion says nothing about a slope).
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


def _axes(xz: np.ndarray) -> np.ndarray:
    """The principal axes of points on the ground [n, 2]: rows, the first the widest spread."""
    d = xz - xz.mean(0)
    cov = d.T @ d
    # the 2x2 symmetric eigenproblem in closed form (so TypeScript can do exactly the same)
    t = 0.5 * np.arctan2(2 * cov[0, 1], cov[0, 0] - cov[1, 1])
    u = np.array([np.cos(t), np.sin(t)])
    return np.stack([u, np.array([-u[1], u[0]])])


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
        # A tilt only along a ground axis the contacts spread over (a walk's direction); across it the
        # two feet are a stride apart and their height difference is no slope.
        axes = _axes(pts[:, [0, 2]])
        along = (pts[:, [0, 2]] - pts[:, [0, 2]].mean(0)) @ axes.T           # [n, 2]
        wide = [k for k in range(2) if np.ptp(along[:, k]) >= MIN_SPREAD]
        design = np.column_stack([along[:, wide], np.ones(len(pts))])
        fit = np.linalg.lstsq(design, pts[:, 1], rcond=None)[0]
        slope = sum((fit[i] * axes[k] for i, k in enumerate(wide)), np.zeros(2))
        if np.hypot(*slope) > MAX_SLOPE:
            slope, fit = np.zeros(2), np.array([np.median(pts[:, 1])])
        centre = pts[:, [0, 2]].mean(0)
        a, b = float(slope[0]), float(slope[1])
        c = float(fit[-1] - slope @ centre)
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
