"""The label distribution of a keypose (Keyposes paper, section 3.2.1): proximity to every cluster
centre = the negative mean per-joint distance, then a softmax with a temperature.

TypeScript twins: proximity and labelDistribution in web/src/sampling/keyposes.ts, softmax and
sampleIndex in web/src/sampling/temperature.ts; contract/vectors/keyposes.json ties them.
"""
from __future__ import annotations

import numpy as np

from ..data.skeleton import SKELETON
from .facing import facing_angle, rotate_about_y

# Table 7's noise (std 0.1) was added to proximities that the softmax then divides by the heat
# 0.03 (Table 10). The softmax only sees proximity / T, so keeping noise / T = 0.1 / 0.03 keeps the
# noise's effect on the distribution the same in our units (metres, our own temperature).
NOISE_PER_TEMPERATURE = 0.1 / 0.03


def face_forward(poses: np.ndarray) -> np.ndarray:
    """Each pose [n, J, 3] turned about +y to face +z on its own: centres carry no heading."""
    poses = np.asarray(poses, dtype=np.float64)
    return np.stack([rotate_about_y(p, -facing_angle(p, SKELETON)) for p in poses]) if len(poses) else poses


def proximity(values: np.ndarray, centres: np.ndarray) -> np.ndarray:
    """[n, J, 3] poses, [K, J, 3] centres -> [n, K]: minus the mean over joints of the distance."""
    v = np.asarray(values, dtype=np.float64)
    c = np.asarray(centres, dtype=np.float64)
    return -np.linalg.norm(v[:, None] - c[None], axis=-1).mean(-1)


def softmax(x: np.ndarray, temperature: float) -> np.ndarray:
    """softmax(x / temperature) over the last axis, in float64 (max subtracted)."""
    if not temperature > 0:
        raise ValueError(f"the temperature must be positive, got {temperature}")
    z = np.asarray(x, dtype=np.float64) / temperature
    z = np.exp(z - z.max(-1, keepdims=True))
    return z / z.sum(-1, keepdims=True)


def label_distribution(values: np.ndarray, centres: np.ndarray, temperature: float) -> np.ndarray:
    return softmax(proximity(values, centres), temperature)


def choose_temperature(values: np.ndarray, centres: np.ndarray, target: float) -> float:
    """The temperature at which the mean top probability over `values` equals `target` (bisection
    in log T; the top probability falls as T grows), rounded to 3 significant digits."""
    prox = proximity(values, centres)
    lo, hi = 1e-5, 10.0
    for _ in range(100):
        mid = float(np.sqrt(lo * hi))
        top = softmax(prox, mid).max(-1).mean()
        lo, hi = (mid, hi) if top > target else (lo, mid)
    return float(f"{np.sqrt(lo * hi):.3g}")


def sample_index(logits: np.ndarray, temperature: float, u: float) -> tuple[int, float]:
    """Draw from softmax(logits / temperature) with one uniform u in [0, 1): the first index whose
    cumulative probability exceeds u. Returns it and u's distance to the nearest inner CDF bound
    (the decision's margin; the bounds 0 and 1 cannot flip it)."""
    p = softmax(np.asarray(logits, dtype=np.float64), temperature)
    cdf = np.cumsum(p)
    above = np.nonzero(u < cdf)[0]
    i = int(above[0]) if len(above) else len(p) - 1
    margin = np.inf
    if i > 0:
        margin = u - cdf[i - 1]
    if i < len(p) - 1:
        margin = min(margin, cdf[i] - u)
    return i, float(margin)
