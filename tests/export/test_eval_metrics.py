"""Every metric of export/eval on a case small enough to compute by hand."""
import math

import numpy as np
import pytest

from export.eval import metrics as M
from export.eval.fid import FeatureSpace, frechet
from export.eval import stats as S
from export.eval.stats import FAILS, HOLDS, INCONCLUSIVE, MISSING, combine, decide, summarise
from export.ops.dct_smoothness import smoothness


def motion(xs, joints=1, y=0.0):
    """[T, joints, 3] with every joint at (x_t, y, 0)."""
    out = np.zeros((len(xs), joints, 3))
    out[:, :, 0] = np.asarray(xs, dtype=float)[:, None]
    out[:, :, 1] = y
    return out


def test_diversity_is_the_mean_pairwise_mean_pose_distance():
    a = np.zeros((2, 1, 3))
    b = np.zeros((2, 1, 3))
    b[0, 0] = [3, 4, 0]                      # frame distances 5 and 0
    assert M.diversity(np.stack([a, b])) == pytest.approx(2.5)
    c3 = [np.full((2, 1, 3), 0.0), np.tile([[[3.0, 4.0, 0.0]]], (2, 1, 1)), np.tile([[[6.0, 8.0, 0.0]]], (2, 1, 1))]
    assert M.diversity(np.stack(c3)) == pytest.approx((5 + 10 + 5) / 3)
    assert M.diversity(a[None]) == 0.0       # one sample has no pairs


def test_pose_distance_is_over_the_whole_pose_not_per_joint():
    a, b = motion([0.0], joints=2), motion([1.0], joints=2)
    assert M.diversity(np.stack([a, b])) == pytest.approx(math.sqrt(2))   # WAT Eq. 10: ||y_i - y_j||_2
    assert M.mpjpe_curves(b[None], a)[0, 0] == pytest.approx(1.0)        # Keyposes MPJPE: mean per joint


def test_diversity_after_dtw_aligns_time_shifts_away():
    a = motion([0, 1, 2])
    b = motion([0, 0, 1, 2])                  # the same motion, one frame late
    assert M.diversity_dtw([a, b]) == pytest.approx(0.0)
    assert M.diversity_dtw([a, motion([0, 0, 1, 2], y=1.0)]) == pytest.approx(1.0)
    aa, bb = M.dtw_align(a, b)
    assert len(aa) == len(bb) == 4


def test_ade_is_best_of_k_over_the_truth_length():
    truth = np.zeros((2, 1, 3))
    s1 = motion([1, 1, 9])                    # the third frame is past the truth and ignored
    s2 = motion([0, 3, 0])
    assert M.ade(np.stack([s1, s2]), truth) == pytest.approx(1.0)
    assert M.ade(np.stack([s2]), truth) == pytest.approx(1.5)


def test_ade_after_dtw():
    truth = motion([0, 1, 2])
    assert M.ade_dtw([motion([0, 0, 1, 2]), motion([5, 5, 5])], truth) == pytest.approx(0.0)
    assert M.ade_dtw([motion([0, 1, 2], y=0.5)], truth) == pytest.approx(0.5)


def test_mpjpe_ave_and_best():
    truth = np.zeros((3, 2, 3))
    s1 = motion([0.1, 0.1, 0.5], joints=2)    # mean 0.233
    s2 = motion([0.3, 0.3, 0.2], joints=2)    # mean 0.267
    ave, best = M.mpjpe_at(np.stack([s1, s2]), truth, 2)
    assert ave == pytest.approx(0.5)          # the sample with the lowest average error, at frame 2
    assert best == pytest.approx(0.2)         # the lowest error at frame 2
    with pytest.raises(ValueError, match="outside"):
        M.mpjpe_at(np.stack([s1]), truth, 3)


