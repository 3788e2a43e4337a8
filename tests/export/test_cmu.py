"""The CMU subset as clips: every take converts, at the index's frame rate, trimmed, retargeted plausibly."""
import re

import numpy as np
import pytest

from export.data.asf_amc import read_asf_amc
from export.data.bvh import joint_positions, read_bvh
from export.data.clip_json import read_clip, write_clip
from export.data.cmu import CMU_DIR, CmuSource, load_index, read_take, repair_spikes
from export.data.retarget import load_map, retarget
from export.data.skeleton import SKELETON
from export.ops.floor import foot_height
from export.paths import ROOT

NAME = re.compile(r"^[a-z0-9][a-z0-9_.-]*$")
L = np.linalg.norm(SKELETON.offsets, axis=-1)
PROJECT_LEG = L[SKELETON.index("right_knee")] + L[SKELETON.index("right_ankle")]


@pytest.fixture(scope="module")
def clips():
    return {c.take: c for c in CmuSource().clips()}


@pytest.fixture(scope="module")
def index():
    return {e["take"]: e for e in load_index()}


def test_the_data_lives_in_the_project():
    assert CMU_DIR == ROOT / "data" / "cmu" and (CMU_DIR / "SOURCE.md").exists()


def test_every_take_converts_with_its_index_action_and_person(clips, index):
    assert len(clips) == 67 and set(clips) == set(index)
    assert len({c.action for c in clips.values()}) == 12
    for take, c in clips.items():
        e = index[take]
        assert NAME.match(c.name) and c.name == f"cmu_{take}"
        assert c.action == e["action"] and c.subject == e["subject"] and c.take == take
        assert c.fps == 30.0 and not c.loops and c.positions.shape[1:] == (18, 3)
        assert np.all(np.isfinite(c.positions))
        assert c.source["file"] == f"data/cmu/{e['file']}" and (ROOT / c.source["file"]).exists()
        assert c.source["dataset"].startswith("CMU Graphics Lab Motion Capture Database (")
        assert "DATA_NOTICE.md" in c.source["license"]
    assert clips["10_05"].action == "kick"  # the file is named "10_05 - walk.amc"


def test_a_clip_writes_as_a_valid_contract_file_and_reads_back(clips, tmp_path):
    c = clips["16_08"]
    write_clip(c, tmp_path / "cmu_16_08.json")   # validates against contract/clip.schema.json
    back = read_clip(tmp_path / "cmu_16_08.json")
    assert (back.name, back.action, back.subject, back.take) == ("cmu_16_08", "run_jog", 16, "16_08")
    np.testing.assert_allclose(back.positions, c.positions, atol=1e-6)


def test_salsa_plays_at_60_fps_not_the_header_120(clips, index):
    for take in ("60_01", "60_02", "60_03", "61_04", "61_05", "61_06"):
        e = index[take]
        assert e["fps"] == 60
        # 3 frames of the Daz-style hand jump are dropped first
        assert abs(len(clips[take]) - (e["frames"] - 3) / 60 * 30) <= 1, take


def test_glitches_are_trimmed_by_rule(index):
    assert read_take(index["07_12"]).trimmed == 1      # the all-zero first frame
    assert read_take(index["08_07"]).trimmed == 6      # 6 frames held still, then a 9 cm jump of the body
    assert read_take(index["135_04"]).trimmed == 3     # Daz-style hand jump
    assert read_take(index["05_01"]).trimmed == 0


def track(speeds, fps=120.0):
    """A point moving along x at the given speeds (m/s), one per frame step."""
    x = np.concatenate([[0.0], np.cumsum(np.asarray(speeds, dtype=float) / fps)])
    return np.stack([x, np.ones_like(x), np.zeros_like(x)], axis=-1)[:, None, :]


def test_isolated_spikes_are_interpolated_and_kicks_stay():
    smooth = [1.0] * 20
    # one frame 15 cm away and back
    p = track(smooth)
    p[10, 0, 1] += 0.15
    fixed, rep = repair_spikes(p, ["hand"], 120.0)
    assert rep == [("hand", 10, 10)]
    np.testing.assert_allclose(fixed, track(smooth), atol=1e-12)
    # three frames away (a plateau that moves slowly) and back
    p = track(smooth)
    p[8:11, 0, 2] += 0.2
    fixed, rep = repair_spikes(p, ["hand"], 120.0)
    assert rep == [("hand", 8, 10)]
    np.testing.assert_allclose(fixed, track(smooth), atol=1e-12)
    # four frames away is not a spike
    p = track(smooth)
    p[8:12, 0, 2] += 0.2
    assert repair_spikes(p, ["hand"], 120.0)[1] == []
    # a kick: faster than 10 m/s for 6 frames, going somewhere
    kick = track([1.0] * 8 + [14.0] * 6 + [1.0] * 8)
    assert repair_spikes(kick, ["foot"], 120.0)[1] == []
    # a short fast burst that goes somewhere is motion too
    burst = track([1.0] * 8 + [12.0] * 2 + [1.0] * 8)
    assert repair_spikes(burst, ["foot"], 120.0)[1] == []


def test_clips_stand_on_the_floor_upright_and_walks_travel(clips):
    head, root = SKELETON.index("head"), 0
    for take, c in clips.items():
        p = c.positions
        assert abs(np.median(foot_height(p))) < 0.05, take
        assert foot_height(p).min() > -0.08, take
        assert np.median(p[:, head, 1] - p[:, root, 1]) > 0.5, take   # the head is above the hips
    for take, c in clips.items():
        if c.action in ("walk", "walk_brisk_long_stride"):
            travel = np.linalg.norm(c.positions[-1, 0, [0, 2]] - c.positions[0, 0, [0, 2]])
            assert 3.0 < travel < 5.0, (take, travel)


def checks():
    rows = {}
    for line in (CMU_DIR / "CHECKS.txt").read_text().splitlines():
        m = re.match(r"(\d+_\d+)\s+\S+\s+\d+\s+\d+\s+[\d.]+\s+([\d.]+)\s+[\d.]+\s+[\d.]+\s+[\d.]+\s+([\d.]+)\s", line)
        if m:
            rows[m[1]] = (float(m[2]), float(m[3]))
    return rows


def test_travel_is_the_measured_travel_scaled_to_the_project_leg(clips):
    for take, (leg, disp) in checks().items():
        if take == "07_12":
            continue  # CHECKS measured from the all-zero first frame, at the origin
        c = clips[take]
        travel = np.linalg.norm(c.positions[-1, 0, [0, 2]] - c.positions[0, 0, [0, 2]])
        want = disp * PROJECT_LEG / leg
        assert abs(travel - want) < 0.05 + 0.04 * want, (take, travel, want)


def test_one_take_read_as_asf_amc_and_as_cgspeed_bvh_retargets_to_nearly_the_same_motion(index):
    e = index["05_02"]
    names, p = read_asf_amc(CMU_DIR / e["asf"], CMU_DIR / e["file"])
    a = retarget(p, names, 1 / 120, load_map("cmu-asf"), "asf")
    bvh = read_bvh(CMU_DIR / "crosscheck/05_02.bvh")
    b = retarget(joint_positions(bvh)[1:], bvh.names, 1 / 120, load_map("cmu-bvh"), "bvh")
    d = np.linalg.norm(a - b, axis=-1)
    legs = [SKELETON.index(n) for n in SKELETON.names if n.endswith(("hip", "knee", "ankle", "toe"))] + [0]
    assert d[:, legs].max() < 1e-3
    # cgspeed has no thorax bone: the neck and arms move a little (measured: 1.7 cm on average)
    assert d.mean() < 0.03 and d.max() < 0.1
