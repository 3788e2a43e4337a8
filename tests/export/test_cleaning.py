"""The cleaning rule of export/data/cmu.py (start transients, spikes, impossible speeds, cuts): on hand-made
tracks, on takes CHECKS.txt flags, and over every take: no clip keeps a glitch the rule would repair."""
import numpy as np
import pytest

from export.data import cmu
from export.data.cmu import (IMPOSSIBLE_SPEED, SPIKE_SPEED, clean, clip_from_take, find_glitches, load_index,
                             read_raw, read_take, repair_glitches, used_points)
from export.data.skeleton import SKELETON


def track(speeds, fps=120.0):
    """A point moving along x at the given speeds (m/s), one per frame step: [frames, 1, 3]."""
    x = np.concatenate([[0.0], np.cumsum(np.asarray(speeds, dtype=float) / fps)])
    return np.stack([x, np.ones_like(x), np.zeros_like(x)], axis=-1)[:, None, :]


def kinds(glitches):
    return [(g.point, g.first, g.last, g.kind) for g in glitches]


def steps(points, fps):
    return np.linalg.norm(np.diff(points, axis=0), axis=-1) * fps


def test_spikes_of_up_to_three_frames_are_replaced_by_the_straight_line():
    smooth = track([1.0] * 20)
    p = smooth.copy()
    p[10, 0, 1] += 0.15                                    # one frame 15 cm away and back: 18 m/s
    fixed, found = repair_glitches(p, ["hand"], 120.0)
    assert kinds(found) == [("hand", 10, 10, "spike")]
    np.testing.assert_allclose(fixed, smooth, atol=1e-12)
    p = smooth.copy()
    p[8:11, 0, 2] += 0.2                                   # a plateau of three frames
    fixed, found = repair_glitches(p, ["hand"], 120.0)
    assert kinds(found) == [("hand", 8, 10, "spike")]
    np.testing.assert_allclose(fixed, smooth, atol=1e-12)
    # the same in frames at 60 fps: the rule counts frames
    p = track([1.0] * 20, fps=60.0)
    p[5:8, 0, 2] += 0.3
    assert kinds(find_glitches(p, ["foot"], 60.0)) == [("foot", 5, 7, "spike")]


def test_real_fast_motion_is_kept():
    # four frames away at 24 m/s (under the impossible speed) is not a spike
    p = track([1.0] * 20)
    p[8:12, 0, 2] += 0.2
    assert find_glitches(p, ["hand"], 120.0) == []
    # a kick: faster than 10 m/s for 6 frames, going somewhere and coming back slower
    kick = track([1.0] * 8 + [14.0] * 6 + [1.0] * 4 + [-6.0] * 14 + [1.0] * 8)
    assert find_glitches(kick, ["foot"], 120.0) == []
    # a short fast burst that goes somewhere is motion too, and so is one fast step (16_01's wrist)
    assert find_glitches(track([1.0] * 8 + [12.0] * 2 + [1.0] * 8), ["foot"], 120.0) == []
    assert find_glitches(track([0.5] * 8 + [13.6] + [0.9] * 8), ["wrist"], 120.0) == []


def test_an_impossible_flip_is_repaired_whatever_its_length_and_whichever_way_is_fast():
    smooth = track([2.0] * 60)
    p = smooth.copy()
    p[20:28, 0, 1] += 0.3                                  # 8 frames away, jumps of 36 m/s (a salsa foot flip)
    fixed, found = repair_glitches(p, ["foot"], 120.0)
    assert kinds(found) == [("foot", 20, 27, "impossible")] and found[0].speed > IMPOSSIBLE_SPEED
    np.testing.assert_allclose(fixed, smooth, atol=1e-12)
    # drifting away at 5 m/s for 6 frames, then snapping back at 30 m/s (subject 5's knees)
    p = smooth.copy()
    p[20:26, 0, 1] += np.arange(1, 7) * 5.0 / 120
    fixed, found = repair_glitches(p, ["knee"], 120.0)
    # the shortest window that comes back starts from frame 22, 12.5 cm up: the rest of the drift stays
    assert kinds(found) == [("knee", 23, 25, "impossible")] and steps(fixed[:, 0], 120.0).max() < SPIKE_SPEED
    np.testing.assert_allclose(fixed[:20], smooth[:20], atol=1e-12)
    np.testing.assert_allclose(fixed[26:], smooth[26:], atol=1e-12)
    # a flip that stays away longer than GLITCH_SECONDS is not interpolated over
    p = smooth.copy()
    p[20:20 + int(cmu.GLITCH_SECONDS * 120) + 2, 0, 1] += 0.3
    assert [g.kind for g in find_glitches(p, ["foot"], 120.0)] == ["cut", "cut"]


