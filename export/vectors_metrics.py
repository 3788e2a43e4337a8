"""The `metrics` family of shared test vectors: what the browser's read-out computes from K futures.

Small deterministic motions of the 18-joint skeleton (a rest pose that travels, plus noise) and the
Python results of export/eval/metrics.py: best-of-K and per-sample ADE/FDE (world frame and
root-relative), APD, bone length error and feet below the floor per sample; and of export/eval/realism:
the per-joint error in cm (mpjpe_cm), the pose spread in cm and the median foot contact speed per
sample. A last case has planted and sliding feet, so skating is not only noise. TypeScript
(web/src/metrics/readout.ts, web/src/metrics/realism.ts) must reproduce them within the file's
tolerance; export/vectors.py registers the family and derives that tolerance.
"""
from __future__ import annotations

import numpy as np

from .data.skeleton import SKELETON
from .eval import metrics as M
from .eval import realism as R
from .ops.floor import CONTACT_BAND, foot_height

SEED = 20240611
HISTORY_FRAMES = 6
DEPTH = 0.03
ROOT_HEIGHT = 0.88          # metres: the rest pose's toes then stand about on the floor
NOISE = 0.03                # metres per coordinate: feet dip below the floor in some frames only
# (K, future frames, truth frames): K = 1, 3, 5; one case whose futures outlast the truth.
CASES = [(1, 4, 4), (3, 8, 6), (5, 12, 12), (3, 10, 10)]
FPS = 30
FEET = ["left_ankle", "left_toe", "right_ankle", "right_toe"]
# The feet case: a body walking 3 cm a frame (0.9 m/s) with little noise, whose feet are planted, lifted
# or left to slide with it.
FEET_FRAMES, FEET_STEP, FEET_NOISE, FEET_LIFT = 10, 0.03, 0.001, 0.2


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


def _cm_errors(futures: np.ndarray, truth: np.ndarray, root_relative: bool) -> dict:
    ade_k, fde_k = R.mpjpe_cm_per_sample(futures, truth, root_relative)
    ade, fde = R.mpjpe_cm(futures, truth, root_relative)
    return {"ade": ade, "fde": fde, "ade_per_sample": ade_k.tolist(), "fde_per_sample": fde_k.tolist()}


def _skating(future: np.ndarray) -> float | None:
    """The median contact speed of one sample; None (JSON null) where no step touched the floor."""
    median = R.median_contact_speed(R.contact_speeds(future, FPS, CONTACT_BAND))
    return None if np.isnan(median) else median


def _feet_case(rng) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(history, truth, futures [3, ...]): sample 0 plants its left foot and lifts its right one, sample 1
    plants the left and lets the right slide with the body, sample 2 lets both slide; the truth is
    sample 0's motion with its own noise."""
    velocity = np.array([FEET_STEP, 0.0, 0.0])
    history = _travel(rng, HISTORY_FRAMES, np.zeros(3), velocity)
    after = HISTORY_FRAMES * velocity
    left = [SKELETON.index(n) for n in FEET[:2]]
    right = [SKELETON.index(n) for n in FEET[2:]]

    def walk(plant_left: bool, lift_right: bool) -> np.ndarray:
        m = _rest_pose() + after + np.arange(FEET_FRAMES)[:, None, None] * velocity
        m = m + rng.normal(scale=FEET_NOISE, size=m.shape)
        if plant_left:
            m[:, left, 0] = m[:1, left, 0] + rng.normal(scale=FEET_NOISE, size=(FEET_FRAMES, 2))
        if lift_right:
            m[:, right, 1] += FEET_LIFT
        return m
    futures = np.stack([walk(True, True), walk(True, False), walk(False, False)])
    return history, walk(True, True), futures


def metrics_vector() -> dict:
    rng = np.random.default_rng(SEED)
    made = []
    for k, frames, truth_frames in CASES:
        start = np.array([rng.uniform(-2, 2), 0.0, rng.uniform(-2, 2)])
        velocity = np.array([rng.uniform(-0.05, 0.05), 0.0, rng.uniform(-0.05, 0.05)])
        history = _travel(rng, HISTORY_FRAMES, start, velocity)
        after = start + HISTORY_FRAMES * velocity
        truth = _travel(rng, truth_frames, after, velocity)
        futures = np.stack([_travel(rng, frames, after, velocity + rng.normal(scale=0.02, size=3) * [1, 0, 1])
                            for _ in range(k)])
        made.append((history, truth, futures))
    made.append(_feet_case(rng))          # drawn after the others, so theirs stay as they were
    cases = []
    for history, truth, futures in made:
        k, frames, truth_frames = len(futures), futures.shape[1], len(truth)
        feet = foot_height(futures)
        if np.abs(feet + DEPTH).min() < 1e-6:     # no case may sit on the floor test's edge
            raise ValueError("a foot lies within 1e-6 m of the depth: pick another seed")
        heights = futures[..., [SKELETON.index(n) for n in FEET], 1]
        if np.abs(heights - CONTACT_BAND).min() < 1e-6:     # nor on the contact band's edge
            raise ValueError("a foot joint lies within 1e-6 m of the contact band: pick another seed")
        reference = M.bone_lengths(history).mean(0)
        spread_last, spread_over = R.pose_spread_cm(futures)
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
            "mpjpe_cm": {"world": _cm_errors(futures, truth, root_relative=False),
                         "root_relative": _cm_errors(futures, truth, root_relative=True)},
            "pose_spread_cm": {"last": spread_last, "over_frames": spread_over},
            "fps": FPS, "band": CONTACT_BAND,
            "foot_skating": [_skating(f) for f in futures],
        })
    return {"about": "read-out metrics of K futures (export/eval/metrics.py): best-of-K and per-sample ADE and FDE "
                     "(whole-pose L2, WAT Eq. 12 / DLow; world frame and root-relative, futures cut to the truth's "
                     "frames), APD (DLow, whole sequence), bone length error against the history's mean bone "
                     "lengths, and the share of frames with a foot more than `depth` below y = 0, per sample; "
                     "export/eval/realism: mpjpe_cm, the mean per-joint distance in cm (best-of-K and per sample, "
                     "over frames and at the last truth frame, world and root-relative), pose_spread_cm, the mean "
                     "over sample pairs of the mean per-joint root-relative distance in cm (last frame, over "
                     "frames), and foot_skating, each sample's median foot contact speed in m/s (the lower of "
                     "ankle and toe per side below `band` at both frames of a step; null without contact). The "
                     "last case has planted, lifted and sliding feet",
            "cases": cases}
