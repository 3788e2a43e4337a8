"""Fréchet distance between classifier features (WAT Eq. 9), on at most 8 PCA dimensions.

With a few hundred motion snippets per set, a 64-dimensional covariance is rank-deficient and
sqrtm of it is noise; projecting onto the reference features' top principal components keeps
the estimate stable. The interval is a percentile bootstrap over the generated set.
"""
from __future__ import annotations

import numpy as np
from scipy.linalg import sqrtm
from sklearn.decomposition import PCA

MAX_DIMS = 8


def frechet(a: np.ndarray, b: np.ndarray) -> float:
    """Eq. 9: ||mu_a - mu_b||^2 + Tr(S_a + S_b - 2 (S_a S_b)^(1/2)) for feature rows a [n, F], b [m, F]."""
    a, b = np.asarray(a, dtype=np.float64), np.asarray(b, dtype=np.float64)
    if len(a) < 2 or len(b) < 2:
        raise ValueError(f"FID needs at least two feature rows per set, got {len(a)} and {len(b)}")
    mu_a, mu_b = a.mean(0), b.mean(0)
    # np.cov centres the features (each set about its own mean).
    s_a, s_b = np.atleast_2d(np.cov(a, rowvar=False)), np.atleast_2d(np.cov(b, rowvar=False))
    root = sqrtm(s_a @ s_b)
    root = np.real(root)  # tiny imaginary parts are numerical noise of sqrtm
    return float(((mu_a - mu_b) ** 2).sum() + np.trace(s_a + s_b - 2.0 * root))


class FeatureSpace:
    """PCA fitted on reference features (the training set's), at most MAX_DIMS components."""

    def __init__(self, reference: np.ndarray, dims: int = MAX_DIMS):
        reference = np.asarray(reference, dtype=np.float64)
        self.pca = PCA(n_components=min(dims, MAX_DIMS, reference.shape[1], len(reference) - 1)).fit(reference)

    def project(self, features: np.ndarray) -> np.ndarray:
        return self.pca.transform(np.asarray(features, dtype=np.float64))

    def fid(self, generated: np.ndarray, reference: np.ndarray) -> float:
        return frechet(self.project(generated), self.project(reference))

    def fid_interval(self, generated: np.ndarray, reference: np.ndarray, rounds: int, seed: int,
                     level: float = 0.95) -> tuple[float, float, float]:
        """(FID, low, high): percentile bootstrap over resampled generated rows."""
        g, r = self.project(generated), self.project(reference)
        rng = np.random.default_rng(seed)
        draws = [frechet(g[rng.integers(0, len(g), len(g))], r) for _ in range(rounds)]
        lo, hi = np.quantile(draws, [(1 - level) / 2, (1 + level) / 2])
        return frechet(g, r), float(lo), float(hi)