def test_clean_trims_the_start_and_cuts_at_a_jump_that_never_comes_back_keeping_the_longer_side():
    p = track([1.0] * 99)
    p[:2, 0, 1] += 0.3                                     # the capture settling in frames 0-1
    fixed, first, stop, repaired, cuts = clean(p, ["hand"], 120.0)
    assert (first, stop, repaired, cuts) == (2, 100, [], []) and len(fixed) == 98
    p = track([1.0] * 99)
    p[30:, 0, 1] += 0.4                                    # a 48 m/s jump to another place for good
    fixed, first, stop, repaired, cuts = clean(p, ["toe"], 120.0)
    assert (first, stop) == (30, 100) and kinds(cuts) == [("toe", 30, 29, "cut")]
    p = track([1.0] * 99)
    p[70:, 0, 1] += 0.4
    assert clean(p, ["toe"], 120.0)[1:3] == (0, 70)
    # the spike inside the kept part is repaired and counted from its first frame
    p = track([1.0] * 99)
    p[70:, 0, 1] += 0.4
    p[50, 0, 2] += 0.2
    fixed, first, stop, repaired, cuts = clean(p, ["toe"], 120.0)
    assert (first, stop) == (0, 70) and kinds(repaired) == [("toe", 50, 50, "spike")]
    assert steps(fixed[:, 0], 120.0).max() < SPIKE_SPEED


def test_the_rule_is_fast():
    rng = np.random.default_rng(0)
    p = np.cumsum(rng.normal(0, 0.004, (36_000, 20, 3)), axis=0)     # 5 min at 120 fps, 20 points
    p[1000::997, 3] += 0.2                                           # 36 spikes
    import time
    t = time.perf_counter()
    found = find_glitches(p, [f"p{j}" for j in range(20)], 120.0)
    assert time.perf_counter() - t < 2.0
    assert len([g for g in found if g.point == "p3" and g.kind == "spike"]) == 36


# --- takes that CHECKS.txt flags ------------------------------------------------------------------------

@pytest.fixture(scope="module")
def index():
    return {e["take"]: e for e in load_index()}


def raw_used(entry):
    form, names, points, _ = read_raw(entry)
    used = used_points(form, names)
    return names, used, points


def test_35_01s_isolated_toe_end_spike_is_found_but_the_toe_end_is_not_read(index):
    # CHECKS: "isolated f99-100 ltoes 14.3": steps from motion frames 99 and 100, so frame 100 (0-based 99) is away
    names, used, points = raw_used(index["35_01"])
    toe = names.index("ltoes")
    found = find_glitches(points[:, [toe]], ["ltoes"], 120.0)
    assert kinds(found) == [("ltoes", 99, 99, "spike")] and found[0].speed == pytest.approx(14.3, abs=0.05)
    assert toe not in used                                 # the clip's toe is the toe base (lfoot)
    take = read_take(index["35_01"])
    assert (take.trimmed, take.dropped, take.repaired, take.cuts) == (0, 0, [], [])


def test_16_15s_start_transient_is_trimmed(index):
    # CHECKS: "start transient f2-2 lhand 107.1": the wrist jumps from motion frame 2 to 3
    names, used, points = raw_used(index["16_15"])
    v = steps(points[:, used], 120.0)
    assert v[1].max() > 50 and v[2:].max() < SPIKE_SPEED
    take = read_take(index["16_15"])
    assert take.trimmed == 2 and take.repaired == [] and len(take.points) == index["16_15"]["frames"] - 2
    assert steps(take.points[:, used], 120.0).max() < SPIKE_SPEED


def test_a_salsa_foot_flip_is_repaired_at_60_fps(index):
    # CHECKS: "sustained f732-735 rFoot_end 47.1" in 60_15: four steps faster than 10 m/s, at 60 fps
    take = read_take(index["60_15"])
    assert take.fps == 60 and take.cuts == []
    foot = [g for g in take.repaired if g.point == "rFoot/end"]
    assert len(foot) == 1 and foot[0].speed == pytest.approx(47.1, abs=0.1)
    first, last = foot[0].first + take.trimmed, foot[0].last + take.trimmed   # 0-based motion frames
    assert 731 <= first <= last <= 735
    used = used_points(take.form, take.names)
    v = steps(take.points[:, used], 60.0)
    assert v[first - take.trimmed - 4:last - take.trimmed + 4].max() < 25.0


