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
| Eq. 4 as the authors' code   | transition_smoothness_unsquared | WAT code: unsquared norms |
| joint speed                  | joint_speed               | mean speed in the last second   |
| classifier accuracy          | accuracy                  | WAT sec. 4.2 (2), Keyposes MOAC |
| mean per-class accuracy      | balanced_accuracy         | LCP-VAE sec. 5 ("context")      |
| best-of-K ADE and FDE        | ade_fde                   | WAT Eq. 12, DLow (ADE, FDE)     |
| average pairwise distance    | apd                       | DLow (APD)                      |
| multi-modal ADE / FDE        | mmade_mmfde               | DLow (MMADE, MMFDE)             |
| bone length error            | bone_length_error         | relative to the history's bones |
| feet below the floor         | foot_below_floor          | share of frames, ops/floor.py   |
| jump at the first frame      | first_frame_jump          | vs the history's own last step  |

DLow: Yuan, Kitani, "DLow: Diversifying Latent Flows for Diverse Human Motion Prediction", ECCV 2020.
"""
from __future__ import annotations

from itertools import combinations

import numpy as np
from dtaidistance import dtw_ndim
from scipy.special import gammaln

from ..data.skeleton import SKELETON, Skeleton
from ..ops import facing
from ..ops.dct import dct_basis
from ..ops.dct_smoothness import L_FRAMES, M_BASES, smoothness
from ..ops.bones import bone_lengths
from ..ops.floor import foot_height


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


# --- DLow's accuracy and diversity metrics, and plausibility checks for the browser's read-out ---------


def root_relative(motion: np.ndarray) -> np.ndarray:
    """World positions [..., T, J, 3] -> root-relative poses: each frame's root x and z subtracted from
    every joint, heights kept (DLow evaluates root-relative poses). The split lives in ops/facing.py."""
    return facing.root_relative(facing.split_root(motion))


_to_root_relative = root_relative   # ade_fde's flag of the same name hides the function inside it


def ade_fde_per_sample(futures: np.ndarray, truth: np.ndarray,
                       root_relative: bool) -> tuple[np.ndarray, np.ndarray]:
    """Each sample's ADE and FDE against the ground truth [T, J, 3]: two [K] arrays (metres).

    ADE = mean over the T truth frames of the whole-pose distance ||y_t - x_t||_2 (J*3 coordinates,
    WAT Eq. 12 before its min, DLow's ADE); FDE = that distance at the last truth frame (DLow).
    Samples longer than the truth are cut to it; `root_relative` compares root_relative() poses.
    """
    futures, truth = np.asarray(futures, dtype=np.float64), np.asarray(truth, dtype=np.float64)
    t = len(truth)
    if futures.shape[1] < t:
        raise ValueError(f"the futures have {futures.shape[1]} frames, fewer than the truth's {t}")
    futures = futures[:, :t]
    if root_relative:
        futures, truth = _to_root_relative(futures), _to_root_relative(truth)
    dist = np.linalg.norm((futures - truth).reshape(len(futures), t, -1), axis=-1)   # [K, T]
    return dist.mean(1), dist[:, -1]


def ade_fde(futures: np.ndarray, truth: np.ndarray, root_relative: bool) -> tuple[float, float]:
    """Best-of-K (ADE, FDE): each minimised over the samples on its own, as DLow does, so the two
    may come from different samples."""
    ade_k, fde_k = ade_fde_per_sample(futures, truth, root_relative)
    return float(ade_k.min()), float(fde_k.min())


def apd(futures: np.ndarray) -> float:
    """DLow's APD: 1 / (K (K - 1)) sum over ordered pairs i != j of ||Y_i - Y_j||_2, where each Y is a
    whole future flattened to T*J*3 numbers; 0 for K = 1.

    Not WAT Eq. 10 (`diversity`), which averages per-frame pose distances: APD takes one norm over
    the whole sequence, so it grows like sqrt(T) for a steady per-frame spread. DLow computes it on
    root-relative poses; pass root_relative(futures) for that.
    """
    flat = np.asarray(futures, dtype=np.float64).reshape(len(futures), -1)
    k = len(flat)
    if k < 2:
        return 0.0
    d = np.linalg.norm(flat[:, None] - flat[None], axis=-1)   # the diagonal is 0
    return float(d.sum() / (k * (k - 1)))


def bone_length_error(motion: np.ndarray, reference_lengths: np.ndarray, skeleton: Skeleton = SKELETON) -> float:
    """Mean over frames and bones of |L - L_ref| / L_ref: how far a prediction stretches the body.

    The reference is the history's mean bone lengths (bone_lengths(history).mean(0)), not the rest
    skeleton, so a retargeted clip whose bones are already off by a little starts at 0.
    """
    ref = np.asarray(reference_lengths, dtype=np.float64)
    if np.any(ref <= 0):
        raise ValueError("reference bone lengths must be positive")
    return float((np.abs(bone_lengths(motion, skeleton) - ref) / ref).mean())


def foot_below_floor(motion: np.ndarray, depth: float = 0.03, skeleton: Skeleton = SKELETON) -> float:
    """Share of frames whose foot (the lower of ankle and toe, either side: ops/floor.foot_height) is
    more than `depth` metres below the floor y = 0. The default is the 3 cm of floor.CONTACT_BAND: a
    foot within it counts as on the floor, so only sinking beyond it is an error."""
    return float((foot_height(np.asarray(motion, dtype=np.float64), skeleton) < -depth).mean())


def first_frame_jump(history: np.ndarray, future: np.ndarray) -> tuple[float, float]:
    """(jump, last_step): the mean per-joint distance from the history's last frame to the future's
    first frame, and the history's own last step (mean per-joint distance between its last two
    frames), metres. A jump well above the step is a visible pop at the seam."""
    h, f = np.asarray(history, dtype=np.float64), np.asarray(future, dtype=np.float64)
    if len(h) < 2:
        raise ValueError("the history needs at least two frames for its last step")
    jump = np.linalg.norm(f[0] - h[-1], axis=-1).mean()
    last_step = np.linalg.norm(h[-1] - h[-2], axis=-1).mean()
    return float(jump), float(last_step)


def jump_ok(jump: float, last_step: float) -> bool:
    """The seam is smooth when jump <= max(1.5 x last step, 1 cm): the floor of 1 cm lets a still
    history (step ~ 0) start a motion without being called a jump."""
    return bool(jump <= max(1.5 * last_step, 0.01))


def _last_pose_distances(histories: np.ndarray) -> np.ndarray:
    """[W, N, J, 3] -> [W, W]: whole-pose L2 distance between the windows' root-relative last poses."""
    last = root_relative(np.asarray(histories)[:, -1:])[:, 0].reshape(len(histories), -1)
    return np.linalg.norm(last[:, None] - last[None], axis=-1)


