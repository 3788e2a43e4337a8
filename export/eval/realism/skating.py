"""Foot skating: how fast a foot slides while it is on the floor (m/s). A planted foot reads ~0; captures
give 0.13-0.23 m/s (marker noise, heel-toe roll), a skating model several times that.

Per side (left, right) and per step t -> t+1 of a world-frame motion [T, J, 3] (floor y = 0): the side's
foot joint is the lower of its ankle and toe at frame t (the ankle on a tie). The step is a contact
sample when that same joint is within `band` of the floor (y < band, 3 cm: ops/floor.CONTACT_BAND) at
both t and t+1, and its value is that joint's horizontal speed |xz_{t+1} - xz_t| * fps. The same joint
at both frames, so a roll from heel to toe is not read as a slide of the ankle-to-toe distance; both
frames in contact, so a foot touching down or lifting off is not measured mid-air. World positions, not
root-relative: a planted foot stands still in the world while the body passes over it.

The samples come back as an array (left then right, each in time order) so callers pool them over
windows before taking a median (median_contact_speed); a mean would follow the rare fast outliers.
Foot skating is a usual realism measure of motion synthesis (e.g. Karunratanakul et al., "Guided Motion
Diffusion for Controllable Human Motion Synthesis", ICCV 2023, a share of skidding frames); the 3 cm band,
the lower of ankle and toe, and the median speed are this project's choices.

TypeScript twin: web/src/metrics/realism.ts contactSpeeds, footSkating (the median per sample).
"""
from __future__ import annotations

import numpy as np

from ...data.skeleton import SKELETON, Skeleton
from ...ops.floor import CONTACT_BAND

FPS = 30
SIDES = (("left_ankle", "left_toe"), ("right_ankle", "right_toe"))


def contact_speeds(motion: np.ndarray, fps: int = FPS, band: float = CONTACT_BAND,
                   skeleton: Skeleton = SKELETON) -> np.ndarray:
    """The horizontal speeds (m/s) of every foot-contact step of a world motion [T, J, 3], both sides: [n].
    TypeScript twin: realism.ts contactSpeeds."""
    m = np.asarray(motion, dtype=np.float64)
    out = []
    for names in SIDES:
        feet = m[:, [skeleton.index(n) for n in names]]            # [T, 2, 3]: ankle, toe
        lower = feet[:, :, 1].argmin(1)                             # argmin keeps the first (ankle) on a tie
        t = np.arange(len(m) - 1)
        joint_now, joint_next = feet[t, lower[:-1]], feet[t + 1, lower[:-1]]   # the joint chosen at t, at t and t+1
        contact = (joint_now[:, 1] < band) & (joint_next[:, 1] < band)
        out.append(np.linalg.norm((joint_next - joint_now)[contact][:, [0, 2]], axis=-1) * fps)
    return np.concatenate(out)


def median_contact_speed(speeds: np.ndarray) -> float:
    """The median of pooled contact speeds (m/s); NaN when no step touched the floor. TypeScript twins:
    realism.ts medianContactSpeed, and footSkating for the median of each of K samples."""
    s = np.asarray(speeds, dtype=np.float64).ravel()
    return float(np.median(s)) if s.size else float("nan")
