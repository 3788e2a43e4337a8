"""The realism measures of export/eval/realism on cases small enough to compute by hand, and for each one
a case that a wrong definition would fail (a sliding foot vs a planted one, travel vs limb motion, ...)."""
import math

import numpy as np
import pytest

from export.data.skeleton import SKELETON
from export.eval import metrics as M
from export.eval import realism as R


def arm(heights, root=(0.0, 0.0)):
    """[T, 2, 3]: the root at (root x, 1, root z) and a second joint above it at the given heights."""
    out = np.zeros((len(heights), 2, 3))
    out[:, :, 0], out[:, :, 2] = root
    out[:, 0, 1] = 1.0
    out[:, 1, 1] = heights
    return out


# --- speed ----------------------------------------------------------------------------------------------


def test_joint_speed_per_second_by_hand_with_a_partial_last_second():
    # steps of the second joint 0.1 .. 0.5 m; the root stands: mean over the 2 joints is half of it, x 2 fps
    future = arm([0.0, 0.1, 0.3, 0.6, 1.0, 1.5])
    got = R.joint_speed_per_second(future, fps=2)
    assert got == pytest.approx([(0.05 + 0.1) / 2 * 2, (0.15 + 0.2) / 2 * 2, 0.25 * 2])   # 0.15, 0.35, 0.5


def test_the_present_is_prepended_so_the_first_second_holds_the_step_into_the_future():
    history = arm([5.0, -0.3])                          # its last frame is the present
    got = R.joint_speed_per_second(arm([0.0, 0.1, 0.3, 0.6, 1.0, 1.5]), history, fps=2)
    assert got == pytest.approx([0.2, 0.25, 0.45])     # steps 0.3, 0.1 | 0.2, 0.3 | 0.4, 0.5
    futures = np.stack([arm([0.0, 0.1]), arm([0.0, 0.0])])   # K = 2 futures share the one history
    assert R.joint_speed_per_second(futures, history, fps=2)[:, 0] == pytest.approx([0.2, 0.15])


def test_travel_is_root_speed_not_joint_speed():
    walk = np.stack([arm([1.5] * 4, root=(0.1 * t, 0.0))[0] for t in range(4)])   # rigid, 0.1 m a frame along x
    assert R.joint_speed_per_second(walk) == pytest.approx([0.0])
    assert R.root_speed_per_second(walk) == pytest.approx([3.0])
    hop = arm([1.5] * 3)
    hop[:, :, 1] += [[0.0], [0.2], [0.4]]                                        # vertical: not horizontal speed
    assert R.root_speed_per_second(hop) == pytest.approx([0.0])
    with pytest.raises(ValueError, match="two frames"):
        R.joint_speed_per_second(walk[:1])


def test_ratio_to_truth_is_a_ratio_of_means():
    assert R.ratio_to_truth([[1.0, 2.0], [3.0, 4.0]], [[2.0, 0.0], [2.0, 0.0]]) == pytest.approx([1.0, math.nan],
                                                                                                 nan_ok=True)
    # a nearly still truth: the mean of per-window ratios would be (100 + 0.5025) / 2 = 50.25
    assert R.ratio_to_truth([[1.0], [1.0]], [[0.01], [1.99]]) == pytest.approx([1.0])
    samples = np.array([[[1.0], [3.0]], [[2.0], [2.0]]])        # [W, K, S]: pooled over samples too
    assert R.ratio_to_truth(samples, [[1.0], [3.0]]) == pytest.approx([1.0])


# --- follow ---------------------------------------------------------------------------------------------


def test_history_speed_and_spearman_by_hand():
    assert R.history_speed(arm([0.0, 0.1, 0.2]), fps=30) == pytest.approx(1.5)   # 0.1 m / 2 joints x 30
    assert R.history_speed(np.stack([arm([0.0, 0.1]), arm([0.0, 0.0])])) == pytest.approx([1.5, 0.0])
    # ranks 1 2 3 4 against 1 2 4 3: rho = 1 - 6 * (1 + 1) / (4 * 15) = 0.8
    assert R.follow([1.0, 2.0, 3.0, 4.0], [10.0, 20.0, 40.0, 30.0]) == pytest.approx(0.8)
    # ranks, not values: any increasing map of the future speeds keeps rho = 1
    assert R.follow([0.1, 0.2, 0.3], [0.0, 0.01, 5.0]) == pytest.approx(1.0)