def test_pskl_by_hand():
    truth = motion([1, 0, 0, 0])[None]        # impulse: flat power spectrum [1/4] * 4
    pred = motion([2, 1, 0, 0])[None]         # |FFT|^2 = [9, 5, 1, 5] -> [.45, .25, .05, .25]
    gt_pred, pred_gt = M.pskl(truth, pred)
    assert gt_pred == pytest.approx(0.25 * math.log(25 / 9), rel=1e-6)
    assert pred_gt == pytest.approx(0.45 * math.log(1.8) + 0.05 * math.log(0.2), rel=1e-6)
    assert M.pskl(truth, 2 * truth) == pytest.approx((0.0, 0.0), abs=1e-9)   # scale does not matter
    with pytest.raises(ValueError, match="one length"):
        M.pskl(truth, motion([1, 0, 0])[None])


def test_joint_speed():
    m = motion([0.0, 0.1, 0.3])
    assert M.joint_speed(m, 30.0) == pytest.approx(4.5)
    assert M.joint_speed(m, 30.0, last_frames=1) == pytest.approx(6.0)
    with pytest.raises(ValueError, match="two frames"):
        M.joint_speed(m[:1], 30.0)


def test_transition_smoothness_calls_eq4():
    still = np.ones((10, 2, 3))
    assert M.transition_smoothness(still, still) == pytest.approx(0.0, abs=1e-20)   # a constant is DCT basis 0
    cut = np.zeros((10, 2, 3))
    assert M.transition_smoothness(np.ones((12, 2, 3)), cut) == pytest.approx(smoothness(still, cut))
    assert M.transition_smoothness(still, cut) > 0.1
    with pytest.raises(ValueError, match="10 frames on each side"):
        M.transition_smoothness(still[:5], cut)


def test_length_histogram_and_accuracy():
    assert M.length_histogram([5, 10, 15, 30], [0, 10, 20, 30]) == [1, 2, 1]
    assert M.accuracy(np.array([1, 2, 3]), np.array([1, 0, 3])) == pytest.approx(2 / 3)
    with pytest.raises(ValueError, match="equal non-empty"):
        M.accuracy(np.array([1]), np.array([1, 2]))
    # nine of class 0 all right, one of class 1 wrong: plain 0.9, mean per class 0.5
    labels = np.array([0] * 9 + [1])
    assert M.accuracy(np.zeros(10, dtype=int), labels) == pytest.approx(0.9)
    assert M.balanced_accuracy(np.zeros(10, dtype=int), labels) == pytest.approx(0.5)


def test_noise_diversity_closed_form_and_monte_carlo():
    sigma = 0.5
    assert M.noise_diversity(sigma, 1) == pytest.approx(2 * sigma / math.sqrt(math.pi))   # E|X - Y|
    assert M.noise_diversity(sigma, 2) == pytest.approx(sigma * math.sqrt(math.pi))       # Rayleigh mean
    rng = np.random.default_rng(0)
    samples = rng.normal(0, 0.02, (10, 400, 18, 3))
    assert M.diversity(samples) == pytest.approx(M.noise_diversity(0.02, 54), rel=0.01)


def test_frechet_by_hand():
    a = np.array([[1, 2], [1, -2], [-1, 2], [-1, -2]], dtype=float)   # mean 0, cov diag(4/3, 16/3)
    b = 2 * a + [3, 0]                                                 # mean (3, 0), cov diag(16/3, 64/3)
    assert frechet(a, b) == pytest.approx(9 + 4 / 3 + 16 / 3)
    assert frechet(a, a) == pytest.approx(0.0, abs=1e-9)
    with pytest.raises(ValueError, match="two feature rows"):
        frechet(a[:1], b)


def test_feature_space_keeps_at_most_8_dims_and_bootstraps():
    rng = np.random.default_rng(1)
    ref = rng.normal(size=(200, 20))
    space = FeatureSpace(ref, dims=12)
    assert space.project(ref).shape == (200, 8)
    value, lo, hi = space.fid_interval(ref + 0.5, ref, rounds=50, seed=0)
    assert lo <= value <= hi and value > 0.5


