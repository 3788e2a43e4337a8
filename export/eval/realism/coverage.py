"""Coverage: does the truth fall outside the cloud of samples? A sampler whose samples sit on one side of
the truth puts it outside far more often than a calibrated one.

Distance: whole-motion L2 over root-relative poses (metrics.root_relative) over the horizon (the truth's
T frames; longer samples are cut to it), i.e. ||x - c||_2 over all T*J*3 numbers, DLow's APD distance.
"Outside": the truth's distance from the samples' mean exceeds every sample's distance from the mean of
the others (the other K - 1 samples and the truth); ties count as inside.

Why each sample is measured from the mean of the others: measured from the samples' own mean, a sample
helped place the centre it is measured from, so even a perfect sampler would leave the truth outside too
often (K = 1: always). Leaving each point out makes the K + 1 points play one role: x_i - mean(others) =
(K + 1) / K (x_i - mean(all K + 1)), so the order is that of the distances to the common mean, and when
the truth and the K samples are exchangeable (a calibrated sampler) each is the farthest with
probability 1 / (K + 1): calibrated(k). A rank test in the spirit of the rank histograms of forecast
verification (Talagrand diagrams; Hamill, "Interpretation of rank histograms for verifying ensemble
forecasts", Monthly Weather Review 2001). K = 1 always ties (both distances are |x - y|): K >= 2.

TypeScript twin: none.
"""
from __future__ import annotations

import numpy as np

from ..metrics import root_relative


def outside(futures: np.ndarray, truth: np.ndarray) -> bool:
    """Whether the truth [T, J, 3] is farther from the mean of the K samples [K, T', J, 3] (T' >= T) than
    every sample is from the mean of the other points."""
    futures, truth = np.asarray(futures, dtype=np.float64), np.asarray(truth, dtype=np.float64)
    k, t = len(futures), len(truth)
    if k < 2:
        raise ValueError("coverage needs at least two samples: with one, the truth and the sample always tie")
    if futures.shape[1] < t:
        raise ValueError(f"the futures have {futures.shape[1]} frames, fewer than the truth's {t}")
    points = root_relative(np.concatenate([truth[None], futures[:, :t]])).reshape(k + 1, -1)   # truth first
    others = (points.sum(0) - points) / k           # each point's mean of the other K (the truth's: the samples')
    d = np.linalg.norm(points - others, axis=1)
    return bool(d[0] > d[1:].max())


def calibrated(k: int) -> float:
    """The share of windows a calibrated sampler leaves the truth outside: 1 / (K + 1)."""
    return 1.0 / (k + 1)
