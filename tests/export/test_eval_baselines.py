"""The deterministic baselines of export/eval/baselines.py on hand-built motions."""
import math

import numpy as np
import pytest

from export.data.skeleton import SKELETON
from export.eval import baselines as B
from export.eval.metrics import root_relative
from export.ops import facing
from export.ops.facing import rotate_about_y


def rest_pose() -> np.ndarray:
    """The skeleton at rest [J, 3] (it faces +x, the URDF's forward), root 0.9 m up."""
    pose = SKELETON.offsets.copy()
    for j, p in enumerate(SKELETON.parents):
        if p >= 0:
            pose[j] = pose[p] + SKELETON.offsets[j]
    return pose + [0.0, 0.9, 0.0]


def gait(frames: int, period: int, speed: float = 0.05) -> np.ndarray:
    """A sinusoidal "gait" [frames, J, 3]: every joint bobs and sways with its own phase, exactly
    periodic in `period` frames, while the body walks along +x at `speed` metres per frame."""
    t = np.arange(frames)[:, None]
    phase = np.arange(SKELETON.num_joints)[None] * 0.7
    out = np.repeat(rest_pose()[None], frames, axis=0)
    out[..., 1] += 0.05 * np.sin(2 * math.pi * t / period + phase)
    out[..., 2] += 0.03 * np.cos(2 * math.pi * t / period + 2 * phase)
    out[..., 0] += speed * t
    return out


def test_constant_velocity_by_hand():
    history = np.zeros((2, 1, 3))
    history[:, 0, 0] = [0.0, 1.0]
    assert B.constant_velocity(history, 3)[:, 0, 0].tolist() == [2.0, 3.0, 4.0]
    with pytest.raises(ValueError, match="two history frames"):
        B.constant_velocity(history[:1], 3)


def test_constant_velocity_continues_a_straight_translation_exactly():
    step = np.array([0.03, 0.0, -0.04])
    t = np.arange(20)[:, None, None]
    walk = rest_pose() + [1.0, 0.0, 2.0] + t * step        # 10 history frames, then the true 10
    assert B.constant_velocity(walk[:10], 10) == pytest.approx(walk[10:], abs=1e-12)


def test_cycle_costs_by_hand():
    # joint 1's height 0, 1, 0, 1, 0, 1 above a still root: period 2 fits, 1 and 3 are 1 m off
    h = np.zeros((6, 2, 3))
    h[:, 1, 1] = [0, 1, 0, 1, 0, 1]
    assert B.cycle_costs(h, min_period=1) == {1: 1.0, 2: 0.0, 3: 1.0}
    assert B.best_period(h, min_period=1) == 2
    assert B.repeat_last_cycle(h, 4, min_period=1)[:, 1, 1].tolist() == [0, 1, 0, 1]


def test_repeat_last_cycle_finds_the_gait_period_and_keeps_walking():
    for period in (10, 12):
        motion = gait(40 + 25, period)
        history = motion[:40]
        # 2 x period also fits exactly (when it fits in the history): ties go to the shortest
        assert B.best_period(history) == period
        assert B.repeat_last_cycle(history, 25) == pytest.approx(motion[40:], abs=1e-9)


def test_repeat_last_cycle_holds_the_last_pose_for_a_short_history():
    history = gait(15, 10)                                    # shorter than 2 x min_period = 16
    assert B.best_period(history) is None
    held = B.repeat_last_cycle(history, 5)
    assert held.shape == (5, SKELETON.num_joints, 3) and np.all(held == history[-1])


def world_windows(count: int, frames: int, seed: int = 0) -> np.ndarray:
    """[count, frames, J, 3] world windows: rest poses walking off in their own directions, with noise."""
    rng = np.random.default_rng(seed)
    t = np.arange(frames)[:, None, None]
    return np.stack([rest_pose() + [rng.uniform(-3, 3), 0, rng.uniform(-3, 3)]
                     + t * [rng.uniform(-0.05, 0.05), 0, rng.uniform(-0.05, 0.05)]
                     + rng.normal(scale=0.05, size=(frames, SKELETON.num_joints, 3)) for _ in range(count)])


