"""Statistics that can fail: a two-level cluster bootstrap (people, then takes), seed variance, the practical
minimum, trends, Holm's correction, and the rule that decides a claim.

A table's numbers are means over items (windows of held-out takes, or window x requested action). Windows
overlap and cluster within a take, and takes cluster within a person (two people can supply most of a table's
windows), so the items are not independent. The bootstrap resamples at both levels: the held-out people with
replacement, then, within each drawn person, that person's takes with replacement; the metric is recomputed on
the drawn takes. A resample is one weight per take (how often it was drawn), so it costs one matrix product
(`resampled`), and every row, deterministic ones too, gets a non-zero uncertainty. Resampling both levels with
replacement errs on the wide side: where people do not differ at all it inflates the variance by about
(2 - 1/P - 1/n) against resampling takes alone (P people of n takes each), so it errs against "holds".
Seed variance (the std over runs = training seeds x sampling seeds of a row's mean) is added to it: the
2-sigma bar of a difference a - b is

    2 sigma,  sigma = sqrt(sd_boot(a - b)^2 + s_a^2 + s_b^2)

with sd_boot the std of the paired difference over the resamples (both rows on the same items).

A claim part "holds" only when the difference lies in the claimed direction by more than its bar (and the
bar is not zero), "fails" when it lies the other way by as much, and is "inconclusive" otherwise. "Similar
or better" parts (not_less / not_greater) need a margin: they hold when the whole 2-sigma interval lies
above -margin, fail when it lies wholly below. Before the bar, in this order:

- identical predictions (the difference exactly 0 on every item, or |difference| < 1e-9) are "no difference"
  whatever the bar or the support;
- a comparison resting on fewer than MIN_PEOPLE held-out people or MIN_TAKES held-out takes, among the items
  both compared rows have (every row, for a trend), is "insufficient data", never "holds";
- a difference smaller than the practical minimum is "no difference", never "holds" or "fails": for metres
  1 mm or 1% of the baseline's value (row b, the reference), whichever is larger (for millimetres likewise
  1 mm or 1%); for % metrics 1 point; for other units 1% of the baseline.
The identity and practical-minimum rules apply to directional parts (greater / less): a "similar or better"
part's margin is its own tolerance.

A trend over settings (rows that differ in one setting, in the setting's order) is one contrast, not
consecutive pairs: the least-squares slope of the metric against the settings' rank (0, 1, ..., n-1; the rank,
not the value, so no setting leans on the fit by its spacing), times the range n - 1: the fitted change from the
first setting to the last. It is a linear combination of the rows, so its bootstrap, seed variance, bar and
status follow the pair's rules with the rows' coefficients; a pair is the trend of two settings.

Each counted comparison has a one-sided p-value, the normal approximation p = 1 - Phi(z) with
z = (signed difference + margin) / sigma (signed: positive in the claimed direction; margin 0 unless
"similar or better"), 1 when sigma is 0. A family of comparisons is corrected by Holm's step-down at
family-wise alpha ALPHA (`holm`): a part holds only if it passes both its 2-sigma bar and Holm.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.stats import binom, norm

HOLDS, FAILS, INCONCLUSIVE, MISSING = "holds", "fails", "inconclusive", "not evaluated"
NO_DIFFERENCE = "no difference"
INSUFFICIENT = "insufficient data"
BY_CONSTRUCTION = "by construction"
UNUSABLE = "unusable"
IN_SAMPLE = "in-sample"
STATUSES = (HOLDS, FAILS, INCONCLUSIVE, NO_DIFFERENCE, INSUFFICIENT, MISSING, BY_CONSTRUCTION, UNUSABLE)

MIN_PEOPLE = 3
MIN_TAKES = 8
ALPHA = 0.05               # family-wise, for Holm
IDENTICAL = 1e-9           # |difference| below this is float noise between identical predictions
CORRECTION = f"Holm's step-down, family-wise alpha {ALPHA}; one-sided p = 1 - Phi(z) with z the signed " \
             "difference (plus the margin of a 'similar or better' part) over sigma = sqrt(sd_boot^2 + s_a^2 + s_b^2)"


def summarise(values: list[float]) -> dict | None:
    """{"mean", "std", "n"} of the finite values (None when there are none); std with ddof=1."""
    v = np.asarray([x for x in values if x is not None and math.isfinite(x)], dtype=np.float64)
    if v.size == 0:
        return None
    return {"mean": float(v.mean()), "std": float(v.std(ddof=1)) if v.size > 1 else 0.0, "n": int(v.size)}


@dataclass(frozen=True)
class Units:
    """The items a table averages over: each item's take (the bootstrap's inner cluster), its group (the action,
    for metrics balanced over actions) and its person (the outer cluster). Arrays of one length; takes and
    groups as indices."""
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


def take_people(u: Units) -> np.ndarray:
    """[takes]: each take's person, as an index (a take belongs to one person)."""
    people, person = np.unique(u.person, return_inverse=True)
    takes = int(u.take.max()) + 1 if len(u) else 0
    out = np.full(takes, -1, dtype=np.int64)
    out[u.take] = person
    if len(u) and (out[u.take] != person).any():
        raise ValueError("a take belongs to more than one person")
    return out


