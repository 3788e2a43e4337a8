"""CMD, the cumulative motion distribution of BeLFusion (Barquero, Escalera, Palmero, "BeLFusion: Latent
Diffusion for Behavior-Driven Human Motion Prediction", ICCV 2023): do the predicted futures keep the
amount of motion of real ones over the whole horizon, instead of freezing?

M_t (metres per frame, t = 1 .. F-1 over F predicted frames): the average displacement between predicted
frames t and t+1, the mean over joints and over every sample (and window) of |p_{t+1,j} - p_{t,j}|;
BeLFusion takes it on root-relative poses. M: the reference, the average displacement of the real
motion (the test set's truth of the same class). Then

    CMD = sum_{i=1}^{F-1} sum_{t=1}^{i} |M_t - M| = sum_{t=1}^{F-1} (F - t) |M_t - M|

(metres per frame), so an early departure from M weighs more: it is carried by every later cumulative
sum. Over a test set BeLFusion computes one M_t per class (the mean over the class's windows) against
that class's M, and averages the classes' CMD weighted by their share of windows (cmd_by_class).
Read from the authors' code (github.com/BarqueroGerman/BeLFusion, metrics/evaluation.py `cmd` and
eval_belfusion.py's "Computing CMD"); the sum is over displacements, not speeds, at the data's frame
rate (50 fps in Human3.6M), so numbers here (30 fps) do not compare with the paper's.

TypeScript twin: none.
"""
from __future__ import annotations

import numpy as np

from ..metrics import root_relative as _root_relative


def displacement_per_frame(motions: np.ndarray, root_relative: bool = True) -> np.ndarray:
    """M_t: the mean over joints and every leading axis (samples, windows) of the per-joint displacement
    between consecutive frames, [..., F, J, 3] -> [F - 1] (metres per frame)."""
    m = np.asarray(motions, dtype=np.float64)
    if root_relative:
        m = _root_relative(m)
    d = np.linalg.norm(np.diff(m, axis=-3), axis=-1).mean(-1)      # [..., F-1]
    return d.reshape(-1, d.shape[-1]).mean(0)


def cmd(per_frame: np.ndarray, reference: float) -> float:
    """sum_{t=1}^{F-1} (F - t) |M_t - M| for M_t = per_frame [F - 1] and M = reference."""
    m = np.asarray(per_frame, dtype=np.float64).ravel()
    weights = np.arange(len(m), 0, -1, dtype=np.float64)           # F - t for t = 1 .. F-1
    return float((weights * np.abs(m - reference)).sum())


def cmd_by_class(per_window: np.ndarray, classes, reference: dict) -> float:
    """BeLFusion's test-set CMD: per class c, cmd(mean over c's windows of their M_t, reference[c]),
    weighted by c's share of the windows. per_window [W, F - 1]: each window's M_t (over its samples,
    displacement_per_frame(futures_of_w)); classes [W]; reference: class -> its real M."""
    per_window = np.asarray(per_window, dtype=np.float64)
    classes = np.asarray(classes)
    if len(classes) != len(per_window):
        raise ValueError(f"{len(classes)} classes for {len(per_window)} windows")
    return float(sum(cmd(per_window[classes == c].mean(0), reference[c]) * (classes == c).mean()
                     for c in np.unique(classes)))