def test_follow_is_nan_for_too_few_windows_or_a_constant_input():
    assert math.isnan(R.follow([1.0, 2.0], [1.0, 2.0]))
    assert math.isnan(R.follow([1.0, 2.0, 3.0], [0.5, 0.5, 0.5]))    # a frozen model: nothing follows
    assert math.isnan(R.follow([1.0, 1.0, 1.0], [0.1, 0.2, 0.3]))
    assert math.isnan(R.follow([1.0, 2.0, math.nan], [0.1, 0.2, 0.3]))


# --- skating --------------------------------------------------------------------------------------------


def feet(frames, left_toe=None, left_ankle=None, right_toe=None, right_ankle=None):
    """[frames, 18, 3] with every joint at y = 1 except the given feet: lists of (x, y) per frame (z = 0)."""
    m = np.zeros((frames, SKELETON.num_joints, 3))
    m[:, :, 1] = 1.0
    for name, xy in [("left_toe", left_toe), ("left_ankle", left_ankle),
                     ("right_toe", right_toe), ("right_ankle", right_ankle)]:
        if xy is not None:
            m[:, SKELETON.index(name), [0, 1]] = xy
    return m


def test_a_planted_foot_reads_zero_and_a_sliding_one_its_speed():
    planted = [(0.5, 0.0)] * 3
    sliding = [(0.02 * t, 0.01) for t in range(3)]             # 2 cm a frame at 1 cm height: 0.6 m/s
    m = feet(3, left_toe=planted, right_toe=sliding)
    assert R.contact_speeds(m) == pytest.approx([0.0, 0.0, 0.6, 0.6])   # left then right, in time order
    assert R.median_contact_speed(R.contact_speeds(m)) == pytest.approx(0.3)
    assert R.median_contact_speed(R.contact_speeds(feet(3, left_toe=planted, right_toe=planted))) == 0.0


def test_contact_needs_both_frames_within_the_band():
    lifting = [(0.0, 0.01), (0.1, 0.02), (0.2, 0.05), (0.3, 0.03)]   # y = 0.03 exactly is not within
    assert R.contact_speeds(feet(4, left_toe=lifting)) == pytest.approx([3.0])
    assert math.isnan(R.median_contact_speed(R.contact_speeds(feet(4))))   # no foot near the floor


def test_the_joint_lower_at_t_is_followed_to_t_plus_1_through_a_heel_toe_roll():
    # frame 0 on the heel (ankle lower), frame 1 rolled onto the toe 20 cm ahead; the ankle moved 1 cm.
    # Comparing the lower joint of each frame would read the ankle-to-toe distance: 0.2 m x 30 = 6 m/s.
    m = feet(2, left_ankle=[(0.0, 0.0), (0.01, 0.02)], left_toe=[(0.2, 0.02), (0.2, 0.0)])
    assert R.contact_speeds(m) == pytest.approx([0.3])


def test_skating_is_measured_in_the_world_not_root_relative():
    m = feet(3, left_toe=[(0.5, 0.0)] * 3)
    m[:, 0, 0] = [0.0, 0.1, 0.2]                                # the root walks over the planted foot
    assert R.contact_speeds(m) == pytest.approx([0.0, 0.0])


# --- jump height ----------------------------------------------------------------------------------------


def test_hip_vertical_range_over_a_motion_and_a_slice():
    m = np.zeros((4, 2, 3))
    m[:, 0, 1] = [0.9, 1.2, 0.8, 1.0]
    m[:, 1, 1] = [0.0, 5.0, 0.0, 0.0]                           # not the hip
    assert R.hip_vertical_range(m) == pytest.approx(0.4)
    assert R.hip_vertical_range(m, start=2) == pytest.approx(0.2)
    assert R.hip_vertical_range(np.stack([m, m * 2])) == pytest.approx([0.4, 0.8])
    with pytest.raises(ValueError, match="no frames"):
        R.hip_vertical_range(m, start=4)