def aggregate(values: np.ndarray, u: Units, balanced: bool = False) -> float:
    """The metric over the finite items: their mean, or (balanced) the mean over groups of each group's mean."""
    v = np.asarray(values, dtype=np.float64)
    ok = np.isfinite(v)
    if not ok.any():
        return math.nan
    if not balanced:
        return float(v[ok].mean())
    return float(np.mean([v[ok & (u.group == g)].mean() for g in np.unique(u.group[ok])]))


def bootstrap_weights(take_person: np.ndarray | int, rounds: int, seed: int = 0) -> np.ndarray:
    """[rounds, takes]: how often each take is drawn in each two-level resample. `take_person` gives each take's
    person (take_people); an int n stands for n takes of n different people, which is the one-level bootstrap
    over takes. A person drawn c times contributes c x (its take count) draws among its own takes: c independent
    draws of its takes with replacement add up to one multinomial of that size."""
    tp = np.arange(take_person) if isinstance(take_person, (int, np.integer)) else np.asarray(take_person)
    rng = np.random.default_rng(seed)
    out = np.zeros((rounds, len(tp)))
    people = np.unique(tp)
    if not len(people):
        return out
    drawn = rng.multinomial(len(people), np.full(len(people), 1.0 / len(people)), size=rounds)   # [rounds, people]
    for j, p in enumerate(people):
        own = np.flatnonzero(tp == p)
        out[:, own] = rng.multinomial(drawn[:, j] * len(own), np.full(len(own), 1.0 / len(own)))
    return out


def resampled(values: np.ndarray, u: Units, weights: np.ndarray, balanced: bool = False) -> np.ndarray:
    """The metric under each resample [rounds] (NaN where a resample holds no finite item). Items are summed per
    (take, group) once, so a resample costs one matrix product."""
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


def _finite_std(x: np.ndarray) -> float:
    x = x[np.isfinite(x)]
    return float(x.std(ddof=1)) if x.size > 1 else 0.0


def cluster_std(values: np.ndarray, u: Units, weights: np.ndarray, balanced: bool = False) -> float:
    """The std of the metric over the resamples (0 for a single take: nothing to resample)."""
    return _finite_std(resampled(values, u, weights, balanced))


def support(mask: np.ndarray, u: Units) -> tuple[int, int]:
    """(people, takes) among the items in `mask`."""
    return len(set(u.person[mask])), len(set(u.take[mask]))


def practical_minimum(unit: str, baseline: float) -> float:
    """The smallest difference that counts, against the baseline's (row b's) value (module docstring)."""
    rel = 0.01 * abs(baseline) if math.isfinite(baseline) else 0.0
    if unit == "%":
        return 1.0
    if unit == "m":
        return max(0.001, rel)
    if unit == "mm":
        return max(1.0, rel)
    return rel


DIRECTIONS = ("greater", "less", "not_less", "not_greater")


