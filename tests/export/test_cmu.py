"""The CMU subset (version 2) as clips: every take of every source form reads at the index's frame rate,
trimmed, with a human leg length where the skeleton is the performer's, and retargets plausibly."""
import re

import numpy as np
import pytest

from export.data.asf_amc import read_asf, read_asf_amc
from export.data.bvh import joint_positions, read_bvh
from export.data.clip_json import read_clip, write_clip
from export.data.cmu import CMU_DIR, UNIT, clip_from_take, form_of, load_index, read_take
from export.data.retarget import load_map, resolve, retarget
from export.data.skeleton import SKELETON
from export.ops.floor import foot_height
from export.paths import ROOT

NAME = re.compile(r"^[a-z0-9][a-z0-9_.-]*$")
L = np.linalg.norm(SKELETON.offsets, axis=-1)
PROJECT_LEG = L[SKELETON.index("right_knee")] + L[SKELETON.index("right_ankle")]


@pytest.fixture(scope="module")
def index():
    return {e["take"]: e for e in load_index()}


@pytest.fixture(scope="module")
def takes(index):
    """Every take read once (cleaned, before retargeting)."""
    return {take: read_take(e) for take, e in index.items()}


@pytest.fixture(scope="module")
def clips(takes):
    return {take: clip_from_take(t) for take, t in takes.items()}


def checks():
    """CHECKS.txt per take: (format, leg_m, disp_m, path_m)."""
    rows = {}
    for line in (CMU_DIR / "CHECKS.txt").read_text().splitlines():
        m = re.match(r"(\d+_\d+)\s+(\S+)\s+\d+\s+\d+\s+[\d.]+\s+([\d.]+)\s+[\d.]+\s+[\d.]+\s+[\d.]+\s+([\d.]+)\s+"
                     r"([\d.]+)\s", line)
        if m:
            rows[m[1]] = (m[2], float(m[3]), float(m[4]), float(m[5]))
    return rows


def test_the_data_lives_in_the_project():
    assert CMU_DIR == ROOT / "data" / "cmu" and (CMU_DIR / "SOURCE.md").exists()


def test_every_take_converts_with_its_index_action_and_person(clips, index):
    assert len(clips) == 242 and set(clips) == set(index) == set(checks())
    assert len({c.action for c in clips.values()}) == 18 and len({c.subject for c in clips.values()}) == 18
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


def frames_at_30(source_frames, fps):
    return int(np.floor((source_frames - 1) * 30 / fps + 1e-9)) + 1


# One file of each source form and repository (SOURCE.md's table): take, joint map, fps, T-pose frame dropped.
FORMS = [
    ("05_02", "cmu-asf", 120, False),    # sxaxmz ASF/AMC @ f138249, 05.asf
    ("105_02", "cmu-asf", 120, False),   # sxaxmz @ d602543, subject 105 with 105.asf
    ("01_01", "cmu-asf", 120, False),    # cyun9601 ASF/AMC with 01.asf
    ("35_01", "cmu-asf", 120, False),    # SheffieldML ASF/AMC with its 35.asf
    ("35_18", "cmu-asf", 120, False),    # sxaxmz's AMC on SheffieldML's 35.asf
    ("07_01", "cmu-bvh", 120, True),     # cgspeed BVH
    ("16_01", "cmu-asf-bvh", 120, False),  # BVH converted from ASF/AMC: no T-pose, header says 30 fps
    ("12_01", "daz", 120, True),         # Daz-style, Przestr
    ("135_04", "daz", 120, True),        # Daz-style, papagina martial arts
    ("60_01", "daz", 60, True),          # Daz-style, papagina salsa: 60 fps, header says 120
]


@pytest.mark.parametrize("take, joint_map, fps, tpose", FORMS)
def test_every_source_form_reads_with_its_frames_rate_and_duration(index, takes, clips, take, joint_map, fps, tpose):
    e, t, c = index[take], takes[take], clips[take]
    form = form_of(e)
    assert (form.joint_map, form.tpose, e["fps"]) == (joint_map, tpose, fps)
    assert e["frames_in_file"] == e["frames"] + tpose
    kept = e["frames"] - t.trimmed - t.dropped
    assert len(t.points) == kept and t.fps == fps
    assert len(c) == frames_at_30(kept, fps)
    assert abs(len(c) / 30 - e["seconds"]) < (t.trimmed + t.dropped) / fps + 1 / 30   # the index's duration
    assert c.source["joint_map"] == joint_map


def test_salsa_plays_at_60_fps_not_the_header_120(index, takes, clips):
    salsa = [k for k, e in index.items() if e["action"] == "dance_salsa"]
    assert len(salsa) == 28
    for take in salsa:
        e, t = index[take], takes[take]
        assert e["fps"] == 60 and read_bvh(CMU_DIR / e["file"]).frame_time == pytest.approx(1 / 120, rel=1e-3)
        # only the Daz-style start transient (1-3 frames of the hands) and the T-pose are dropped
        assert t.trimmed <= 3 and t.dropped == 0 and t.cuts == []
        assert len(clips[take]) == frames_at_30(e["frames"] - t.trimmed, 60), take
        assert abs(len(clips[take]) / 30 - e["seconds"]) < 0.1, take