def test_summary_and_the_two_sigma_rule():
    s = summarise([1.0, 2.0, 3.0])
    assert s == {"mean": 2.0, "std": 1.0, "n": 3}
    assert summarise([float("nan")]) is None
    assert decide(1.0, 0.2, "greater") == HOLDS and decide(1.0, 0.2, "less") == FAILS
    assert decide(0.2, 0.28, "greater") == INCONCLUSIVE                    # 0.2 < its bar
    assert decide(1.0, 0.0, "greater") == INCONCLUSIVE                     # never holds on a zero bar
    assert decide(-1.0, 0.0, "greater") == INCONCLUSIVE
    # "similar or better" within a margin: the whole 2-sigma interval must lie above -margin
    assert decide(-1.0, 2.0, "not_less", margin=5.0) == HOLDS
    assert decide(-1.0, 6.0, "not_less", margin=5.0) == INCONCLUSIVE       # a 67-point bar decides nothing
    assert decide(-9.0, 2.0, "not_less", margin=5.0) == FAILS
    assert decide(3.0, 1.0, "not_greater", margin=1.0) == FAILS
    with pytest.raises(ValueError, match="positive margin"):
        decide(0.0, 1.0, "not_less")
    assert decide(float("nan"), 1.0, "greater") == MISSING
    assert combine([HOLDS, INCONCLUSIVE]) == INCONCLUSIVE and combine([HOLDS, FAILS]) == FAILS
    assert combine([HOLDS, HOLDS]) == HOLDS and combine([HOLDS, MISSING]) == MISSING
    assert combine([HOLDS, S.INSUFFICIENT]) == S.INSUFFICIENT and combine([S.INSUFFICIENT, FAILS]) == FAILS
    assert combine([HOLDS, S.UNUSABLE]) == S.UNUSABLE
    with pytest.raises(ValueError, match="direction"):
        decide(1.0, 1.0, "bigger")


def hand_units():
    """Six items in three takes (two actions, two people): take t0 = items 0, 1; t1 = 2, 3; t2 = 4, 5."""
    return S.units(["t0", "t0", "t1", "t1", "t2", "t2"], ["walk", "walk", "walk", "walk", "run", "run"],
                   [1, 1, 2, 2, 2, 2])


def test_aggregate_plain_and_balanced_by_hand():
    u = hand_units()
    v = np.array([1.0, 3.0, 5.0, 7.0, 10.0, np.nan])
    assert S.aggregate(v, u) == pytest.approx(26 / 5)                      # NaN items are left out
    assert S.aggregate(v, u, balanced=True) == pytest.approx((4.0 + 10.0) / 2)   # walk 4, run 10


def test_cluster_bootstrap_resamples_whole_takes():
    u = hand_units()
    v = np.array([1.0, 3.0, 5.0, 7.0, 10.0, 10.0])
    w = np.array([[1.0, 1.0, 1.0], [2.0, 0.0, 1.0], [0.0, 0.0, 3.0], [3.0, 0.0, 0.0]])
    got = S.resampled(v, u, w)
    # take sums 4, 12, 20 over 2 items each: (w . sums) / (2 * sum w)
    assert got == pytest.approx([36 / 6, 28 / 6, 60 / 6, 12 / 6])
    bal = S.resampled(v, u, w, balanced=True)
    assert bal[0] == pytest.approx((4 + 10) / 2) and bal[1] == pytest.approx((2.0 + 10) / 2)
    assert np.isnan(S.resampled(v, u, np.array([[0.0, 0.0, 0.0]]))[0])
    draws = S.bootstrap_weights(3, 500, seed=1)
    assert draws.shape == (500, 3) and (draws.sum(1) == 3).all()
    assert S.cluster_std(v, u, draws) > 0                                  # deterministic values still spread
    single = S.units(["t"] * 4, ["a"] * 4, [1] * 4)
    assert S.cluster_std(np.arange(4.0), single, S.bootstrap_weights(1, 50)) == 0.0