def _signed(diff: float, direction: str) -> float:
    """The difference, positive in the claimed direction."""
    if direction not in DIRECTIONS:
        raise ValueError(f"direction must be one of {DIRECTIONS}, got {direction!r}")
    return diff if direction in ("greater", "not_less") else -diff


def decide(diff: float, bar: float, direction: str, margin: float = 0.0) -> str:
    """The status of a difference a - b with its 2-sigma bar, in a claimed direction (module docstring)."""
    signed = _signed(diff, direction)
    if not (math.isfinite(diff) and math.isfinite(bar)):
        return MISSING
    if direction.startswith("not_"):
        if not margin > 0:
            raise ValueError("a 'similar or better' comparison needs a positive margin")
        if signed - bar > -margin and bar > 0:
            return HOLDS
        return FAILS if signed + bar < -margin else INCONCLUSIVE
    if bar > 0 and signed > bar:
        return HOLDS
    return FAILS if bar > 0 and -signed > bar else INCONCLUSIVE


def judge(diff: float, bar: float, direction: str, margin: float, minimum: float, identical: bool,
          people: int, takes: int) -> tuple[str, str]:
    """(status, reason) of a difference: identity, support and the practical minimum before the bar (module
    docstring); the reason is empty when the bar decides."""
    if not (math.isfinite(diff) and math.isfinite(bar)):
        return MISSING, ""
    directional = not direction.startswith("not_")
    if directional and identical:
        return NO_DIFFERENCE, "identical predictions"
    if people < MIN_PEOPLE or takes < MIN_TAKES:
        return INSUFFICIENT, (f"{people} people and {takes} takes; holds needs at least {MIN_PEOPLE} people and "
                              f"{MIN_TAKES} takes")
    if directional and abs(diff) < minimum:
        return NO_DIFFERENCE, f"the difference is below the practical minimum {minimum:.3g}"
    return decide(diff, bar, direction, margin), ""


def p_value(diff: float, sigma: float, direction: str, margin: float = 0.0) -> float:
    """One-sided p of the claimed direction, normal approximation: 1 - Phi((signed diff + margin) / sigma);
    1 when sigma is 0 (no spread, no evidence)."""
    z = _signed(diff, direction) + (margin if direction.startswith("not_") else 0.0)
    return float(norm.sf(z / sigma)) if sigma > 0 and math.isfinite(sigma) else 1.0


def holm(p: list[float]) -> np.ndarray:
    """Holm's step-down adjusted p-values, in the given order: sorted ascending, the k-th smallest (k = 0, 1, ...)
    times (m - k), made non-decreasing (running max) and capped at 1. Rejecting where the adjusted p <= alpha is
    the step-down: reject the smallest while p_(k) <= alpha / (m - k), stop at the first that is not."""
    p = np.asarray(p, dtype=np.float64)
    m = len(p)
    order = np.argsort(p, kind="stable")
    adj = np.minimum(1.0, np.maximum.accumulate((m - np.arange(m)) * p[order]))
    out = np.empty(m)
    out[order] = adj
    return out


def _contrast(series: list[np.ndarray], coef: np.ndarray, u: Units, weights: np.ndarray, seed_stds: list[float],
              balanced: bool) -> tuple[np.ndarray, list[float], float, float, float]:
    """A paired linear combination sum_i coef_i row_i on the items every row has: (mask, each row's paired value,
    the estimate, its bootstrap std, sigma with the seed variances)."""
    rows = [np.asarray(s, dtype=np.float64) for s in series]
    both = np.logical_and.reduce([np.isfinite(r) for r in rows])
    rows = [np.where(both, r, np.nan) for r in rows]
    paired = [aggregate(r, u, balanced) for r in rows]
    estimate = float(np.dot(coef, paired))
    sd = _finite_std(sum(c * resampled(r, u, weights, balanced) for c, r in zip(coef, rows)))
    sigma = math.sqrt(sd ** 2 + sum((c * s) ** 2 for c, s in zip(coef, seed_stds)))
    return both, paired, estimate, sd, sigma