def test_metrics_root_relative_is_facings_for_world_positions():
    w = world_windows(1, 5)[0]
    assert root_relative(w) == pytest.approx(facing.root_relative(facing.split_root(w)), abs=1e-12)


def test_nearest_index_by_hand():
    train = np.zeros((3, 2, 2, 3))                              # canonical: joint 1 relative to the root
    train[:, :, 1, 1] = [[0.0, 0.0], [1.0, 1.0], [0.4, 0.0]]   # joint 1's heights
    train[1, :, 0, 0] = [-0.5, 0.0]                            # a root channel (travel): left out
    query = np.zeros((2, 2, 3))
    query[:, 1, 1] = [0.5, 0.5]                                # distances 0.707, 0.707, 0.510
    query[:, 0, 2] = [-9.0, 0.0]
    assert B.nearest_index(query, train) == 2
    with pytest.raises(ValueError, match="training histories"):
        B.nearest_index(query[:1], train)


def test_nearest_window_turns_and_moves_the_training_future_onto_the_query():
    n = 10
    world = world_windows(4, n + 6)
    canonical = np.stack([facing.canonicalise(w, n - 1, SKELETON)[0] for w in world])   # as data/windows.py
    hs, fs = canonical[:, :n], canonical[:, n:]
    angle, shift = 0.7, np.array([3.0, 0.0, -2.0])
    query = rotate_about_y(world[2, :n], angle) + shift       # window 2, elsewhere and turned
    expected = rotate_about_y(world[2, n:], angle) + shift
    assert B.nearest_window(query, hs, fs) == pytest.approx(expected, abs=1e-9)
    assert B.nearest_window(world[1, :n], hs, fs) == pytest.approx(world[1, n:], abs=1e-9)


def test_nearest_indices_is_nearest_index_for_every_query():
    n = 10
    world = world_windows(40, n + 4, seed=3)
    canonical = np.stack([facing.canonicalise(w, n - 1, SKELETON)[0] for w in world])
    queries = np.stack([facing.canonicalise(w, n - 1, SKELETON)[0] for w in world_windows(9, n, seed=4)])
    got = B.nearest_indices(queries, canonical[:, :n], chunk=4)
    assert got.tolist() == [B.nearest_index(q, canonical[:, :n]) for q in queries]
    assert B.nearest_indices(canonical[:5, :n], canonical[:, :n]).tolist() == [0, 1, 2, 3, 4]   # itself
    with pytest.raises(ValueError, match="training histories"):
        B.nearest_indices(queries[:, :5], canonical[:, :n])


def test_the_harness_lookup_is_nearest_window_over_every_training_window(deepmimic):
    """export/eval/harness.nearest_futures streams the bank clip by clip; it must pick what nearest_window
    picks over the whole bank, and give a training window its own future back."""
    from export.data.windows import windows
    from export.eval.harness import nearest_futures
    clips = [c for c in deepmimic.values() if c.split.role != "test"][:4]
    h, t = 10, 12
    bank = windows(clips, "train", h + t, h, stride=3, mirror=True)
    hs, fs = np.stack([w.positions[:h] for w in bank]), np.stack([w.positions[h:] for w in bank])
    walk = deepmimic["walker_walk_forward"].positions
    queries = [walk[s:s + h] for s in (0, 7, len(walk) - h)]
    got = nearest_futures(queries, clips, h, t, stride=3)
    for q, g in zip(queries, got):
        assert g == pytest.approx(B.nearest_window(q, hs, fs), abs=1e-9)
    own = clips[0].positions
    assert nearest_futures([own[6:6 + h]], clips, h, t, stride=3)[0] == pytest.approx(own[6 + h:6 + h + t], abs=1e-9)