def test_paired_comparison_needs_people_and_takes():
    u = hand_units()
    a, b = np.array([1.0, 1.1, 1.0, 1.2, 0.9, 1.0]), np.array([2.0, 2.1, 2.2, 2.0, 1.9, 2.0])
    w = S.bootstrap_weights(3, 400, seed=0)
    c = S.compare(a, b, u, w, 0.0, 0.0, "less")
    assert c["status"] == S.INSUFFICIENT and (c["people"], c["takes"]) == (2, 3)   # 3 takes < 8
    assert c["difference"] == pytest.approx(np.mean(a) - np.mean(b)) and c["bar"] > 0
    a, b = np.append(a, [1.1, 1.0]), np.append(b, [2.1, 2.0])
    takes = [f"t{i}" for i in range(8)]
    u8 = S.units(takes, ["walk"] * 8, [1, 1, 1, 2, 2, 2, 3, 3])         # 3 people, 8 takes: the minimum
    w8 = S.bootstrap_weights(S.take_people(u8), 400, seed=0)
    assert S.compare(a, b, u8, w8, 0.0, 0.0, "less")["status"] == HOLDS
    assert S.compare(a, b, u8, w8, 0.0, 5.0, "less")["status"] == INCONCLUSIVE     # a large seed std
    one = S.units(takes, ["walk"] * 8, [1] * 8)
    assert S.compare(a, b, one, w8, 0.0, 0.0, "less")["status"] == S.INSUFFICIENT  # one person
    gap = a.copy()
    gap[:3] = np.nan                                                       # compared on the items both have
    c = S.compare(gap, b, u8, w8, 0.0, 0.0, "less")
    assert c["items"] == 5 and c["b_paired"] == pytest.approx(b[3:].mean())
    assert S.compare(np.full(8, np.nan), b, u8, w8, 0, 0, "less")["status"] == MISSING


def test_binomial_band_by_hand():
    lo, hi = S.binomial_band(100, 0.5, 0.99)
    assert lo == pytest.approx(0.37) and hi == pytest.approx(0.63)          # scipy's binom.ppf, n = 100
    assert S.binomial_band(10, 0.0) == (0.0, 0.0)
    narrow, wide = S.binomial_band(1000, 0.05), S.binomial_band(50, 0.05)
    assert narrow[1] - narrow[0] < wide[1] - wide[0]


def test_eq4_unsquared_is_the_mean_norm_where_printed_is_the_mean_squared_norm():
    still = np.ones((10, 2, 3))
    assert M.transition_smoothness_unsquared(still, still) == pytest.approx(0.0, abs=1e-12)
    rng = np.random.default_rng(0)
    a, b = rng.normal(size=(12, 2, 3)), rng.normal(size=(10, 2, 3))
    from export.ops.dct import dct_basis
    z = np.concatenate([a[-10:], b]).reshape(20, -1)
    d = dct_basis(20, 5)
    r = np.linalg.norm(z - d @ d.T @ z, axis=1)
    assert M.transition_smoothness_unsquared(a, b) == pytest.approx(r.mean())
    assert M.transition_smoothness(a, b) == pytest.approx((r ** 2).mean())
    with pytest.raises(ValueError, match="10 frames on each side"):
        M.transition_smoothness_unsquared(a[:4], b)


def test_ade_fde_many_is_ade_fde_per_truth():
    rng = np.random.default_rng(3)
    futures, truths = rng.normal(size=(4, 7, 3, 3)), rng.normal(size=(5, 6, 3, 3))
    for rel in (True, False):
        ade, fde = M.ade_fde_many(futures, truths, root_relative=rel)
        for m in range(5):
            assert (ade[m], fde[m]) == pytest.approx(M.ade_fde(futures, truths[m], root_relative=rel))


# --- ADE/FDE, APD, MMADE/MMFDE (DLow) and the read-out's plausibility checks ---------------------------


def test_root_relative_subtracts_the_roots_horizontal_position_and_keeps_height():
    m = np.array([[[1.0, 0.5, 2.0], [2.0, 1.0, 3.0]]])
    assert M.root_relative(m).tolist() == [[[0.0, 0.5, 0.0], [1.0, 1.0, 1.0]]]
    k = np.stack([m, m + [10.0, 0.0, -4.0]])                  # [K, T, J, 3] works too
    assert np.allclose(M.root_relative(k)[1], M.root_relative(m))