def compare(a: np.ndarray, b: np.ndarray, u: Units, weights: np.ndarray, seed_std_a: float, seed_std_b: float,
            direction: str, balanced: bool = False, margin: float = 0.0, unit: str = "") -> dict:
    """Paired comparison of two rows' per-item values (run-averaged) on the items both have:
    {"status", "difference", "bar", "boot_std", "p", "minimum", "people", "takes", "items", "a_paired",
    "b_paired"} and a "reason" when identity, support or the practical minimum decided."""
    a, b = np.asarray(a, dtype=np.float64), np.asarray(b, dtype=np.float64)
    both = np.isfinite(a) & np.isfinite(b)
    people, takes = support(both, u)
    out = {"people": people, "takes": takes, "items": int(both.sum())}
    if not both.any():
        return {**out, "status": MISSING, "difference": None, "bar": None, "boot_std": None, "p": None}
    _, (ap, bp), diff, sd, sigma = _contrast([a, b], np.array([1.0, -1.0]), u, weights, [seed_std_a, seed_std_b],
                                             balanced)
    identical = bool((a[both] == b[both]).all()) or abs(diff) < IDENTICAL
    minimum = practical_minimum(unit, bp)
    status, reason = judge(diff, 2.0 * sigma, direction, margin, minimum, identical, people, takes)
    return {**out, "a_paired": ap, "b_paired": bp, "status": status, "difference": diff, "bar": 2.0 * sigma,
            "boot_std": sd, "p": p_value(diff, sigma, direction, margin), "minimum": minimum,
            **({"reason": reason} if reason else {})}


def trend(series: list[np.ndarray], u: Units, weights: np.ndarray, seed_stds: list[float], direction: str,
          balanced: bool = False, unit: str = "") -> dict:
    """A trend over rows in their settings' order, on the items every row has: the least-squares slope against
    the rank, and the fitted change over the range (slope x (n - 1)), whose bar and status follow the pair's rules
    with the first setting as the baseline: {"status", "slope", "difference" (the change), "bar", "boot_std", "p",
    "minimum", "values" (each row's paired value), "people", "takes", "items"}."""
    if direction not in ("greater", "less"):
        raise ValueError(f"a trend rises ('greater') or falls ('less'), got {direction!r}")
    n = len(series)
    if n < 2:
        raise ValueError("a trend needs at least two settings")
    rank = np.arange(n, dtype=np.float64) - (n - 1) / 2
    slope_coef = rank / (rank ** 2).sum()
    both = np.logical_and.reduce([np.isfinite(np.asarray(s, dtype=np.float64)) for s in series])
    people, takes = support(both, u)
    out = {"people": people, "takes": takes, "items": int(both.sum())}
    if not both.any():
        return {**out, "status": MISSING, "difference": None, "bar": None, "boot_std": None, "p": None}
    _, paired, change, sd, sigma = _contrast(series, slope_coef * (n - 1), u, weights, seed_stds, balanced)
    rows = [np.asarray(s, dtype=np.float64)[both] for s in series]
    identical = all((r == rows[0]).all() for r in rows[1:]) or abs(change) < IDENTICAL
    minimum = practical_minimum(unit, paired[0])
    status, reason = judge(change, 2.0 * sigma, direction, 0.0, minimum, identical, people, takes)
    return {**out, "values": paired, "slope": change / (n - 1), "status": status, "difference": change,
            "bar": 2.0 * sigma, "boot_std": sd, "p": p_value(change, sigma, direction), "minimum": minimum,
            **({"reason": reason} if reason else {})}


def combine(statuses: list[str]) -> str:
    """A claim made of parts: not evaluated if any part is, fails if any part fails, unusable if a part
    rests on a classifier that failed its check, insufficient data if a part has too few people or takes,
    no difference if a part's difference is below the practical minimum, holds if all hold, else inconclusive."""
    if not statuses or MISSING in statuses:
        return MISSING
    for s in (FAILS, UNUSABLE, INSUFFICIENT, NO_DIFFERENCE):
        if s in statuses:
            return s
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