def similar_sets(histories: np.ndarray, threshold: float) -> list[np.ndarray]:
    """DLow's multi-modal ground truth: for each window w, the indices of the windows whose last history
    pose lies within `threshold` (L2 over the whole root-relative pose, metres) of w's; w is always in
    its own set. The histories must face one way at their last frame: canonical windows (ops/facing),
    whose root channel is 0 at that frame, so their last poses read as positions.

    `<=` where DLow's code has `<`, so a threshold taken from the distances themselves
    (choose_threshold) includes the pair that defines it.
    """
    d = _last_pose_distances(histories)
    return [np.flatnonzero(row <= threshold) for row in d]


def choose_threshold(histories: np.ndarray, min_median_size: int = 5) -> float:
    """The smallest threshold, among the windows' pairwise last-pose distances, at which the median
    similar set has at least `min_median_size` members (itself included).

    DLow fixes 0.5 for Human3.6M; our windows and skeleton differ, so the threshold is chosen from
    the data instead. The median set size only grows with the threshold: a binary search suffices.
    """
    d = _last_pose_distances(histories)
    if len(d) < min_median_size:
        raise ValueError(f"{len(d)} windows cannot give sets of {min_median_size}")
    candidates = np.unique(d)              # sorted; includes 0 (each window with itself)
    lo, hi = 0, len(candidates) - 1        # the largest distance puts every window in every set
    while lo < hi:
        mid = (lo + hi) // 2
        if np.median((d <= candidates[mid]).sum(1)) >= min_median_size:
            hi = mid
        else:
            lo = mid + 1
    return float(candidates[lo])