def test_ade_fde_best_of_k_each_minimised_on_its_own():
    truth = np.zeros((2, 1, 3))
    s1 = np.zeros((3, 1, 3))
    s1[0, 0] = [3, 4, 0]                     # distances 5, 0 (the third frame is past the truth)
    s1[2, 0] = [9, 9, 9]
    s2 = motion([1, 1, 1])                   # distances 1, 1
    ade_k, fde_k = M.ade_fde_per_sample(np.stack([s1, s2]), truth, root_relative=False)
    assert ade_k.tolist() == [2.5, 1.0] and fde_k.tolist() == [0.0, 1.0]
    assert M.ade_fde(np.stack([s1, s2]), truth, root_relative=False) == (1.0, 0.0)   # two different samples
    assert M.ade_fde(np.stack([s1, s2]), truth, False)[0] == pytest.approx(M.ade(np.stack([s1, s2]), truth))
    with pytest.raises(ValueError, match="fewer than"):
        M.ade_fde(np.stack([s1[:1]]), truth, False)


def test_ade_fde_whole_pose_and_root_relative():
    truth = motion([0, 0], joints=2)
    moved = motion([5, 5], joints=2)                    # every joint 5 m along x: the root too
    assert M.ade_fde(moved[None], truth, root_relative=False) == pytest.approx((5 * math.sqrt(2),) * 2)
    assert M.ade_fde(moved[None], truth, root_relative=True) == (0.0, 0.0)   # travel is not pose
    lifted = motion([5, 5], joints=2, y=1.0)            # ... but height is
    assert M.ade_fde(lifted[None], truth, root_relative=True) == pytest.approx((math.sqrt(2),) * 2)


def test_apd_is_one_norm_over_the_whole_sequence():
    y0 = np.zeros((2, 1, 3))
    y1 = np.zeros((2, 1, 3))
    y1[0, 0] = [3, 4, 0]                     # |y1 - y0| = 5
    y2 = np.zeros((2, 1, 3))
    y2[1, 0] = [6, 8, 0]                     # |y2 - y0| = 10, |y2 - y1| = sqrt(9 + 16 + 36 + 64)
    three = np.stack([y0, y1, y2])
    assert M.apd(three) == pytest.approx((5 + 10 + math.sqrt(125)) / 3)
    assert M.diversity(three) == pytest.approx((2.5 + 5 + 7.5) / 3)       # WAT Eq. 10: per frame, then mean
    assert M.apd(y0[None]) == 0.0


def test_bone_length_error_relative_to_the_reference():
    from export.data.skeleton import SKELETON, Skeleton
    chain = Skeleton(names=("root", "a", "b"), parents=(-1, 0, 1), offsets=np.zeros((3, 3)))
    m = np.array([[[0, 0, 0], [0, 1, 0], [0, 1, 2]],          # bones 1, 2
                  [[0, 0, 0], [0, 1.1, 0], [0, 1.1, 1.5]]])   # bones 1.1, 1.5
    lengths = M.bone_lengths(m, chain)
    assert lengths == pytest.approx(np.array([[1, 2], [1.1, 1.5]]))
    ref = lengths.mean(0)                                     # 1.05, 1.75
    # (0.05/1.05 + 0.25/1.75 + 0.05/1.05 + 0.25/1.75) / 4 = (1/21 + 1/7) / 2
    assert M.bone_length_error(m, ref, chain) == pytest.approx(2 / 21)
    rest = SKELETON.offsets.copy()
    for j, p in enumerate(SKELETON.parents):                  # parents precede children: the rest pose
        if p >= 0:
            rest[j] = rest[p] + SKELETON.offsets[j]
    assert M.bone_lengths(rest[None]) == pytest.approx(SKELETON.bone_lengths()[None])
    assert M.bone_length_error(rest[None], SKELETON.bone_lengths()) == pytest.approx(0.0, abs=1e-12)
    with pytest.raises(ValueError, match="positive"):
        M.bone_length_error(m, [1.0, 0.0], chain)


def test_foot_below_floor_counts_frames_more_than_depth_under():
    from export.data.skeleton import SKELETON
    m = np.ones((4, SKELETON.num_joints, 3))
    feet = [SKELETON.index(n) for n in ("right_ankle", "right_toe", "left_ankle", "left_toe")]
    m[:, feet, 1] = 0.0
    m[1, SKELETON.index("left_toe"), 1] = -0.05       # below
    m[2, SKELETON.index("right_ankle"), 1] = -0.03    # exactly the depth: not more than it
    m[3, SKELETON.index("right_toe"), 1] = -0.031     # below
    m[0, SKELETON.index("root"), 1] = -5.0            # not a foot
    assert M.foot_below_floor(m) == 0.5
    assert M.foot_below_floor(m, depth=0.1) == 0.0


