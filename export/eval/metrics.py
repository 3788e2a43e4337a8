"""The papers' metrics as small pure functions on numpy arrays (metres, frames at 30 fps).

A motion is [T, J, 3]; a set of K sampled futures is [K, T, J, 3] (or a list of variable-length
motions). A "pose" in WAT's Eqs. 10-12 is one frame flattened to a vector of J*3 coordinates,
so those distances are the L2 norm of the whole pose difference; Keyposes' MPJPE instead
averages the per-joint distances.

| metric                       | function                  | source                          |
|------------------------------|---------------------------|---------------------------------|
| diversity                    | diversity                 | WAT Eq. 10                      |
| diversity after DTW          | diversity_dtw             | WAT Eq. 11                      |
| best-of-K ADE                | ade                       | WAT Eq. 12                      |
| ADE after DTW                | ade_dtw                   | WAT sec. 4.2 ("ADE_w")          |
| MPJPE "ave" / "best" at t    | mpjpe_at                  | Keyposes sec. 4.3, Table 3      |
| PSKL gt-pred / pred-gt       | pskl                      | Keyposes sec. 4.3 (from [33])   |
| predicted lengths per action | length_histogram          | WAT sec. 3.3                    |
| transition smoothness        | transition_smoothness     | WAT Eq. 4 (ops/dct_smoothness)  |
| joint speed                  | joint_speed               | mean speed in the last second   |
| classifier accuracy          | accuracy                  | WAT sec. 4.2 (2), Keyposes MOAC |
| mean per-class accuracy      | balanced_accuracy         | LCP-VAE sec. 5 ("context")      |
"""
from __future__ import annotations

from itertools import combinations

import numpy as np
from dtaidistance import dtw_ndim
from scipy.special import gammaln

from ..ops.dct_smoothness import L_FRAMES, smoothness


def _flat(motion: np.ndarray) -> np.ndarray:
    """[T, J, 3] -> [T, J*3] float64, the pose vectors of WAT's equations."""
    motion = np.asarray(motion, dtype=np.float64)
    return np.ascontiguousarray(motion.reshape(len(motion), -1))


