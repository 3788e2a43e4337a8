"""WAT's weakly-supervised transitions (section 3.2, supplement 6 and 9): action instances and pairs.

An action instance is a non-looping clip's training part, or one loop cycle (any phase) of a
looping clip that may be repeated. A *cross* pair puts an instance of one action after a history of
another, T0 = floor(k ||x_N - y'_1||) unsupervised transition frames in between (capped); a
*same* pair continues a history with its own clip (T0 = 0). Everything is cut from training
ranges only (through the split's ranges and the loop repeat that `windows()` uses).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import dataclasses

import numpy as np

from ..data.clip import Clip
from ..data.skeleton import SKELETON
from ..data.windows import _repeatable, windows  # the split's rule for which loops may wrap
from .facing import canonicalise, root_relative, split_root
from .mirror import mirror_positions


def cached_repeats(clip: Clip) -> Clip:
    """The clip with its loop repeat memoised (a repeat re-runs forward kinematics; we ask several times)."""
    if clip.repeat is None:
        return clip
    cache: dict[int, np.ndarray] = {}

    def repeat(cycles: int) -> np.ndarray:
        if cycles not in cache:
            cache[cycles] = clip.repeat(cycles)
        return cache[cycles]
    return dataclasses.replace(clip, repeat=repeat)


# An instance "ends" (Eq. 7's padding applies after it) only where the person stops: a CMU take ends at
# the edge of the capture volume, mid-stride. Counted on the v2 training takes, the mean joint speed of
# the last 0.5 s is below REST_SPEED in 27% of walks, 54% of jumps, 20% of dances and 3% of runs; the
# rest were cut while moving, and padding them with their last pose taught every model to stop.
REST_SECONDS = 0.5
REST_SPEED = 0.15          # m/s, mean over joints (world frame): slower than any gait, faster than idling


def ends_at_rest(positions: np.ndarray, fps: float) -> bool:
    """Whether a motion [F, J, 3] ends with the person at rest (the last REST_SECONDS below REST_SPEED)."""
    tail = np.asarray(positions, dtype=np.float64)[-(int(round(REST_SECONDS * fps)) + 1):]
    if len(tail) < 2:
        return True
    return bool(np.linalg.norm(np.diff(tail, axis=0), axis=-1).mean() * fps < REST_SPEED)


def loop_period(clip: Clip) -> int | None:
    """Cycle length of a loop whose training part may be repeated, else None (an instance is the part)."""
    return len(clip) if _repeatable(clip, "train") else None


def transition_rate(clips: list[Clip], statistic: str = "median") -> float:
    """k of supplement Eq. 3: frames per metre of pose change, |i - j| / ||x_i - x_j|| over the frame
    pairs of each clip's training part.

    In a loop, phases i and j are min(|i - j|, period - |i - j|) frames apart: pairs almost a period
    apart are almost the same pose (||x_i - x_j|| ~ 0) and would count as far apart in time, so the
    time between two phases is measured the short way round the loop, always less than one period.
    Eq. 3 takes the mean; the ratio is heavy-tailed (near-static pairs), so the median is the default
    (measured here: mean 14.0, median 11.6 frames per metre).
    """
    ratios = []
    for clip in clips:
        period = loop_period(clip)
        for a, b in clip.split.train:
            x = root_relative(split_root(clip.positions[a:b])).reshape(b - a, -1)   # poses, not travel
            i, j = np.triu_indices(b - a, 1)
            frames = j - i
            if period:
                frames = np.minimum(frames, period - frames)
            dist = np.linalg.norm(x[i] - x[j], axis=1)
            ok = dist > 1e-9
            ratios.append(frames[ok] / dist[ok])
    r = np.concatenate(ratios)
    if statistic == "median":
        return float(np.median(r))
    if statistic == "mean":
        return float(r.mean())
    raise ValueError(f"statistic must be 'median' or 'mean', got {statistic!r}")


def transition_frames(x_last: np.ndarray, y_first: np.ndarray, k: float, cap: int) -> int:
    """T0 = min(floor(k ||x_N - y'_1||_2), cap) (supplement Eq. 2) for two poses [J, 3] in one frame."""
    d = float(np.linalg.norm(np.asarray(x_last, np.float64) - np.asarray(y_first, np.float64)))
    return int(min(np.floor(k * d), cap))


@dataclass
class Bank:
    """Histories and instances as arrays, and the pairs that join them (indices into both)."""
    histories: np.ndarray            # [H, N, J, 3] float32, facing +z at the last frame
    history_action: np.ndarray       # [H] action index
    instances: np.ndarray            # [I, S, J, 3] float32, the first S frames of each instance
    instance_length: np.ndarray      # [I] full instance length (may exceed S)
    instance_action: np.ndarray      # [I]
    pair_history: np.ndarray         # [P]
    pair_instance: np.ndarray        # [P]
    pair_t0: np.ndarray              # [P] transition frames (0 for same pairs)
    pair_same: np.ndarray            # [P] bool
    instance_person: np.ndarray = field(default_factory=lambda: np.zeros(0))  # [I] the instance clip's person
    instance_open: np.ndarray = field(default_factory=lambda: np.zeros(0, bool))  # [I] its end is no motion end
    uncapped_t0: np.ndarray = field(default_factory=lambda: np.zeros(0))  # cross pairs, before the cap


def _mirror_variants(seq: np.ndarray, at: int, mirror: bool) -> list[np.ndarray]:
    out = [canonicalise(seq, at, SKELETON)[0]]
    if mirror:  # mirror first, then face +z again (as windows() does)
        out.append(canonicalise(mirror_positions(seq, SKELETON), at, SKELETON)[0])
    return out


def continuations(clip: Clip, n: int, min_future: int, mirror: bool, store: int | None = None
                  ) -> list[tuple[np.ndarray, np.ndarray, int]]:
    """Same pairs of one clip: (history [n, J, 3], its own continuation [T, J, 3], T) in the history's frame.

    A repeatable loop continues for one cycle after every phase; any other clip continues to the end
    of its training part (histories leaving fewer than `min_future` frames are skipped). With `store`,
    only the continuation's first `store` frames are kept (and turned), its full length T still given:
    a 30 s take would otherwise hold every start's whole remainder, quadratic in the take's length.
    """
    period = loop_period(clip)
    if period:
        return [(w.positions[:n], w.positions[n:n + store] if store else w.positions[n:], period)
                for w in windows([clip], "train", n + period, n, mirror=mirror)]
    out = []
    for a, b in clip.split.train:
        for s in range(a + n, b - min_future + 1):
            end = b if store is None else min(b, s + store)
            for seq in _mirror_variants(clip.positions[s - n:end], n - 1, mirror):
                out.append((seq[:n], seq[n:], b - s))
    return out


def instance_starts(clip: Clip, start_search: int, mirror: bool) -> list[tuple[tuple[int, int, bool], np.ndarray]]:
    """Cross-pair instances of one clip, each facing +z at its own first frame: ((group, start, mirrored), frames).

    A repeatable loop gives one instance per phase p (a cycle starting there; group p, start 0); any
    other clip gives each training part r started at each of its first `start_search` frames (group r).
    A pair picks, among a few candidate starts, the one nearest x_N (the official code's trick,
    which shortens T0): phases p..p+S-1 of a loop, or the S starts of a part.
    """
    period = loop_period(clip)
    out = []
    if period:
        seq = clip.repeat(4)  # phase + a full cycle fits; 4 is also what windows() asks for one cycle ahead
        for p in range(period):
            for m, frames in enumerate(_mirror_variants(seq[p:p + period], 0, mirror)):
                out.append(((p, 0, bool(m)), frames))
        return out
    for r, (a, b) in enumerate(clip.split.train):
        for s in range(min(start_search, b - a - 1)):
            for m, frames in enumerate(_mirror_variants(clip.positions[a + s:b], 0, mirror)):
                out.append(((r, s, bool(m)), frames))
    return out


def build_bank(clips: list[Clip], actions: list[str], n: int, store: int, k: float, t0_cap: int,
               start_search: int, same_copies: int, weak: bool, mirror: bool, min_future: int,
               seed: int, cross_per_history: int | None = None) -> Bank:
    """Every training history, every instance, and the pairs: `same_copies` same pairs per history and,
    when `weak`, cross pairs with other actions (random clip of the action, phase / mirror, nearest
    start, capped T0): one per other action, or `cross_per_history` other actions drawn at random.

    With many actions (24 in the default data) one pair per other action would make 23 cross pairs per
    history against 4 same ones; drawing a few keeps continuing an action as much of the training as
    switching to another, while every action is still paired with every other across the bank."""
    rng = np.random.default_rng(seed)
    train = [cached_repeats(c) for c in clips if c.split.train]
    hist, hist_act, inst, inst_len, inst_act, inst_person, inst_open = [], [], [], [], [], [], []
    # A loop never ends; another clip's instances end where its training part ends, which is a motion
    # end only when the person is at rest there (ends_at_rest).
    open_end = {c.name: bool(loop_period(c)) or not ends_at_rest(c.positions[:c.split.train[-1][1]], c.fps)
                for c in train}

    def add_instance(frames: np.ndarray, action: int, clip: Clip, length: int | None = None) -> int:
        stored = np.repeat(frames[-1:], store, axis=0)
        stored[:min(store, len(frames))] = frames[:store]
        inst.append(stored.astype(np.float32))
        inst_len.append(len(frames) if length is None else length)
        inst_act.append(action)
        inst_person.append(str(clip.subject))
        inst_open.append(open_end[clip.name])
        return len(inst) - 1

    pair_h, pair_i, pair_t0, pair_same = [], [], [], []
    for clip in train:
        a = actions.index(clip.action)
        for h, future, length in continuations(clip, n, min_future, mirror, store):
            hist.append(h.astype(np.float32))
            hist_act.append(a)
            i = add_instance(future, a, clip, length)
            for _ in range(same_copies):
                pair_h.append(len(hist) - 1), pair_i.append(i), pair_t0.append(0), pair_same.append(True)

    uncapped = []
    if weak:
        x_last = np.stack(hist)[:, -1].reshape(len(hist), -1).astype(np.float64)
        by_action: dict[int, list[tuple[Clip, dict, dict]]] = {}
        for clip in train:
            a = actions.index(clip.action)
            ids = {key: add_instance(frames, a, clip) for key, frames in instance_starts(clip, start_search, mirror)}
            first = {i: inst[i][0].reshape(-1).astype(np.float64) for i in ids.values()}
            by_action.setdefault(a, []).append((clip, ids, first))
        for hi in range(len(hist)):
            others = sorted(a for a in by_action if a != hist_act[hi])
            if cross_per_history is not None and cross_per_history < len(others):
                others = sorted(rng.choice(others, size=cross_per_history, replace=False).tolist())
            for a in others:
                clip, ids, first = by_action[a][int(rng.integers(len(by_action[a])))]
                m = bool(rng.integers(2)) if mirror else False
                period = loop_period(clip)
                if period:
                    p = int(rng.integers(period))
                    cand = [ids[((p + s) % period, 0, m)] for s in range(start_search)]
                else:
                    r = int(rng.integers(len(clip.split.train)))
                    cand = [i for (g, _, mm), i in ids.items() if g == r and mm == m]
                # ||x_N - y'_1|| for the few candidate starts only (all pairings would not fit in memory)
                dist = np.linalg.norm(np.stack([first[i] for i in cand]) - x_last[hi], axis=1)
                best = cand[int(np.argmin(dist))]
                uncapped.append(int(np.floor(k * dist.min())))
                pair_h.append(hi), pair_i.append(best)
                pair_t0.append(min(uncapped[-1], t0_cap)), pair_same.append(False)

    return Bank(np.stack(hist), np.asarray(hist_act), np.stack(inst), np.asarray(inst_len), np.asarray(inst_act),
                np.asarray(pair_h), np.asarray(pair_i), np.asarray(pair_t0), np.asarray(pair_same),
                np.asarray(inst_person), np.asarray(inst_open, dtype=bool), np.asarray(uncapped))
