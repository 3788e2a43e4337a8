"""The KL annealing weight lambda of Eq. 9: a logistic curve from 0 to 1, then 1 (Bowman et al.)."""
from __future__ import annotations

import math


def kl_weight(step: int, end: int, sharpness: float = 10.0) -> float:
    """lambda(step): 0 at step 0, 1 from step `end` on, a logistic curve centred at end/2 between.

    A plain logistic never reaches 0 or 1; the paper starts from lambda = 0 and continues at
    lambda = 1 (Section 4.2), so the curve is rescaled to hit both ends exactly. `sharpness` is
    the logistic's slope over the ramp (10: from 0.7% to 99.3% of the way across).
    """
    if end <= 0 or step >= end:
        return 1.0
    if step <= 0:
        return 0.0

    def logistic(s: float) -> float:
        return 1.0 / (1.0 + math.exp(-sharpness * (s / end - 0.5)))

    lo, hi = logistic(0), logistic(end)
    return (logistic(step) - lo) / (hi - lo)