def test_first_frame_jump_and_its_rule():
    history = motion([0.0, 0.1, 0.2], joints=2)
    assert M.first_frame_jump(history, motion([0.3], joints=2)) == pytest.approx((0.1, 0.1))
    two = motion([0.5], joints=2)
    two[0, 1, 0] = 0.2                                 # one joint jumps 0.3, the other stays: mean 0.15
    jump, step = M.first_frame_jump(history, two)
    assert (jump, step) == pytest.approx((0.15, 0.1))
    assert M.jump_ok(jump, step) and not M.jump_ok(0.151, step)     # 1.5 x the last step
    assert M.jump_ok(0.01, 0.0) and not M.jump_ok(0.0101, 0.0)     # a still history: 1 cm
    with pytest.raises(ValueError, match="two frames"):
        M.first_frame_jump(history[:1], two)


def four_histories():
    """Four windows whose last poses differ only in joint 1's x offset from the root: 0, 0.25, 0.75, 2 m
    (so their distances are the differences, exact in binary); the roots stand elsewhere (ignored)."""
    h = np.zeros((4, 2, 2, 3))
    for w, (root_x, offset) in enumerate([(0, 0.0), (7, 0.25), (-3, 0.75), (2, 2.0)]):
        h[w, :, :, 0] = root_x
        h[w, -1, 1, 0] = root_x + offset
        h[w, 0, 1, 0] = root_x + 0.5 * w               # the earlier frame does not matter
    return h


def test_similar_sets_by_last_pose_include_the_window_itself():
    h = four_histories()
    sets = M.similar_sets(h, 0.5)
    assert [s.tolist() for s in sets] == [[0, 1], [0, 1, 2], [1, 2], [3]]
    assert [s.tolist() for s in M.similar_sets(h, 0.0)] == [[0], [1], [2], [3]]


def test_choose_threshold_is_the_smallest_distance_giving_the_median_size():
    h = four_histories()
    # sizes at 0.25: [2, 2, 1, 1] (median 1.5); at 0.5: [2, 3, 2, 1] (median 2)
    assert M.choose_threshold(h, min_median_size=2) == 0.5
    # at 0.75: [3, 3, 3, 1] (median 3)
    assert M.choose_threshold(h, min_median_size=3) == 0.75
    assert M.choose_threshold(h, min_median_size=1) == 0.0
    with pytest.raises(ValueError, match="cannot give sets of 5"):
        M.choose_threshold(h)


def test_mmade_mmfde_by_hand():
    truths = np.stack([motion([0, 0]), motion([1, 1]), motion([5, 5])])
    futures = [np.stack([motion([0, 0]), motion([1, 1])]),     # vs truth 0: 0; vs truth 1: 0
               np.stack([motion([2, 2]), motion([3, 3])]),     # vs truth 0: 2; vs truth 1: 1 -> mean 1.5
               np.stack([motion([5, 7]), motion([8, 8])])]     # alone, vs its own truth: ADE 1, FDE 2
    sets = [np.array([0, 1]), np.array([0, 1]), np.array([2])]
    mmade, mmfde = M.mmade_mmfde(futures, truths, sets, root_relative=False)
    assert mmade == pytest.approx((0 + 1.5 + 1) / 3)
    assert mmfde == pytest.approx((0 + 1.5 + 2) / 3)
    assert M.mmade_mmfde(futures, truths, sets) == (0.0, 0.0)   # one joint, x only: nothing root-relative
    with pytest.raises(ValueError, match="one similar set"):
        M.mmade_mmfde(futures, truths, sets[:2])


def test_metrics_vector_is_deterministic_and_covers_k_1_3_5():
    from export.vectors_metrics import metrics_vector
    a, b = metrics_vector(), metrics_vector()
    assert a == b
    assert sorted({c["k"] for c in a["cases"]}) == [1, 3, 5]
    c = a["cases"][-1]
    assert c["world"]["ade"] == min(c["world"]["ade_per_sample"])
