"""Statistics that can fail: a cluster bootstrap over takes, seed variance, and the rule that decides a claim.

A table's numbers are means over items (windows of held-out takes, or window x requested action). Windows
overlap and cluster within a take, so their spread is not independent: the bootstrap resamples whole takes
(with replacement) and recomputes the metric, which gives every row, deterministic ones too, a non-zero
uncertainty. Seed variance (the std over runs = training seeds x sampling seeds of a row's mean) is added
to it: the 2-sigma bar of a difference a - b is

    2 sqrt(sd_boot(a - b)^2 + s_a^2 + s_b^2)

with sd_boot the std of the paired difference over take resamples (both rows on the same items).

A claim part "holds" only when the difference lies in the claimed direction by more than its bar (and the
bar is not zero), "fails" when it lies the other way by as much, and is "inconclusive" otherwise. "Similar
or better" parts (not_less / not_greater) need a margin: they hold when the whole 2-sigma interval lies
above -margin, fail when it lies wholly below. A comparison resting on fewer than MIN_PEOPLE held-out
people or MIN_TAKES held-out takes is "insufficient data", never "holds".
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.stats import binom

HOLDS, FAILS, INCONCLUSIVE, MISSING = "holds", "fails", "inconclusive", "not evaluated"
INSUFFICIENT = "insufficient data"
BY_CONSTRUCTION = "by construction"
UNUSABLE = "unusable"
IN_SAMPLE = "in-sample"
STATUSES = (HOLDS, FAILS, INCONCLUSIVE, INSUFFICIENT, MISSING, BY_CONSTRUCTION, UNUSABLE)

MIN_PEOPLE = 2
MIN_TAKES = 5


def summarise(values: list[float]) -> dict | None:
    """{"mean", "std", "n"} of the finite values (None when there are none); std with ddof=1."""
    v = np.asarray([x for x in values if x is not None and math.isfinite(x)], dtype=np.float64)
    if v.size == 0:
        return None
    return {"mean": float(v.mean()), "std": float(v.std(ddof=1)) if v.size > 1 else 0.0, "n": int(v.size)}


@dataclass(frozen=True)
class Units:
    """The items a table averages over: each item's take (the bootstrap's cluster), its group (the action,
    for metrics balanced over actions) and its person. Arrays of one length; takes and groups as indices."""
    take: np.ndarray
    group: np.ndarray
    person: np.ndarray

    def __len__(self) -> int:
        return len(self.take)


def units(takes: list[str], groups: list[str], people: list) -> Units:
    def index(xs):
        order = {x: i for i, x in enumerate(sorted(set(map(str, xs))))}
        return np.array([order[str(x)] for x in xs], dtype=np.int64)
    return Units(index(takes), index(groups), np.array([str(p) for p in people]))


def aggregate(values: np.ndarray, u: Units, balanced: bool = False) -> float:
    """The metric over the finite items: their mean, or (balanced) the mean over groups of each group's mean."""
    v = np.asarray(values, dtype=np.float64)
    ok = np.isfinite(v)
    if not ok.any():
        return math.nan
    if not balanced:
        return float(v[ok].mean())
    return float(np.mean([v[ok & (u.group == g)].mean() for g in np.unique(u.group[ok])]))


def bootstrap_weights(clusters: int, rounds: int, seed: int = 0) -> np.ndarray:
    """[rounds, clusters]: how often each take is drawn in each resample (clusters draws with replacement)."""
    rng = np.random.default_rng(seed)
    return rng.multinomial(clusters, np.full(clusters, 1.0 / clusters), size=rounds).astype(np.float64)


def resampled(values: np.ndarray, u: Units, weights: np.ndarray, balanced: bool = False) -> np.ndarray:
    """The metric under each take resample [rounds] (NaN where a resample holds no finite item). Items are
    summed per (take, group) once, so a resample costs one matrix product."""
    v = np.asarray(values, dtype=np.float64)
    ok = np.isfinite(v)
    takes, groups = weights.shape[1], int(u.group.max()) + 1 if len(u) else 1
    sums, counts = np.zeros((takes, groups)), np.zeros((takes, groups))
    np.add.at(sums, (u.take[ok], u.group[ok]), v[ok])
    np.add.at(counts, (u.take[ok], u.group[ok]), 1.0)
    s, n = weights @ sums, weights @ counts               # [rounds, groups]
    with np.errstate(invalid="ignore", divide="ignore"):
        if not balanced:
            return s.sum(1) / n.sum(1)
        means = np.where(n > 0, s / np.where(n > 0, n, 1.0), np.nan)
        present = (n > 0).sum(1)
        return np.where(present > 0, np.nansum(means, 1) / np.maximum(present, 1), np.nan)


