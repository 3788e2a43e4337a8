"""Mean ± std over runs (training seeds × sampling seeds) and the rule that decides a paper claim.

A claim "holds" only when the difference of means lies in the claimed direction by more than
twice the std of that difference, "fails" when it lies the other way by as much, and is
"inconclusive" otherwise. The std of a difference of independent means is sqrt(s_a^2 + s_b^2),
with s the sample std (ddof=1) over runs; a row with one run has s = 0.
"""
from __future__ import annotations

import math

import numpy as np

HOLDS, FAILS, INCONCLUSIVE, MISSING = "holds", "fails", "inconclusive", "not evaluated"


def summarise(values: list[float]) -> dict | None:
    """{"mean", "std", "n"} of the finite values (None when there are none)."""
    v = np.asarray([x for x in values if x is not None and math.isfinite(x)], dtype=np.float64)
    if v.size == 0:
        return None
    return {"mean": float(v.mean()), "std": float(v.std(ddof=1)) if v.size > 1 else 0.0, "n": int(v.size)}


DIRECTIONS = ("greater", "less", "not_less", "not_greater")


def compare(a: dict | None, b: dict | None, direction: str) -> tuple[str, float, float]:
    """Is a > b ("greater"), a < b ("less"), a not below b ("not_less": "similar or better"), or a not
    above b ("not_greater")? -> (status, difference a - b, its 2-std bar)."""
    if direction not in DIRECTIONS:
        raise ValueError(f"direction must be one of {DIRECTIONS}, got {direction!r}")
    if a is None or b is None:
        return MISSING, math.nan, math.nan
    diff = a["mean"] - b["mean"]
    bar = 2.0 * math.hypot(a["std"], b["std"])
    signed = diff if direction in ("greater", "not_less") else -diff
    if -signed > bar:
        return FAILS, diff, bar
    if direction.startswith("not_"):
        return HOLDS, diff, bar    # only a clear difference the wrong way refutes "similar or better"
    return (HOLDS if signed > bar else INCONCLUSIVE), diff, bar


def combine(statuses: list[str]) -> str:
    """A claim made of parts: fails if any part fails, holds if all hold, else inconclusive."""
    if not statuses or MISSING in statuses:
        return MISSING
    if FAILS in statuses:
        return FAILS
    return HOLDS if all(s == HOLDS for s in statuses) else INCONCLUSIVE