def mmade_mmfde(futures_per_window, truths: np.ndarray, sets: list[np.ndarray],
                root_relative: bool = True) -> tuple[float, float]:
    """DLow's MMADE and MMFDE: for window w, the best-of-K ADE (FDE) of w's futures [K, T', J, 3] against
    each member's truth [T, J, 3] of w's similar set, averaged over the set; then the mean over windows.

    A window whose set is only itself still counts, with its own truth (its MMADE term is then its
    ADE), as in DLow. Root-relative by default: the truths of other windows started elsewhere. Each
    window's futures and truth are positions in its own canonical frame (facing +z at its last history
    frame): facing.join_root of a canonical window, not the models' tensors with the root channel.
    """
    truths = np.asarray(truths, dtype=np.float64)
    if len(sets) != len(truths) or len(futures_per_window) != len(truths):
        raise ValueError("one similar set and one set of futures per window")
    per_window = [np.mean([ade_fde(futures_per_window[w], truths[v], root_relative) for v in members], axis=0)
                  for w, members in enumerate(sets)]
    mm = np.mean(per_window, axis=0)
    return float(mm[0]), float(mm[1])


# --- Eq. 4 as the authors' released code computes it (issue 18: disclosed beside the printed one) -------


def transition_smoothness_unsquared(before: np.ndarray, after: np.ndarray, frames: int = L_FRAMES,
                                    bases: int = M_BASES) -> float:
    """WAT Eq. 4 with the unsquared per-pose norm, (1/2L) sum_i ||z_i - z~_i||_2 (metres), as the authors'
    code takes the mean of the norms; the paper prints the squared norm (transition_smoothness). Same
    Z and the same M lowest DCT bases over 2L frames."""
    if len(before) < frames or len(after) < frames:
        raise ValueError(f"transition smoothness needs {frames} frames on each side, "
                         f"got {len(before)} before and {len(after)} after")
    z = np.concatenate([np.asarray(before, dtype=np.float64)[-frames:],
                        np.asarray(after, dtype=np.float64)[:frames]]).reshape(2 * frames, -1)
    d = dct_basis(2 * frames, bases)
    return float(np.linalg.norm(z - d @ (d.T @ z), axis=1).mean())


def ade_fde_many(futures: np.ndarray, truths: np.ndarray, root_relative: bool) -> tuple[np.ndarray, np.ndarray]:
    """ade_fde of the same K futures against each of M truths [M, T, J, 3] at once: two [M] arrays, each
    entry what ade_fde(futures, truths[m], root_relative) gives (MMADE's inner loop, one array operation)."""
    futures, truths = np.asarray(futures, dtype=np.float64), np.asarray(truths, dtype=np.float64)
    t = truths.shape[1]
    if futures.shape[1] < t:
        raise ValueError(f"the futures have {futures.shape[1]} frames, fewer than the truths' {t}")
    futures = futures[:, :t]
    if root_relative:
        futures, truths = _to_root_relative(futures), _to_root_relative(truths)
    f = futures.reshape(len(futures), t, -1)
    g = truths.reshape(len(truths), t, -1)
    # |f - g|^2 = |f|^2 + |g|^2 - 2 f.g per frame: no [K, M, T, D] temporary (M is a whole similar set).
    sq = (f * f).sum(-1)[:, None] + (g * g).sum(-1)[None] - 2.0 * np.einsum("ktd,mtd->kmt", f, g)
    dist = np.sqrt(np.maximum(sq, 0.0))                    # [K, M, T]
    return dist.mean(-1).min(0), dist[..., -1].min(0)