def cluster_std(values: np.ndarray, u: Units, weights: np.ndarray, balanced: bool = False) -> float:
    """The std of the metric over take resamples (0 for a single take: nothing to resample)."""
    r = resampled(values, u, weights, balanced)
    r = r[np.isfinite(r)]
    return float(r.std(ddof=1)) if r.size > 1 else 0.0


def support(mask: np.ndarray, u: Units) -> tuple[int, int]:
    """(people, takes) among the items in `mask`."""
    return len(set(u.person[mask])), len(set(u.take[mask]))


DIRECTIONS = ("greater", "less", "not_less", "not_greater")


def decide(diff: float, bar: float, direction: str, margin: float = 0.0) -> str:
    """The status of a difference a - b with its 2-sigma bar, in a claimed direction (module docstring)."""
    if direction not in DIRECTIONS:
        raise ValueError(f"direction must be one of {DIRECTIONS}, got {direction!r}")
    if not (math.isfinite(diff) and math.isfinite(bar)):
        return MISSING
    signed = diff if direction in ("greater", "not_less") else -diff
    if direction.startswith("not_"):
        if not margin > 0:
            raise ValueError("a 'similar or better' comparison needs a positive margin")
        if signed - bar > -margin and bar > 0:
            return HOLDS
        return FAILS if signed + bar < -margin else INCONCLUSIVE
    if bar > 0 and signed > bar:
        return HOLDS
    return FAILS if bar > 0 and -signed > bar else INCONCLUSIVE


def compare(a: np.ndarray, b: np.ndarray, u: Units, weights: np.ndarray, seed_std_a: float, seed_std_b: float,
            direction: str, balanced: bool = False, margin: float = 0.0) -> dict:
    """Paired comparison of two rows' per-item values (run-averaged) on the items both have:
    {"status", "difference", "bar", "boot_std", "people", "takes", "items", "a_paired", "b_paired"}."""
    a, b = np.asarray(a, dtype=np.float64), np.asarray(b, dtype=np.float64)
    both = np.isfinite(a) & np.isfinite(b)
    people, takes = support(both, u)
    out = {"people": people, "takes": takes, "items": int(both.sum())}
    if not both.any():
        return {**out, "status": MISSING, "difference": None, "bar": None, "boot_std": None}
    a, b = np.where(both, a, np.nan), np.where(both, b, np.nan)
    out.update(a_paired=aggregate(a, u, balanced), b_paired=aggregate(b, u, balanced))
    diff = out["a_paired"] - out["b_paired"]
    boot = resampled(a, u, weights, balanced) - resampled(b, u, weights, balanced)
    boot = boot[np.isfinite(boot)]
    sd = float(boot.std(ddof=1)) if boot.size > 1 else 0.0
    bar = 2.0 * math.sqrt(sd ** 2 + seed_std_a ** 2 + seed_std_b ** 2)
    status = decide(diff, bar, direction, margin)
    if people < MIN_PEOPLE or takes < MIN_TAKES:
        status = INSUFFICIENT if status != MISSING else MISSING
    return {**out, "status": status, "difference": diff, "bar": bar, "boot_std": sd}


def combine(statuses: list[str]) -> str:
    """A claim made of parts: not evaluated if any part is, fails if any part fails, unusable if a part
    rests on a classifier that failed its check, insufficient data if a part has too few people or takes,
    holds if all hold, else inconclusive."""
    if not statuses or MISSING in statuses:
        return MISSING
    if FAILS in statuses:
        return FAILS
    if UNUSABLE in statuses:
        return UNUSABLE
    if INSUFFICIENT in statuses:
        return INSUFFICIENT
    return HOLDS if all(s == HOLDS for s in statuses) else INCONCLUSIVE


def binomial_band(n: int, p: float, level: float = 0.99) -> tuple[float, float]:
    """The central `level` range of the share of successes in n trials at probability p (exact binomial
    quantiles): where a classifier that guesses at chance p lands on n test snippets."""
    if n < 1 or not 0 <= p <= 1:
        raise ValueError(f"a binomial band needs n >= 1 and 0 <= p <= 1, got n = {n}, p = {p}")
    if p in (0.0, 1.0):
        return p, p
    tail = (1.0 - level) / 2.0
    return float(binom.ppf(tail, n, p) / n), float(binom.ppf(1.0 - tail, n, p) / n)
