"""The root channel for Keyposes: how far the body travels while it moves between keyposes.

Keyposes predicts root-relative poses (keypose extraction, k-means and interpolation act on them,
export/ops/facing.py), and its centres face +z with no heading, so the predicted body keeps facing
+z in the history's canonical frame. The root channel is predicted per segment: a segment that
leads to a keypose of cluster c moves the root by table[c] per frame, where table[c] is the mean
root velocity, in the body's own facing frame, of the training frames of segments that lead to a
keypose labelled c (clusters never reached keep the mean over all segments). A walk's keyposes thus
carry the walker forward at its training pace, a jump's carry it as far as training jumps went.

The pace follows the history (`pace`): the table's velocities are scaled by the history's own root speed
over the table speed of the history's own keypose labels, so a fast walker keeps walking fast and a
standing dancer stays where she is (with one table pace, every future moved at about 1.05 m/s whatever
the history: 1.02-1.74 m/s walks, a 2.04 m/s run).
TypeScript twins: `travel` and `pace` in web/src/sampling/keyposes.ts.
"""
from __future__ import annotations

import numpy as np

from ..data.skeleton import SKELETON, Skeleton
from .facing import facing_angle, root_channel, rotate_about_y


def facing_velocities(motion: np.ndarray, skeleton: Skeleton = SKELETON) -> np.ndarray:
    """A motion that carries the root channel [F, J, 3] -> [F - 1, 2]: the root's step into each frame,
    turned into the body's facing frame at that frame (x sideways, z forward)."""
    steps = np.diff(root_channel(motion), axis=0)
    out = np.empty_like(steps)
    for f, (dx, dz) in enumerate(steps):
        v = rotate_about_y(np.array([dx, 0.0, dz]), -facing_angle(motion[f + 1], skeleton))
        out[f] = v[[0, 2]]
    return out


def velocity_table(segments: list[tuple[int, np.ndarray]], clusters: int) -> np.ndarray:
    """(label of the keypose a segment leads to, its facing-frame steps [n, 2]) -> table [clusters, 2]."""
    sums, counts = np.zeros((clusters, 2)), np.zeros(clusters)
    for label, steps in segments:
        sums[label] += steps.sum(0)
        counts[label] += len(steps)
    overall = sums.sum(0) / max(counts.sum(), 1)
    table = np.where(counts[:, None] > 0, sums / np.maximum(counts, 1)[:, None], overall)
    return np.round(table, 6)


PACE_RANGE = (0.25, 4.0)       # the history's pace within this factor of the table's
PACE_FLOOR = 1e-3              # metres per frame (3 cm/s): a table speed below it sets no pace


def pace(history_root: np.ndarray, observed: list[int], table: np.ndarray) -> float:
    """The factor on the table's velocities for a history: its root's mean speed per frame over its
    frames [N, 2] (the root channel's x and z), over the mean table speed of its observed keypose labels;
    1 where those labels barely travel, clipped to PACE_RANGE."""
    steps = np.linalg.norm(np.diff(np.asarray(history_root, dtype=np.float64), axis=0), axis=-1)
    mine = float(steps.mean()) if len(steps) else 0.0
    theirs = float(np.linalg.norm(np.asarray(table, dtype=np.float64)[observed], axis=-1).mean()) if observed else 0.0
    if theirs < PACE_FLOOR:
        return 1.0
    return float(np.clip(mine / theirs, *PACE_RANGE))


def travel(labels: list[int], durations: list[int], table: np.ndarray, frames: int, scale: float = 1.0) -> np.ndarray:
    """The root channel [frames, 2] of a sampled future: frame t (1-based) lies in the segment whose
    keypose it moves towards and adds that keypose's table velocity (times `scale`, the history's pace);
    past the last keypose it holds."""
    steps = np.zeros((frames, 2))
    t = 0
    for label, d in zip(labels, durations):
        steps[t:t + d] = np.asarray(table[label]) * scale
        t += d
        if t >= frames:
            break
    return np.cumsum(steps, axis=0)