def test_05_06s_knee_flips_are_repaired_and_the_take_is_cut_at_the_toe_flip_that_stays(index):
    names, used, points = raw_used(index["05_06"])
    fixed, found = repair_glitches(points[:, used], [names[i] for i in used], 120.0)
    knees = [g for g in found if g.point == "rfemur"]
    # CHECKS lists rfemur flips of 25-47 m/s at motion frames 128, 146, 156, 165, 192, 459, 466
    assert len(knees) >= 6 and all(g.kind == "impossible" and g.speed > IMPOSSIBLE_SPEED for g in knees)
    assert [g.kind for g in found if g.point == "lfoot"] == ["spike"]
    assert kinds([g for g in found if g.kind == "cut"]) == [("rfoot", 432, 431, "cut")]
    take = read_take(index["05_06"])
    assert (take.trimmed, take.dropped) == (432, 0) and len(take.points) == 885 - 432   # the longer side


def test_a_kicking_foot_is_real_motion_and_kept(index):
    # CHECKS: 10_05 "sustained f293-303 rtoes 18.6": the kick; its toe base passes 10 m/s for several frames
    take = read_take(index["10_05"])
    assert (take.trimmed, take.dropped, take.repaired, take.cuts) == (0, 0, [], [])
    toe = take.names.index("rfoot")
    assert (steps(take.points[:, toe], 120.0)[285:310] > SPIKE_SPEED).sum() >= 4


def test_without_the_rule_a_salsa_flip_reaches_the_30_hz_clip(index):
    # so the all-takes check below can fail: uncleaned, 60_13's foot flip survives resampling as a spike
    found = find_glitches(clip_from_take(read_take(index["60_13"], repair=False)).positions, SKELETON.names, 30.0)
    assert any(g.kind == "spike" and g.point.startswith("left_") for g in found)


# --- every take ---------------------------------------------------------------------------------------

@pytest.fixture(scope="module")
def cleaned():
    """Every take read and cleaned once, with its clip (18 joints, 30 Hz)."""
    takes = [read_take(e) for e in load_index()]
    return [(t, clip_from_take(t)) for t in takes]


def test_no_clip_keeps_a_glitch_the_rule_would_repair(cleaned):
    assert len(cleaned) == 242
    for take, clip in cleaned:
        used = used_points(take.form, take.names)
        # at the source rate, on the points the joint map reads: a second pass finds nothing
        assert find_glitches(take.points[:, used], [take.names[i] for i in used], take.fps) == [], take.entry["take"]
        # and on the clip itself: no spike, impossible step or jump that stays, at 30 Hz
        assert find_glitches(clip.positions, SKELETON.names, 30.0) == [], take.entry["take"]
        assert steps(clip.positions, 30.0).max() < IMPOSSIBLE_SPEED, take.entry["take"]


def test_what_the_rule_did_over_all_takes(cleaned):
    repaired = {t.entry["take"] for t, _ in cleaned if t.repaired}
    cut = {t.entry["take"]: (t.trimmed, t.dropped) for t, _ in cleaned if t.cuts}
    # the repairs are where CHECKS.txt finds spikes or impossible speeds on points the joint maps read
    assert repaired == {"05_05", "05_06", "05_08", "05_10", "05_15", "05_16", "05_17", "05_18", "05_19", "05_20",
                        "60_04", "60_09", "60_10", "60_11", "60_13", "60_15", "105_12"}
    # only subject 5's dances hold a toe or knee flip that never comes back
    assert cut == {"05_05": (380, 0), "05_06": (432, 0), "05_08": (197, 0), "05_16": (0, 59), "05_18": (0, 491),
                   "05_19": (320, 0)}
    # start transients: the Daz-style hands (1-3 frames), 16_15/16_23/16_28's hands, 08_07, 07_12's zero frame
    trims = {t.entry["take"]: t.trimmed for t, _ in cleaned if not t.cuts}
    assert all(0 <= trims[t.entry["take"]] <= 3 for t, _ in cleaned if t.form.key == "daz")
    assert {k: trims[k] for k in ("07_12", "08_07", "16_15", "16_23", "16_28", "60_01", "61_09")} == \
        {"07_12": 1, "08_07": 6, "16_15": 2, "16_23": 3, "16_28": 6, "60_01": 2, "61_09": 0}
