"""The `metrics` family of shared test vectors: what the browser's read-out computes from K futures.

Small deterministic motions of the 18-joint skeleton (a rest pose that travels, plus noise) and the
Python results of export/eval/metrics.py: best-of-K and per-sample ADE/FDE (world frame and
root-relative), APD, bone length error and feet below the floor per sample. TypeScript
(web/src/metrics/readout.ts) must reproduce them within the file's tolerance; export/vectors.py
registers the family and derives that tolerance.
"""
from __future__ import annotations

import numpy as np

from .data.skeleton import SKELETON
from .eval import metrics as M
from .ops.floor import foot_height

SEED = 20240611
HISTORY_FRAMES = 6
DEPTH = 0.03
ROOT_HEIGHT = 0.88          # metres: the rest pose's toes then stand about on the floor
NOISE = 0.03                # metres per coordinate: feet dip below the floor in some frames only
# (K, future frames, truth frames): K = 1, 3, 5; one case whose futures outlast the truth.
CASES = [(1, 4, 4), (3, 8, 6), (5, 12, 12), (3, 10, 10)]


def _rest_pose() -> np.ndarray:
    """The skeleton's rest pose [J, 3] by forward kinematics of its offsets, root at ROOT_HEIGHT."""
    pose = SKELETON.offsets.copy()
    for j, p in enumerate(SKELETON.parents):     # parents precede children
        if p >= 0:
            pose[j] = pose[p] + SKELETON.offsets[j]
    return pose + [0.0, ROOT_HEIGHT, 0.0]


def _travel(rng, frames: int, start: np.ndarray, velocity: np.ndarray) -> np.ndarray:
    """The rest pose carried along `velocity` (metres per frame) from `start`, plus noise: [frames, J, 3]."""
    t = np.arange(frames)[:, None, None]
    return _rest_pose() + start + t * velocity + rng.normal(scale=NOISE, size=(frames, SKELETON.num_joints, 3))


def _errors(futures: np.ndarray, truth: np.ndarray, root_relative: bool) -> dict:
    ade_k, fde_k = M.ade_fde_per_sample(futures, truth, root_relative)
    ade, fde = M.ade_fde(futures, truth, root_relative)
    return {"ade": ade, "fde": fde, "ade_per_sample": ade_k.tolist(), "fde_per_sample": fde_k.tolist()}


def metrics_vector() -> dict:
    rng = np.random.default_rng(SEED)
    cases = []
    for k, frames, truth_frames in CASES:
        start = np.array([rng.uniform(-2, 2), 0.0, rng.uniform(-2, 2)])
        velocity = np.array([rng.uniform(-0.05, 0.05), 0.0, rng.uniform(-0.05, 0.05)])
        history = _travel(rng, HISTORY_FRAMES, start, velocity)
        after = start + HISTORY_FRAMES * velocity
        truth = _travel(rng, truth_frames, after, velocity)
        futures = np.stack([_travel(rng, frames, after, velocity + rng.normal(scale=0.02, size=3) * [1, 0, 1])
                            for _ in range(k)])
        feet = foot_height(futures)
        if np.abs(feet + DEPTH).min() < 1e-6:     # no case may sit on the floor test's edge
            raise ValueError("a foot lies within 1e-6 m of the depth: pick another seed")
        reference = M.bone_lengths(history).mean(0)
        cases.append({
            "k": k, "frames": frames, "truth_frames": truth_frames, "joints": SKELETON.num_joints,
            "history": history.tolist(), "futures": futures.tolist(), "truth": truth.tolist(),
            "world": _errors(futures, truth, root_relative=False),
            "root_relative": _errors(futures, truth, root_relative=True),
            "apd": M.apd(futures),
            "reference_bone_lengths": reference.tolist(),
            "bone_length_error": [M.bone_length_error(f, reference) for f in futures],
            "depth": DEPTH,
            "foot_below_floor": [M.foot_below_floor(f, DEPTH) for f in futures],
        })
    return {"about": "read-out metrics of K futures (export/eval/metrics.py): best-of-K and per-sample ADE and FDE "
                     "(whole-pose L2, WAT Eq. 12 / DLow; world frame and root-relative, futures cut to the truth's "
                     "frames), APD (DLow, whole sequence), bone length error against the history's mean bone "
                     "lengths, and the share of frames with a foot more than `depth` below y = 0, per sample",
            "cases": cases}
