"""Who a model learns from: per-example sampling weights that cap people within an action and actions
overall (issue 27, item 4).

In the CMU subset one subject (105) holds 80% of the walking seconds and salsa is 35% of all seconds;
drawn uniformly, a model would learn walking from one person and motion mostly from salsa. The rule:
1. within an action with at least MIN_PEOPLE training people, no person supplies more than PERSON_CAP
   of the action's draws (1/3);
2. no action supplies more than ACTION_CAP of all draws (1/4).
Both are "water-filling": shares start proportional to what each has (seconds, i.e. windows), every
share above the cap is set to the cap, and the excess is spread over the others in proportion to
what they have, repeated until none exceeds it. Within an (action, person) group every example has
the same weight, so a person's own takes and mirrors keep their proportions. An action with fewer
than MIN_PEOPLE people keeps its people's natural shares (a cap of 1/3 cannot hold with two).

The weights are sampling probabilities of the training loop (export/train/loop.py), not a subsample:
every window is still seen, the dominant ones less often.
"""
from __future__ import annotations

from collections import Counter
from typing import Hashable, Sequence

import numpy as np

PERSON_CAP = 1.0 / 3.0
ACTION_CAP = 0.25
MIN_PEOPLE = 3
RULE = (f"training draws are weighted: within an action with {MIN_PEOPLE} or more training people no person "
        f"supplies more than {PERSON_CAP:.3g} of its draws, and no action more than {ACTION_CAP:g} of all "
        "draws (water-filling from each one's share of the windows; equal weights within an action and person)")


def capped_shares(amounts: dict[Hashable, float], cap: float) -> dict[Hashable, float]:
    """Shares proportional to `amounts`, none above `cap` (water-filling; see the module docstring)."""
    keys = list(amounts)
    a = np.asarray([float(amounts[k]) for k in keys])
    if (a < 0).any() or a.sum() <= 0:
        raise ValueError("capped shares need non-negative amounts with a positive sum")
    if cap * len(keys) < 1 - 1e-12:
        raise ValueError(f"{len(keys)} shares cannot all stay at or below {cap:.3g}")
    shares = a / a.sum()
    fixed = np.zeros(len(keys), dtype=bool)
    while True:
        over = ~fixed & (shares > cap + 1e-12)
        if not over.any():
            break
        fixed |= over
        free = ~fixed
        rest = 1.0 - cap * fixed.sum()
        shares = np.where(fixed, cap, 0.0)
        if free.any() and a[free].sum() > 0:
            shares[free] = rest * a[free] / a[free].sum()
    return dict(zip(keys, shares.tolist()))


def example_weights(actions: Sequence[str], people: Sequence[Hashable], person_cap: float = PERSON_CAP,
                    action_cap: float = ACTION_CAP, min_people: int = MIN_PEOPLE) -> np.ndarray:
    """[N] sampling weights (mean 1) of N examples, each of an action and a person, by the rule above."""
    if len(actions) != len(people):
        raise ValueError(f"{len(actions)} actions for {len(people)} people")
    if not len(actions):
        return np.zeros(0)
    groups = Counter(zip(actions, map(str, people)))
    per_action = Counter(actions)
    action_cap = max(action_cap, 1.0 / len(per_action))     # too few actions for the cap: equal shares
    action_share = capped_shares(dict(per_action), action_cap)
    group_share = {}
    for action in per_action:
        mine = {p: n for (a, p), n in groups.items() if a == action}
        person = capped_shares(mine, person_cap) if len(mine) >= min_people else \
            {p: n / sum(mine.values()) for p, n in mine.items()}
        group_share.update({(action, p): action_share[action] * s for p, s in person.items()})
    w = np.asarray([group_share[(a, str(p))] / groups[(a, str(p))] for a, p in zip(actions, people)])
    return w * len(w) / w.sum()


def shares(weights: np.ndarray, actions: Sequence[str], people: Sequence[Hashable]) -> dict:
    """What the weights give: {"actions": {action: share}, "people": {action: {person: share in it}}}."""
    w = np.asarray(weights, dtype=np.float64)
    total = w.sum()
    out_a: dict[str, float] = {}
    out_p: dict[str, dict[str, float]] = {}
    for wi, a, p in zip(w, actions, people):
        out_a[a] = out_a.get(a, 0.0) + wi / total
        out_p.setdefault(a, {})[str(p)] = out_p.setdefault(a, {}).get(str(p), 0.0) + wi
    for a, d in out_p.items():
        s = sum(d.values())
        out_p[a] = {p: v / s for p, v in sorted(d.items())}
    return {"actions": dict(sorted(out_a.items())), "people": dict(sorted(out_p.items()))}
