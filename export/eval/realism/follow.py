"""Does the future's speed follow the history's? A still history should give a calm future, a fast one
a lively future.

The Spearman rank correlation (scipy.stats.spearmanr) across windows between each window's history mean
joint speed (root-relative, m/s, over all the history's steps: history_speed) and its first predicted
second's mean joint speed (speed.joint_speed_per_second(...)[..., 0] with the history's last frame
prepended; for K samples, e.g. their mean). Unitless, in [-1, 1]. NaN (not an exception) with fewer
than 3 windows, a constant input (no ranks to correlate) or a non-finite value.

TypeScript twin: none.
"""
from __future__ import annotations

import numpy as np
from scipy.stats import spearmanr

from ..metrics import root_relative

FPS = 30


def history_speed(history: np.ndarray, fps: int = FPS) -> np.ndarray:
    """Mean joint speed over the whole history, root-relative (m/s): [..., H, J, 3] -> [...]."""
    poses = root_relative(np.asarray(history, dtype=np.float64))
    if poses.shape[-3] < 2:
        raise ValueError("a history speed needs at least two frames")
    return np.linalg.norm(np.diff(poses, axis=-3), axis=-1).mean((-2, -1)) * fps


def follow(history_speeds, future_speeds) -> float:
    """Spearman's rho across windows between history speeds [W] and first-second future speeds [W]."""
    x = np.asarray(history_speeds, dtype=np.float64).ravel()
    y = np.asarray(future_speeds, dtype=np.float64).ravel()
    if x.shape != y.shape:
        raise ValueError(f"{x.size} history speeds for {y.size} future speeds")
    if x.size < 3 or not (np.isfinite(x).all() and np.isfinite(y).all()) or np.ptp(x) == 0 or np.ptp(y) == 0:
        return float("nan")
    return float(spearmanr(x, y).statistic)