# --- coverage -------------------------------------------------------------------------------------------


def heights(*ys):
    """[K, 1, 1, 3]: one frame of the root joint at height y (root-relative keeps only the height)."""
    out = np.zeros((len(ys), 1, 1, 3))
    out[:, 0, 0, 1] = ys
    return out


def test_outside_by_hand():
    samples = heights(0.0, 1.0, 2.0)
    # truth 10: 9 from the samples' mean 1; the farthest sample, 0, is 13/3 from the mean of 1, 2 and 10
    assert R.outside(samples, heights(10.0)[0])
    # truth 1.5: 0.5 from the samples' mean; sample 0 is 1.5 from the mean of 1, 2 and 1.5
    assert not R.outside(samples, heights(1.5)[0])
    # horizontal offsets do not count (root-relative), frames past the truth are cut
    moved = np.concatenate([samples, heights(99.0, 99.0, 99.0)], axis=1)
    moved[:, :, :, 0] += 7.0
    assert R.outside(moved, heights(10.0)[0]) and not R.outside(moved, heights(1.5)[0])
    with pytest.raises(ValueError, match="two samples"):
        R.outside(samples[:1], heights(10.0)[0])


def test_a_calibrated_sampler_leaves_the_truth_outside_one_time_in_k_plus_1():
    """Truth and K = 4 samples drawn alike: the share is 1/5. Measuring the samples from their own mean
    (the truth from it too) would put the truth outside far more often."""
    rng = np.random.default_rng(0)
    k, trials = 4, 8000
    draws = rng.normal(size=(trials, k + 1, 2, 3, 3))
    share = np.mean([R.outside(d[1:], d[0]) for d in draws])
    assert R.calibrated(k) == 0.2
    assert abs(share - 0.2) < 4 * math.sqrt(0.2 * 0.8 / trials)
    flat = M.root_relative(draws).reshape(trials, k + 1, -1)
    centre = flat[:, 1:].mean(1, keepdims=True)
    d = np.linalg.norm(flat - centre, axis=-1)
    assert (d[:, 0] > d[:, 1:].max(1)).mean() > 0.3            # the naive rule: not calibrated


# --- MPJPE and pose spread (cm) -------------------------------------------------------------------------


def test_mpjpe_cm_by_hand_world_and_root_relative():
    truth = np.zeros((2, 2, 3))
    s = np.zeros((3, 2, 3))                                     # a third frame past the truth is cut
    s[0, 0] = [3.0, 4.0, 0.0]                                   # frame 0: 5 and 0; frame 1: 1 and 1
    s[1] = [0.0, 1.0, 0.0]
    s[2] = 9.0
    ade, fde = R.mpjpe_cm_per_sample(s[None], truth, root_relative=False)
    assert ade == pytest.approx([175.0]) and fde == pytest.approx([100.0])
    shifted = truth[None] + [2.0, 0.0, 0.0]                    # the whole body 2 m along x
    assert R.mpjpe_cm(shifted, truth, root_relative=False) == pytest.approx((200.0, 200.0))
    assert R.mpjpe_cm(shifted, truth, root_relative=True) == pytest.approx((0.0, 0.0))
    # best-of-K, each minimised on its own: late has the lower mean, early the lower final error
    late = np.zeros((2, 2, 3))
    late[1] = 0.3                                               # 0, 0 then sqrt(0.27) twice
    early = np.zeros((2, 2, 3))
    early[0] = 1.0                                              # sqrt(3) twice, then 0, 0
    best = R.mpjpe_cm(np.stack([late, early]), truth, root_relative=False)
    assert best == pytest.approx((math.sqrt(0.27) * 50, 0.0))
    with pytest.raises(ValueError, match="fewer than"):
        R.mpjpe_cm(s[None, :1], truth, root_relative=False)


