"""Keypose extraction, labels, pruning, duration classes, proximity softmax, interpolation and
temperature draws (export/ops/keyposes.py, proximity.py, keypose_interpolation.py)."""
import numpy as np

from export.ops.facing import root_relative, split_root
import pytest

from export.data.skeleton import SKELETON
from export.ops import keyposes as kp
from export.ops.facing import facing_angle, rotate_about_y
from export.ops.keypose_interpolation import interpolate, keypose_times
from export.ops.proximity import (NOISE_PER_TEMPERATURE, choose_temperature, face_forward, label_distribution,
                                  proximity, sample_index, softmax)
from export.rng import Prng

J = SKELETON.num_joints


def _pose(seed: int) -> np.ndarray:
    return np.random.default_rng(seed).normal(size=(J, 3))


def _piecewise(poses: list[np.ndarray], lengths: list[int]) -> np.ndarray:
    """Exactly linear segments between the given poses."""
    frames = [poses[0]]
    for a, b, n in zip(poses, poses[1:], lengths):
        frames += [a + (b - a) * t / n for t in range(1, n + 1)]
    return np.stack(frames)


def test_extraction_finds_the_corners_of_piecewise_linear_motion():
    motion = _piecewise([_pose(0), _pose(1), _pose(2), _pose(3)], [7, 12, 5])
    assert kp.extract(motion, 0.05) == [0, 7, 19, 24]
    # a straight line needs only its two ends, whatever the threshold
    assert kp.extract(_piecewise([_pose(0), _pose(1)], [20]), 1e-6) == [0, 20]


def test_extraction_inserts_the_frame_of_largest_error_until_the_mean_error_is_below_threshold():
    rng = np.random.default_rng(3)
    motion = np.cumsum(rng.normal(scale=0.05, size=(40, J, 3)), axis=0)
    keys = kp.extract(motion, 0.3)
    assert keys[0] == 0 and keys[-1] == 39 and keys == sorted(set(keys))
    for a, b in zip(keys, keys[1:]):          # every final segment meets the threshold
        if b - a >= 2:
            assert kp.frame_errors(motion, a, b)[1:-1].mean() < 0.3
    # the first insertion is the frame of largest error against the end-to-end interpolation
    errors = kp.frame_errors(motion, 0, 39)
    assert 1 + int(np.argmax(errors[1:-1])) in keys
    assert set(kp.extract(motion, 0.6)) <= set(keys) <= set(kp.extract(motion, 0.1))
    with pytest.raises(ValueError, match="threshold must be positive"):
        kp.extract(motion, 0)


def test_observed_keyposes_use_only_frames_up_to_the_present():
    rng = np.random.default_rng(4)
    motion = np.cumsum(rng.normal(scale=0.05, size=(60, J, 3)), axis=0)
    history = kp.extract(motion[:30], 0.3)
    changed = motion.copy()
    changed[30:] += 5.0                        # the future changes; the history's keyposes do not
    assert kp.extract(changed[:30], 0.3) == history and history[-1] == 29


def test_extraction_on_the_deepmimic_clips_matches_the_recorded_numbers(deepmimic):
    # keyposes act on root-relative poses (ops/facing.py); the numbers are those of ops/keyposes.py's comment
    poses = [root_relative(split_root(c.positions)) for c in deepmimic.values() if not c.name.startswith("walker_")]
    counts = [len(kp.extract(p, kp.THRESHOLD)) for p in poses]
    gaps = np.concatenate([np.diff(kp.extract(p, kp.THRESHOLD)) for p in poses])
    assert len(counts) == 15 and sum(counts) == 171 and min(counts) == 4 and max(counts) == 25
    assert 6.0 < gaps.mean() < 6.6


def test_nearest_centre_and_pruning():
    centres = np.stack([_pose(i) for i in range(4)])
    values = centres[[2, 2, 0, 3]] + 0.01
    labels, margins = kp.nearest_centre(values, centres)
    assert labels.tolist() == [2, 2, 0, 3] and np.all(margins > 0)
    assert kp.prune([3, 3, 3, 1]) == [0, 2, 3]           # a held pose keeps its first and last keypose
    assert kp.prune([1, 2, 2, 2, 2, 5, 5]) == [0, 1, 4, 5, 6]
    assert kp.prune([7, 7, 7, 7]) == [0, 3] and kp.prune([4]) == [0] and kp.prune([]) == []


def test_bound_gaps_splits_only_gaps_longer_than_the_longest_class():
    assert kp.bound_gaps([0, 5, 35], 30) == [0, 5, 35]                 # 30 frames apart: left alone
    assert kp.bound_gaps([0, 90], 30) == [0, 30, 60, 90]
    assert kp.bound_gaps([10, 45], 30) == [10, 40, 45]                  # steps of 30, the remainder last
    out = kp.bound_gaps([0, 3, 100, 161, 170], 30)
    assert set([0, 3, 100, 161, 170]) <= set(out) and np.diff(out).max() <= 30 and out == sorted(out)
    assert kp.bound_gaps([], 30) == [] and kp.bound_gaps([7], 30) == [7]
    with pytest.raises(ValueError, match="at least 1 frame"):
        kp.bound_gaps([0, 5], 0)


