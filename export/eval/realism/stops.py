"""WAT's variable lengths (sec. 3.3, Eq. 8 stops): the share of samples that last the whole horizon.

On the windows whose truth continues the same action through the horizon (the caller picks them: this
function takes only their samples' lengths), a sampler that stops early cuts a motion the person kept
going. The share is the fraction of lengths (frames) >= the horizon (frames), over every length given
(pooled over windows and samples); NaN when none is given.

TypeScript twin: none.
"""
from __future__ import annotations

import numpy as np


def full_length_share(lengths, horizon: int) -> float:
    """Fraction of sample lengths (frames) that reach the horizon (length >= horizon)."""
    n = np.asarray(lengths).ravel()
    return float((n >= horizon).mean()) if n.size else float("nan")