def test_whole_pose_l2_is_sqrt_18_times_the_per_joint_error_when_every_joint_is_off_alike():
    rng = np.random.default_rng(1)
    truth = rng.normal(size=(3, SKELETON.num_joints, 3))
    direction = rng.normal(size=(3, SKELETON.num_joints, 3))
    off = truth + 0.05 * direction / np.linalg.norm(direction, axis=-1, keepdims=True)   # every joint 5 cm off
    ade_cm, fde_cm = R.mpjpe_cm(off[None], truth, root_relative=False)
    assert ade_cm == pytest.approx(5.0) and fde_cm == pytest.approx(5.0)
    ade_l2, fde_l2 = M.ade_fde(off[None], truth, root_relative=False)
    assert ade_l2 == pytest.approx(math.sqrt(18) * ade_cm / 100, rel=1e-12)
    assert fde_l2 == pytest.approx(math.sqrt(18) * fde_cm / 100, rel=1e-12)
    # one joint carrying all the error: the whole-pose norm is 18x the mean, not sqrt(18)x
    one = truth.copy()
    one[:, 5, 0] += 0.18
    assert R.mpjpe_cm(one[None], truth, root_relative=False)[0] == pytest.approx(1.0)
    assert M.ade_fde(one[None], truth, root_relative=False)[0] == pytest.approx(0.18)


def test_pose_spread_cm_by_hand():
    samples = np.zeros((3, 2, 1, 3))
    samples[:, :, 0, 1] = [[0.0, 0.0], [1.0, 2.0], [3.0, 4.0]]   # pairs per frame: (1, 2), (3, 4), (2, 2)
    last, over = R.pose_spread_cm(samples)
    assert last == pytest.approx((2 + 4 + 2) / 3 * 100)
    assert over == pytest.approx((1.5 + 3.5 + 2.0) / 3 * 100)
    apart = samples[:1].repeat(2, axis=0)
    apart[1, :, :, 0] += 5.0                                     # the same pose 5 m to the side
    assert R.pose_spread_cm(apart) == pytest.approx((0.0, 0.0))
    assert R.pose_spread_cm(samples[:1]) == (0.0, 0.0)


# --- CMD ------------------------------------------------------------------------------------------------


def test_displacement_per_frame_is_over_joints_and_samples():
    futures = np.stack([arm([0.0, 0.1, 0.3]), arm([0.0, 0.3, 0.3])])
    assert R.displacement_per_frame(futures) == pytest.approx([0.1, 0.05])   # [.05, .1] and [.15, 0]
    travel = np.stack([arm([0.0, 0.0], root=(x, 0.0))[0] for x in (0.0, 0.4)])
    assert R.displacement_per_frame(travel) == pytest.approx([0.0])
    assert R.displacement_per_frame(travel, root_relative=False) == pytest.approx([0.4])


def test_cmd_by_hand_weighs_an_early_departure_more():
    # F = 3 frames, M_t for t = 1, 2 weighted F - t = 2, 1
    assert R.cmd([0.1, 0.05], 0.05) == pytest.approx(0.1)
    assert R.cmd([0.05, 0.1], 0.05) == pytest.approx(0.05)       # the same departure one frame later
    assert R.cmd([0.0, 0.0, 0.0], 0.01) == pytest.approx(0.06)   # frozen: 3 + 2 + 1 times M
    assert R.cmd([0.02, 0.0], 0.01) == pytest.approx(0.03)       # |M_t - M|: too fast counts as too slow


def test_cmd_by_class_weighs_each_class_by_its_share_of_windows():
    per_window = [[0.1, 0.05], [0.05, 0.05], [0.0, 0.0]]
    got = R.cmd_by_class(per_window, ["a", "a", "b"], {"a": 0.05, "b": 0.02})
    # a: the mean M_t [0.075, 0.05] gives 2 x 0.025 = 0.05; b: 2 x 0.02 + 0.02 = 0.06
    assert got == pytest.approx(0.05 * 2 / 3 + 0.06 / 3)
    with pytest.raises(ValueError, match="classes"):
        R.cmd_by_class(per_window, ["a"], {"a": 0.05})


# --- stops ----------------------------------------------------------------------------------------------


def test_full_length_share():
    assert R.full_length_share([90, 60, 90, 120], 90) == 0.75
    assert R.full_length_share([[89, 90], [30, 45]], 90) == 0.25
    assert math.isnan(R.full_length_share([], 90))