def test_16_01_has_no_tpose_plays_at_120_fps_despite_its_header_and_has_subject_16s_legs(index, takes, clips):
    e = index["16_01"]
    bvh = read_bvh(CMU_DIR / e["file"])
    assert bvh.frame_time == pytest.approx(1 / 30, rel=1e-4) and e["fps"] == 120     # the header is wrong
    assert len(bvh) == e["frames"] == e["frames_in_file"] == 322
    # frame 0 is motion, not an added T-pose: its step into frame 1 is like the steps after it
    p = joint_positions(bvh) * UNIT
    first = np.linalg.norm(p[1] - p[0], axis=-1).max()
    assert first < 0.02 and first < 3 * np.median(np.linalg.norm(np.diff(p, axis=0), axis=-1).max(axis=1))
    assert (takes["16_01"].trimmed, takes["16_01"].dropped) == (0, 0)
    assert len(clips["16_01"]) == frames_at_30(322, 120) == 81        # 2.68 s; read at 30 fps it would be 10.7 s
    # a BVH joint sits at the start of its bone: with the ASF map (bone ends) the "leg" would be knee to toe
    asf = read_asf(CMU_DIR / index["16_02"]["asf"])
    bone = {b.name: b.length * asf.metres for b in asf.bones}
    want = np.mean([bone[f"{s}femur"] + bone[f"{s}tibia"] for s in "lr"])
    assert leg_length(p, bvh.names, "cmu-asf-bvh") == pytest.approx(want, abs=1e-3)
    assert want == pytest.approx(0.836, abs=1e-3)
    assert abs(leg_length(p, bvh.names, "cmu-asf") - want) > 0.05


def test_glitches_are_trimmed_by_rule(takes):
    trims = {k: (t.trimmed, t.dropped) for k, t in takes.items()}
    assert trims["07_12"] == (1, 0)      # the all-zero first frame
    assert trims["08_07"] == (6, 0)      # 6 frames held still, then a 9 cm jump of the body
    assert trims["135_04"] == (3, 0)     # Daz-style hand jump, frames 1-3
    assert trims["60_01"] == (2, 0)      # the same at 60 fps, frames 1-2
    assert trims["16_28"] == (6, 0)      # a hand at 96 m/s in motion frames 5-7
    assert trims["05_01"] == (0, 0)


def leg_length(points, names, joint_map):
    """Hip joint to ankle, mean of left and right, median over frames, in the points' units."""
    src = dict(zip(SKELETON.names, resolve(load_map(joint_map), names, joint_map)))
    q = {j: points[:, src[j]].mean(axis=1) for j in src if src[j]}
    legs = [np.linalg.norm(q[f"{s}_hip"] - q[f"{s}_knee"], axis=-1) + np.linalg.norm(q[f"{s}_knee"] - q[f"{s}_ankle"], axis=-1)
            for s in ("left", "right")]
    return float(np.median(np.mean(legs, axis=0)))


def test_every_performer_skeleton_has_a_human_leg_length_in_metres(takes):
    want = checks()
    legs = {k: leg_length(t.points, t.names, t.form.joint_map) for k, t in takes.items() if t.form.key != "daz"}
    assert len(legs) == 164 + 38 + 1
    for take, leg in legs.items():
        assert 0.74 <= leg <= 0.90, (take, leg)
        assert abs(leg - want[take][1]) < 2e-3, (take, leg, want[take])
    assert min(legs.values()) == pytest.approx(0.743, abs=1e-3)                # subject 105
    # Daz-style takes share one mannequin: the same 0.822 m leg for everyone
    daz = {round(leg_length(t.points, t.names, "daz"), 3) for t in takes.values() if t.form.key == "daz"}
    assert daz == {0.822}


def test_clips_stand_on_the_floor_upright_and_straight_walks_travel(clips):
    head, root = SKELETON.index("head"), 0
    # Measured in v2: a toe pointing down poked up to 12.5 cm under the floor (the project's toe on the
    # source's direction) in four long takes, and 06_02 (dribbling on the run) has its feet 5.4 cm up on median.
    low_toes = {"06_13": -0.113, "105_15": -0.125, "105_28": -0.098, "61_09": -0.087}
    for take, c in clips.items():
        p = c.positions
        assert abs(np.median(foot_height(p))) < (0.06 if take == "06_02" else 0.05), take
        assert foot_height(p).min() > low_toes.get(take, -0.08) - 0.005, take
        assert np.percentile(foot_height(p), 1) > -0.09, take
        assert np.median(p[:, head, 1] - p[:, root, 1]) > 0.5, take   # the head is above the hips
    rows = checks()
    straight = [k for k, c in clips.items() if c.action in ("walk", "walk_brisk_long_stride")
                and rows[k][3] - rows[k][2] < 0.2]                       # path = displacement: no turns
    assert len(straight) >= 30
    for take in straight:
        c = clips[take]
        travel = np.linalg.norm(c.positions[-1, 0, [0, 2]] - c.positions[0, 0, [0, 2]])
        assert 3.0 < travel < 5.0, (take, travel)


def test_travel_is_the_measured_travel_scaled_to_the_project_leg(clips, takes):
    for take, (_, leg, disp, _) in checks().items():
        if take == "07_12" or takes[take].cuts:
            continue  # CHECKS measured 07_12 from its all-zero first frame; a cut take lost part of its path
        c = clips[take]
        travel = np.linalg.norm(c.positions[-1, 0, [0, 2]] - c.positions[0, 0, [0, 2]])
        want = disp * PROJECT_LEG / leg
        # CHECKS follows the ASF root, a clip the middle of the hips: a few cm apart in a turn (105_52's
        # jump turns in place: 6.8 cm)
        assert abs(travel - want) < 0.07 + 0.04 * want, (take, travel, want)


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