def test_duration_classes_are_the_papers_scaled_to_30_hz():
    assert len(kp.DURATION_BOUNDS) == len(kp.DURATION_LENGTHS) == 5
    np.testing.assert_allclose(np.asarray(kp.DURATION_BOUNDS[1:]) / np.array([4, 10, 14, 25]), 1.2, atol=0.05)
    for c, length in enumerate(kp.DURATION_LENGTHS):    # each class stands for a length inside it
        assert kp.duration_class(length) == c
    assert [kp.duration_class(d) for d in (1, 4, 5, 11, 12, 16, 17, 29, 30, 300)] == [0, 0, 1, 1, 2, 2, 3, 3, 4, 4]
    with pytest.raises(ValueError, match="at least 1 frame"):
        kp.duration_class(0)


def test_face_forward_removes_heading_only():
    pose = _pose(5)
    turned = rotate_about_y(pose, 1.1)
    np.testing.assert_allclose(face_forward(turned[None])[0], face_forward(pose[None])[0], atol=1e-12)
    assert abs(facing_angle(face_forward(turned[None])[0], SKELETON)) < 1e-12


def test_proximity_softmax_and_the_temperature_choice():
    centres = np.stack([_pose(i) for i in range(6)])
    values = centres[[1, 4]] + 0.02
    prox = proximity(values, centres)
    want = -np.linalg.norm(values[:, None] - centres[None], axis=-1).mean(-1)
    np.testing.assert_allclose(prox, want)
    p = label_distribution(values, centres, 0.1)
    np.testing.assert_allclose(p.sum(-1), 1.0)
    assert p.argmax(-1).tolist() == [1, 4]
    assert label_distribution(values, centres, 0.01).max() > label_distribution(values, centres, 1.0).max()
    many = np.concatenate([centres + np.random.default_rng(i).normal(scale=0.3, size=centres.shape) for i in range(5)])
    t = choose_temperature(many, centres, 0.6)
    assert abs(softmax(proximity(many, centres), t).max(-1).mean() - 0.6) < 0.01
    assert NOISE_PER_TEMPERATURE == pytest.approx(0.1 / 0.03)
    with pytest.raises(ValueError, match="temperature must be positive"):
        softmax(prox, 0.0)


def test_interpolation_starts_from_the_present_and_reaches_each_keypose_on_time():
    present, a, b = _pose(0), _pose(1), _pose(2)
    out = interpolate(present, np.stack([a, b]), [4, 6], 14)
    assert out.shape == (14, J, 3)
    np.testing.assert_allclose(out[0], present + (a - present) / 4)   # one step from the present, no jump
    np.testing.assert_allclose(out[3], a)
    np.testing.assert_allclose(out[6], a + 3 * (b - a) / 6)          # Eq. 3
    np.testing.assert_allclose(out[9], b)
    np.testing.assert_allclose(out[10:], np.repeat(b[None], 4, 0))    # held after the last keypose
    assert keypose_times([4, 6]).tolist() == [4, 10]
    with pytest.raises(ValueError, match="at least 1 frame"):
        interpolate(present, a[None], [0], 3)


def test_temperature_draws_follow_the_distribution_and_report_margins():
    logits = np.array([0.2, -1.0, 1.1, 0.4])
    p = softmax(logits, 0.7)
    rng = Prng(5)
    draws = [sample_index(logits, 0.7, rng.uniform()) for _ in range(20000)]
    freq = np.bincount([i for i, _ in draws], minlength=4) / len(draws)
    np.testing.assert_allclose(freq, p, atol=0.015)
    cdf = np.cumsum(p)
    i, m = sample_index(logits, 0.7, 0.5)
    assert cdf[i - 1] <= 0.5 < cdf[i] and m == pytest.approx(min(0.5 - cdf[i - 1], cdf[i] - 0.5))
    assert sample_index(np.array([3.0]), 1.0, 0.4) == (0, np.inf)
    # nearly all mass on the largest logit at the lowest offered temperature
    assert softmax(np.array([1.0, 2.0, 0.5]), 0.05)[1] > 0.99


def test_the_travel_follows_the_history_pace_by_hand():
    from export.ops.keypose_travel import PACE_RANGE, pace, travel
    table = np.array([[0.0, 0.03], [0.0, 0.05], [0.0, 0.0]])        # metres per frame, facing frame
    walk = np.stack([np.zeros(11), np.arange(11) * 0.06], 1)        # 0.06 m/frame forward
    # the history's labels 0 and 1 travel 0.04 m/frame on average: the pace is 0.06 / 0.04
    assert pace(walk, [0, 1], table) == pytest.approx(1.5)
    path = travel([1, 0], [2, 3], table, 6, scale=1.5)
    np.testing.assert_allclose(path[:, 1], np.cumsum([0.075, 0.075, 0.045, 0.045, 0.045, 0.0]))
    # a standing history stops the future's travel (down to the range's floor); labels that barely
    # travel set no pace; a racing history is capped
    assert pace(np.zeros((11, 2)), [0, 1], table) == PACE_RANGE[0]
    assert pace(walk, [2], table) == 1.0
    assert pace(walk * 100, [0, 1], table) == PACE_RANGE[1]