def pose_distances(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Frame-wise ||a_k - b_k||_2 over whole poses: [T, J, 3] x [T, J, 3] -> [T]."""
    return np.linalg.norm(_flat(a) - _flat(b), axis=1)


def dtw_align(a: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Temporally align two motions of any lengths (WAT sec. 4.2, [58]); both come back [T_ab, J, 3].

    The path minimises the summed squared pose distance (dtaidistance's default inner distance).
    """
    fa, fb = _flat(a), _flat(b)
    if fa.shape[1] < 2:
        raise ValueError("dtw_align needs at least two coordinates per pose")
    path = np.asarray(dtw_ndim.warping_path(fa, fb, use_c=True))
    return np.asarray(a)[path[:, 0]], np.asarray(b)[path[:, 1]]


def diversity(futures: np.ndarray) -> float:
    """WAT Eq. 10: mean over sample pairs of the mean frame-wise pose distance, over all T_max frames.

    Variable-length samples come padded with their last pose (the predictor's contract), which
    stands in for "the model generates the maximum number of frames". One sample: 0.
    """
    futures = np.asarray(futures)
    if len(futures) < 2:
        return 0.0
    return float(np.mean([pose_distances(futures[i], futures[j]).mean()
                          for i, j in combinations(range(len(futures)), 2)]))


def diversity_dtw(futures: list[np.ndarray]) -> float:
    """WAT Eq. 11: Eq. 10 on each DTW-aligned pair of variable-length samples ([T_i, J, 3] each)."""
    if len(futures) < 2:
        return 0.0
    return float(np.mean([pose_distances(*dtw_align(futures[i], futures[j])).mean()
                          for i, j in combinations(range(len(futures)), 2)]))


def ade(futures: np.ndarray, truth: np.ndarray) -> float:
    """WAT Eq. 12: min over samples of the mean frame-wise pose distance to the ground truth [T, J, 3]."""
    t = len(truth)
    return float(min(pose_distances(f[:t], truth).mean() for f in np.asarray(futures)))


def ade_dtw(futures: list[np.ndarray], truth: np.ndarray) -> float:
    """ADE_w (WAT sec. 4.2): Eq. 12 after aligning each variable-length sample to the truth by DTW."""
    return float(min(pose_distances(*dtw_align(f, truth)).mean() for f in futures))


def mpjpe_curves(futures: np.ndarray, truth: np.ndarray) -> np.ndarray:
    """Mean per-joint position error of each sample at each frame: [K, T] (metres)."""
    t = len(truth)
    return np.linalg.norm(np.asarray(futures, dtype=np.float64)[:, :t] - truth, axis=-1).mean(-1)


def mpjpe_at(futures: np.ndarray, truth: np.ndarray, frame: int) -> tuple[float, float]:
    """Keyposes Table 3: MPJPE at `frame` (0-based) of the sample with the lowest MPJPE averaged over
    all frames ("ave"), and the lowest MPJPE of any sample at that frame ("best")."""
    curves = mpjpe_curves(futures, truth)
    if not 0 <= frame < curves.shape[1]:
        raise ValueError(f"frame {frame} is outside the {curves.shape[1]} ground-truth frames")
    # "ave" chooses its sample over the whole evaluated future (the paper does not say how far).
    ave = curves[int(np.argmin(curves.mean(1))), frame]
    return float(ave), float(curves[:, frame].min())


def power_spectrum(motions: np.ndarray, keep: np.ndarray | None = None) -> np.ndarray:
    """The set's power spectrum per coordinate, as in [33]'s code: |FFT over time|^2 of every motion
    [N, T, J, 3], pooled over motions, + 1e-8, normalised over frequency -> [T, D].

    Pooled by the mean rather than [33]'s sum, so the 1e-8 floor does not depend on the set size.
    `keep` selects coordinates (see pskl).
    """
    x = np.asarray(motions, dtype=np.float64).reshape(len(motions), np.shape(motions)[1], -1)
    if keep is not None:
        x = x[:, :, keep]
    ps = (np.abs(np.fft.fft(x, axis=1)) ** 2).mean(0) + 1e-8
    return ps / ps.sum(0, keepdims=True)


def _kl(p: np.ndarray, q: np.ndarray) -> float:
    """KL(p || q) per coordinate (sum over frequency), averaged over coordinates."""
    return float((p * np.log(p / q)).sum(0).mean())


def pskl(truth: np.ndarray, predicted: np.ndarray) -> tuple[float, float]:
    """Keyposes sec. 4.3 (PSKL of [33]): (KL(gt || pred), KL(pred || gt)) between the power spectra of
    two sets of equally long motions [N, T, J, 3]. Close values mean similarly complex motion.

    Coordinates that never move in the ground truth (e.g. the root's x and z here) are dropped,
    as [33]'s code drops dimensions with std < 1e-4.
    """
    truth, predicted = np.asarray(truth), np.asarray(predicted)
    if truth.shape[1:] != predicted.shape[1:]:
        raise ValueError(f"PSKL needs motions of one length: truth {truth.shape[1:]} vs {predicted.shape[1:]}")
    keep = np.flatnonzero(truth.reshape(-1, int(np.prod(truth.shape[2:]))).std(0) >= 1e-4)
    p, q = power_spectrum(truth, keep), power_spectrum(predicted, keep)
    return _kl(p, q), _kl(q, p)


def joint_speed(motion: np.ndarray, fps: float, last_frames: int | None = None) -> float:
    """Mean joint speed (m/s) over the last `last_frames` frames (all when None): does motion stay dynamic?"""
    m = np.asarray(motion, dtype=np.float64)
    if last_frames is not None:
        m = m[-(last_frames + 1):]   # n frames of motion need n+1 poses
    if len(m) < 2:
        raise ValueError("joint speed needs at least two frames")
    return float(np.linalg.norm(np.diff(m, axis=0), axis=-1).mean() * fps)


def transition_smoothness(before: np.ndarray, after: np.ndarray, frames: int = L_FRAMES) -> float:
    """WAT Eq. 4 at a transition: the last `frames` poses before it and the first `frames` after it
    (square metres; lower is smoother). Calls the one implementation in ops/dct_smoothness.py."""
    if len(before) < frames or len(after) < frames:
        raise ValueError(f"transition smoothness needs {frames} frames on each side, "
                         f"got {len(before)} before and {len(after)} after")
    return smoothness(np.asarray(before)[-frames:], np.asarray(after)[:frames])


def length_histogram(lengths: list[int], edges: list[int]) -> list[int]:
    """Counts of predicted lengths (frames) in the bins [edges[i], edges[i+1]), the last one closed."""
    counts, _ = np.histogram(np.asarray(lengths, dtype=np.float64), bins=np.asarray(edges, dtype=np.float64))
    return [int(c) for c in counts]


def accuracy(predicted: np.ndarray, labels: np.ndarray) -> float:
    """Fraction of predicted class indices equal to the labels."""
    predicted, labels = np.asarray(predicted), np.asarray(labels)
    if predicted.shape != labels.shape or predicted.size == 0:
        raise ValueError(f"accuracy needs equal non-empty label arrays, got {predicted.shape} and {labels.shape}")
    return float((predicted == labels).mean())


def balanced_accuracy(predicted: np.ndarray, labels: np.ndarray) -> float:
    """Mean over the classes present in `labels` of each class's accuracy: LCP-VAE's "mean class
    accuracy" (sec. 5). Here the test windows are ~90% walking, so plain accuracy would let a
    classifier that maps every static input to "walk" score ~90%."""
    predicted, labels = np.asarray(predicted), np.asarray(labels)
    accuracy(predicted, labels)   # same checks
    return float(np.mean([(predicted[labels == c] == c).mean() for c in np.unique(labels)]))


def noise_diversity(sigma: float, coordinates: int) -> float:
    """Expected Eq. 10 of samples truth + N(0, sigma^2 I) over `coordinates` dims: the difference of two
    samples is N(0, 2 sigma^2 I), whose norm is sqrt(2) sigma times a chi variable with D degrees of
    freedom, with mean sqrt(2) Gamma((D+1)/2) / Gamma(D/2). The sanity row checks Eq. 10 against it."""
    d = coordinates
    return float(2.0 * sigma * np.exp(gammaln((d + 1) / 2) - gammaln(d / 2)))
