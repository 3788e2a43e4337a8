"""Deterministic baselines to read the learned methods against, as pure functions on world-frame motions.

- constant_velocity: every joint keeps its last velocity (the "does it just drift on?" floor);
- repeat_last_cycle: the history's best period, repeated (a walk keeps walking, a dance keeps dancing);
- nearest_window: the future of the most similar training history (a lookup, no learning).

Histories are [N, J, 3] metres, y up, world frame (clips keep the horizontal root travel; joint 0 is
the root); a baseline's future is [frames, J, 3] in the same frame, starting the frame after the history.
"""
from __future__ import annotations

import numpy as np

from ..data.skeleton import SKELETON
from ..ops.facing import canonicalise, place
from ..ops.facing import root_relative as facing_root_relative
from .metrics import root_relative

PERIOD_TIE = 1e-9   # metres: periods fitting this close to the best count as ties, the shortest wins


def constant_velocity(history: np.ndarray, frames: int) -> np.ndarray:
    """x_{N+t} = x_N + t (x_N - x_{N-1}) for t = 1..frames, every joint on its own (float64)."""
    h = np.asarray(history, dtype=np.float64)
    if len(h) < 2:
        raise ValueError("constant velocity needs at least two history frames")
    step = h[-1] - h[-2]
    return h[-1] + np.arange(1, frames + 1)[:, None, None] * step


def cycle_costs(history: np.ndarray, min_period: int = 8) -> dict[int, float]:
    """Each candidate period p (min_period..N//2) -> the mean whole-pose distance (root-relative, metres)
    between the last p frames and the p frames before them: 0 for a motion that repeats every p."""
    rel = root_relative(history).reshape(len(history), -1)
    n = len(rel)
    return {p: float(np.linalg.norm(rel[n - p:] - rel[n - 2 * p:n - p], axis=1).mean())
            for p in range(min_period, n // 2 + 1)}


def best_period(history: np.ndarray, min_period: int = 8) -> int | None:
    """The period with the lowest cycle cost, or None when the history is shorter than 2 x min_period.
    Whole multiples of the true period fit as well, so ties (within PERIOD_TIE) go to the shortest."""
    costs = cycle_costs(history, min_period)
    if not costs:
        return None
    best = min(costs.values())
    return min(p for p, c in costs.items() if c <= best + PERIOD_TIE)


def repeat_last_cycle(history: np.ndarray, frames: int, min_period: int = 8) -> np.ndarray:
    """The history's last cycle (best_period frames) repeated for `frames` frames.

    Repeat r (r = 1, 2, ...) of the cycle frames is shifted horizontally by r times the root's
    horizontal travel over the last cycle, so a walk keeps walking instead of stepping back. The
    height is not shifted. A history shorter than 2 x min_period has no period to trust: the last pose
    is held instead.
    """
    h = np.asarray(history, dtype=np.float64)
    p = best_period(h, min_period)
    if p is None:
        return np.repeat(h[-1:], frames, axis=0)
    travel = np.zeros(3)
    travel[[0, 2]] = h[-1, 0, [0, 2]] - h[-1 - p, 0, [0, 2]]
    t = np.arange(frames)
    return h[len(h) - p + t % p] + (t // p + 1)[:, None, None] * travel


# No canonical round trip of our own: ops/facing.py's canonicalise() turns a window to face +z, moves its
# root above the origin and returns a Placement, and place() undoes both (an earlier facing.py only
# turned, about the world origin). Its canonical windows, data/windows.py's too, are the models' tensors:
# root-relative poses, with the root's horizontal travel (the root channel) in the root joint's x and z.
# So poses are compared with facing.root_relative (drop the channel), not metrics.root_relative, which
# is for world positions.
def nearest_index(canonical_history: np.ndarray, train_histories: np.ndarray) -> int:
    """The training window whose history is closest to the query: L2 over the whole sequence of
    root-relative poses (N*J*3 numbers, the root channel left out). All histories are canonical
    (ops/facing.canonicalise at their last frame); ties go to the first."""
    train = np.asarray(train_histories, dtype=np.float64)
    if train.shape[1:] != np.shape(canonical_history):
        raise ValueError(f"the training histories are {train.shape[1:]}, the query {np.shape(canonical_history)}")
    q = facing_root_relative(canonical_history).reshape(-1)
    d = np.linalg.norm(facing_root_relative(train).reshape(len(train), -1) - q, axis=1)
    return int(np.argmin(d))


def nearest_window(history: np.ndarray, train_histories: np.ndarray, train_futures: np.ndarray) -> np.ndarray:
    """The future of the nearest training window (nearest_index), placed where the query history stands:
    the query is canonicalised at its last frame, and the chosen canonical future [T, J, 3], whose root
    channel starts from that frame, is turned back and moved onto the query's last root (facing.place)."""
    canonical, placement = canonicalise(np.asarray(history, dtype=np.float64), len(history) - 1, SKELETON)
    return place(np.asarray(train_futures)[nearest_index(canonical, train_histories)], placement)


def nearest_indices(canonical_histories: np.ndarray, train_histories: np.ndarray, chunk: int = 256) -> np.ndarray:
    """nearest_index for many queries at once [Q, N, J, 3] -> [Q]: the same distance (L2 over the whole
    root-relative history), computed as |q|^2 + |t|^2 - 2 q.t in chunks of queries, so a bank of tens of
    thousands of training windows is searched in one matrix product per chunk. Ties go to the first."""
    q = facing_root_relative(np.asarray(canonical_histories, dtype=np.float64))
    t = facing_root_relative(np.asarray(train_histories, dtype=np.float64))
    if t.shape[1:] != q.shape[1:]:
        raise ValueError(f"the training histories are {t.shape[1:]}, the queries {q.shape[1:]}")
    q, t = q.reshape(len(q), -1), t.reshape(len(t), -1)
    tt = (t * t).sum(1)
    out = np.empty(len(q), dtype=np.int64)
    for a in range(0, len(q), chunk):
        part = q[a:a + chunk]
        d = tt[None] - 2.0 * part @ t.T + (part * part).sum(1)[:, None]   # squared distances
        out[a:a + chunk] = np.argmin(d, axis=1)
    return out
