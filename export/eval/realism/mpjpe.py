"""Mean per-joint position error (MPJPE) and the pose spread between samples, in CENTIMETRES.

MPJPE of one sample against the truth (T truth frames, J joints): the mean over frames and joints of the
per-joint Euclidean distance |y_tj - x_tj|, times 100 (cm), ADE-like; its final-frame version is the
mean over joints at the last truth frame (FDE-like). Best-of-K: each minimised over the samples on its
own (as DLow's ADE/FDE). World positions or root-relative poses (metrics.root_relative). Keyposes'
MPJPE (metrics.mpjpe_curves) is the same per-joint mean, in metres, per frame.

Pose spread: the mean over sample pairs of the mean per-joint distance between the two samples'
root-relative poses (cm), at the last predicted frame and averaged over all predicted frames. 0 for one
sample.

Against the field's whole-pose L2 (WAT Eq. 12 ADE, DLow's ADE/FDE/APD: metrics.ade_fde): that norm is
sqrt(sum_j d_j^2) = sqrt(J * mean_j d_j^2) for per-joint distances d_j, about sqrt(J) = sqrt(18) ~ 4.24
times the mean per-joint distance when the distances are similar (exactly, when every joint is off by
the same distance; more than that when a few joints carry the error). So a whole-pose ADE of 0.42 m is
about 10 cm of per-joint error.

TypeScript twins: web/src/metrics/realism.ts mpjpeCmPerSample, mpjpeCm, poseSpreadCm.
"""
from __future__ import annotations

from itertools import combinations

import numpy as np

from ..metrics import mpjpe_curves, root_relative as _root_relative

CM = 100.0


def mpjpe_cm_per_sample(futures: np.ndarray, truth: np.ndarray, root_relative: bool) -> tuple[np.ndarray, np.ndarray]:
    """Each sample's MPJPE over the truth's frames and at its last frame (cm): two [K] arrays.
    Samples longer than the truth [T, J, 3] are cut to it. TypeScript twin: realism.ts mpjpeCmPerSample."""
    if np.shape(futures)[1] < len(truth):
        raise ValueError(f"the futures have {np.shape(futures)[1]} frames, fewer than the truth's {len(truth)}")
    if root_relative:
        futures, truth = _root_relative(futures), _root_relative(truth)
    curves = mpjpe_curves(futures, truth)               # [K, T]: Keyposes' per-frame MPJPE, metres
    return curves.mean(1) * CM, curves[:, -1] * CM


def mpjpe_cm(futures: np.ndarray, truth: np.ndarray, root_relative: bool) -> tuple[float, float]:
    """Best-of-K (over frames, final frame) MPJPE in cm, each minimised over the samples on its own.
    TypeScript twin: realism.ts mpjpeCm."""
    ade_k, fde_k = mpjpe_cm_per_sample(futures, truth, root_relative)
    return float(ade_k.min()), float(fde_k.min())


def pose_spread_cm(futures: np.ndarray) -> tuple[float, float]:
    """(at the last frame, over all frames): the mean over sample pairs of the mean per-joint distance
    between root-relative poses [K, T, J, 3] (cm); (0, 0) for one sample. TypeScript twin: realism.ts
    poseSpreadCm."""
    f = _root_relative(np.asarray(futures, dtype=np.float64))
    if len(f) < 2:
        return 0.0, 0.0
    pairs = np.array([np.linalg.norm(f[i] - f[j], axis=-1).mean(-1)      # [T]: per frame, mean over joints
                      for i, j in combinations(range(len(f)), 2)])
    return float(pairs[:, -1].mean() * CM), float(pairs.mean() * CM)
