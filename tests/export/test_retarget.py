"""Retargeting onto the project skeleton: hand-computed poses, units, up axis, frame rate, joint maps."""
import json
import shutil
from pathlib import Path

import numpy as np
import pytest

from export.data.bvh import joint_positions, read_bvh
from export.cli import main
from export.data.retarget import (MIN_FRAMES, RetargetError, UnknownSkeletonError, body_problems, builtin_map,
                                  load_map, pick_map, plausibility_warning, resample_points, retarget, tried_maps)
from export.data.sources import BvhFolderSource
from export.data.skeleton import SKELETON
from export.ops.floor import CONTACT_BAND, foot_height

FIXTURES = Path(__file__).resolve().parents[1] / "fixtures"
L = {n: float(np.linalg.norm(o)) for n, o in zip(SKELETON.names, SKELETON.offsets)}
UP, DOWN, LEFT, RIGHT, BACK = (np.array(v, dtype=float) for v in ([0, 1, 0], [0, -1, 0], [1, 0, 0], [-1, 0, 0],
                                                                   [0, 0, -1]))


def unit(*v):
    v = np.asarray(v, dtype=float)
    return v / np.linalg.norm(v)


def run(name, override=None, **kw):
    bvh = read_bvh(FIXTURES / name)
    return retarget(joint_positions(bvh), bvh.names, bvh.frame_time, load_map("cmu-bvh", override), name, **kw)


def expected_tpose(right_shin=DOWN, right_toe=unit(0, -6, 12), toes=None):
    """The T-pose fixture by hand: it faces +z, left at +x; every project bone takes its source bone's
    direction (fixtures/make_fixtures.py lists the offsets) and the project's length."""
    p = {"root": np.array([0.0, 0.8315, 0.0])}
    p["chest"] = p["root"] + L["chest"] * UP
    p["neck"] = p["chest"] + L["neck"] * UP
    p["head"] = p["neck"] + L["head"] * UP
    for side, out in (("right", RIGHT), ("left", LEFT)):
        p[f"{side}_hip"] = p["root"] + L[f"{side}_hip"] * out
        p[f"{side}_knee"] = p[f"{side}_hip"] + L[f"{side}_knee"] * DOWN
        shin = right_shin if side == "right" else DOWN
        p[f"{side}_ankle"] = p[f"{side}_knee"] + L[f"{side}_ankle"] * shin
        toe = toes if toes is not None else (right_toe if side == "right" else unit(0, -6, 12))
        p[f"{side}_toe"] = p[f"{side}_ankle"] + (L[f"{side}_toe"] * toe if toes is None else toe)
        # chest (Spine, 102 cm) -> shoulder (RightArm: Spine1 + (-18, 4, 0) = (-18, 118, 0) cm)
        p[f"{side}_shoulder"] = p["chest"] + L[f"{side}_shoulder"] * unit(18 * out[0], 16, 0)
        p[f"{side}_elbow"] = p[f"{side}_shoulder"] + L[f"{side}_elbow"] * out
        p[f"{side}_wrist"] = p[f"{side}_elbow"] + L[f"{side}_wrist"] * out
    pose = np.stack([p[n] for n in SKELETON.names])
    pose[:, 1] -= pose[:, 1].min()
    return pose


def test_tpose_by_hand():
    out = run("tpose.bvh")
    assert out.shape == (12, 18, 3)  # 48 frames at 120 Hz = 0.39 s -> 12 frames at 30 Hz
    np.testing.assert_allclose(out, np.broadcast_to(expected_tpose(), out.shape), atol=1e-9)


def test_bent_knee_by_hand():
    # RightLeg Xrotation 90 turns the shin from -y to -z, and the foot with it: toe (0, -6, 12) -> (0, -12, -6).
    out = run("knee.bvh")
    want = expected_tpose(right_shin=BACK, right_toe=unit(0, -12, -6))
    np.testing.assert_allclose(out[0], want, atol=1e-9)


def test_derived_head_and_toes():
    # head continues neck - chest; toes are the rest toe offset (0.1335 forward, 0.05 down) turned to the
    # pelvis heading, here +z because the right hip is at -x.
    derive = {"joints": {"head": [None], "right_toe": [None], "left_toe": [None]}}
    out = run("knee.bvh", derive)
    rest = SKELETON.offsets[SKELETON.index("right_toe")]
    want = expected_tpose(right_shin=BACK, toes=np.array([0.0, rest[1], rest[0]]))
    np.testing.assert_allclose(out[0], want, atol=1e-9)


def test_walk_keeps_project_bone_lengths_travels_and_keeps_its_feet_on_the_floor():
    out = run("walk.bvh")
    assert out.shape == (46, 18, 3)  # 151 frames at 100 Hz = 1.5 s
    lengths = np.stack([np.linalg.norm(out[:, j] - out[:, p], axis=-1) for p, j in SKELETON.bones], axis=1)
    np.testing.assert_allclose(lengths, np.broadcast_to(SKELETON.bone_lengths(), lengths.shape), atol=1e-12)
    # the walk travels along +z in the file, and so does the clip: the root's path scaled by the leg ratio
    bvh = read_bvh(FIXTURES / "walk.bvh")
    src = joint_positions(bvh)
    hips = src[:, bvh.names.index("Hips")]
    assert out[-1, 0, 2] - out[0, 0, 2] > 1.0
    np.testing.assert_allclose(out[:, 0, 0], 0.0, atol=1e-9)
    scale = (out[-1, 0, 2] - out[0, 0, 2]) / (hips[-1, 2] - hips[0, 2])
    assert 0.04 < scale < 0.08   # CMU units (0.0564 m) to metres, times a leg ratio near 1
    # feet on the floor: the lower of ankle and toe touches y = 0 within the contact band
    feet = foot_height(out)
    assert abs(np.median(feet)) < 0.01 and feet.min() > -CONTACT_BAND
    # the body faces about +z
    assert np.all(np.abs(out[:, SKELETON.index("right_hip"), 0] - out[:, SKELETON.index("left_hip"), 0]) > 0.1)


def test_units_do_not_matter():
    bvh = read_bvh(FIXTURES / "walk.bvh")
    names, dt, jmap = bvh.names, bvh.frame_time, load_map("cmu-bvh")
    base = retarget(joint_positions(bvh), names, dt, jmap, "walk")
    for factor in (2.54 / 0.45, 0.0254, 100.0):  # CMU units -> cm, -> m, and something in mm-ish
        bvh.offsets *= factor
        bvh.motion[:, :3] *= factor
        np.testing.assert_allclose(retarget(joint_positions(bvh), names, dt, jmap, "walk"), base, atol=1e-12)
        bvh.offsets /= factor
        bvh.motion[:, :3] /= factor


def test_z_up_file_with_up_z_matches_the_y_up_file():
    np.testing.assert_allclose(run("walk_zup.bvh", {"up": "z"}), run("walk.bvh"), atol=1e-9)
    # read as y-up it is lying down, which is a different clip
    assert np.abs(run("walk_zup.bvh") - run("walk.bvh")).max() > 0.1


def test_resampling_is_linear_in_time_over_the_duration():
    src = np.random.default_rng(0).normal(size=(11, 2, 3))      # 11 frames at 100 Hz: 0.1 s
    out = resample_points(src, 0.01)
    assert len(out) == 4                                        # t = 0, 1/30, 2/30, 3/30
    t = np.arange(11) * 0.01
    for k, tk in enumerate(np.arange(4) / 30):
        np.testing.assert_allclose(out[k], [[np.interp(tk, t, src[:, j, c]) for c in range(3)] for j in range(2)])
    # a 30 Hz source passes through unchanged
    np.testing.assert_array_equal(resample_points(src, 1 / 30), src)


def test_too_few_frames_names_the_problem():
    with pytest.raises(RetargetError, match=r"short.bvh: too few frames: 3 at 120 Hz is 1 at 30 Hz, and a "
                                            rf"history needs at least {MIN_FRAMES}"):
        run("short.bvh")


def test_unknown_skeleton_lists_what_is_missing_and_what_the_file_has():
    with pytest.raises(UnknownSkeletonError) as e:
        run("unknown_skeleton.bvh")
    text = str(e.value)
    assert "unknown skeleton for joint map cmu-bvh" in text and "no source joint for root" in text
    assert "J0, J1, J2" in text and "BRING_YOUR_OWN" in text


def test_a_user_map_fixes_an_unknown_skeleton(tmp_path):
    # the unknown skeleton is the T-pose with joints renamed J0.. in file order
    from tests.fixtures.make_fixtures import TPOSE
    names = [n for n, _, _ in TPOSE if not n.endswith("/end")]
    cmu = json.loads((Path(__file__).resolve().parents[2] / "contract/joint-maps/cmu-bvh.json").read_text())

    def rename(alt):
        return None if alt is None else "+".join(
            f"J{names.index(part.removesuffix('/end'))}" + ("/end" if part.endswith("/end") else "")
            for part in alt.split("+"))

    joints = {j: [rename(next(a for a in alts if a is None or all(p.removesuffix("/end") in names
                                                                     for p in a.split("+"))))]
              for j, alts in cmu["joints"].items()}
    path = tmp_path / "my-map.json"
    path.write_text(json.dumps({"joints": joints}))
    bvh = read_bvh(FIXTURES / "unknown_skeleton.bvh")
    out = retarget(joint_positions(bvh), bvh.names, bvh.frame_time, load_map("cmu-bvh", path), "u")
    np.testing.assert_allclose(out, run("tpose.bvh"), atol=1e-12)


def test_prefixed_names_match():
    bvh = read_bvh(FIXTURES / "walk.bvh")
    prefixed = ["mixamorig:" + n for n in bvh.names]
    jmap = load_map("cmu-bvh")
    np.testing.assert_allclose(retarget(joint_positions(bvh), prefixed, bvh.frame_time, jmap, "w"), run("walk.bvh"))


def test_coincident_source_points_are_named():
    with pytest.raises(RetargetError, match="the source points for chest and neck coincide"):
        run("walk.bvh", {"joints": {"chest": ["Spine1"], "neck": ["Neck"]}})


@pytest.mark.parametrize("override, message", [
    ({"up": "x"}, 'field up: must be "y" or "z"'),
    ({"joints": {"elbow": ["X"]}}, "field joints/elbow: not a project joint"),
    ({"joints": {"right_knee": [None]}}, "only head, right_toe, left_toe can be derived"),
    ({"joints": {"right_knee": "RightLeg"}}, "field joints/right_knee: must be a non-empty list"),
    ({"joint": {}}, "unknown field 'joint'"),
    ({"extends": "nope"}, "no joint map named 'nope'"),
])
def test_bad_user_maps_name_the_field(override, message):
    with pytest.raises(RetargetError, match=message.replace("(", r"\(")):
        load_map("cmu-bvh", override)


def test_unreadable_user_map_is_named(tmp_path):
    path = tmp_path / "map.json"
    path.write_text("{nope")
    with pytest.raises(RetargetError, match="map.json: not a readable joint map JSON"):
        load_map("cmu-bvh", path)


def test_non_finite_points_are_refused():
    pts = np.zeros((20, 2, 3))
    pts[3, 1, 1] = np.nan
    with pytest.raises(RetargetError, match="NaN or infinite"):
        retarget(pts, ["a", "b"], 1 / 30, load_map("cmu-bvh"), "x")


# --- issue 30: files from other rigs ---------------------------------------------------------------

ROOT = Path(__file__).resolve().parents[2]
DAZ_TAKE = ROOT / "data/cmu/data/Przestr+motion-capture/data/13/13_41.bvh"   # a Daz-style retarget, 369 frames


def test_a_rounded_frame_time_keeps_the_last_frame():
    # 31 frames at "Frame Time: 0.0333333" span 29.99997 frames at 30 Hz: all 31 come out, the last the file's last
    bvh = read_bvh(FIXTURES / "frame_time_rounded.bvh")
    assert len(bvh) == 31 and bvh.frame_time == 0.0333333
    points = joint_positions(bvh)
    out = resample_points(points, bvh.frame_time)
    assert len(out) == 31
    np.testing.assert_array_equal(out[-1], points[-1])
    exact = retarget(points, bvh.names, 1 / 30, load_map("cmu-bvh"), "exact")
    np.testing.assert_allclose(run("frame_time_rounded.bvh"), exact, atol=1e-5)   # 1e-6 of a frame apart in time
    # the take: 138 frames at 0.0333333 gave "137 frames ... from 138"
    assert len(resample_points(np.zeros((138, 1, 3)), 0.0333333)) == 138


@pytest.mark.parametrize("frames, frame_time, expected", [
    (8, 1 / 120, 2),          # 1.75 output frames: a real fraction is not rounded up
    (11, 0.01, 4),            # 3 frames and a third
    (41, 1 / 120, 11),        # exactly 10
    (5, 0.0333, 4),           # 3.996 frames: 1e-3 of the duration short, more than a written Frame Time's rounding
    (31, 0.0330, 30),         # 29.7 frames: no rounding explains 0.3 of a frame
    (20001, 0.033333, 20000),  # 19999.8: never more than 0.1 frame is rounded up, however long the take
])
def test_frames_out_are_the_whole_output_frames_of_the_duration(frames, frame_time, expected):
    assert len(resample_points(np.zeros((frames, 1, 3)), frame_time)) == expected


def _points(name):
    bvh = read_bvh(FIXTURES / name)
    return joint_positions(bvh), bvh.names


@pytest.mark.parametrize("name, up, fix", [("walk.bvh", "z", "y"), ("walk_zup.bvh", "y", "z")])
def test_a_wrong_up_axis_is_warned_with_the_up_that_stands_the_body_up(name, up, fix):
    points, names = _points(name)
    text = plausibility_warning(points, names, load_map("cmu-bvh", {"up": up}), name)
    assert text.startswith(f"{name}: does not look like a person standing upright")
    assert "the head is" in text and "the ankles are" in text
    assert f'the file looks {fix}-up: it was read with "up": "{up}" and lies flat; set "up": "{fix}"' in text
    assert plausibility_warning(points, names, load_map("cmu-bvh", {"up": fix}), name) is None


def test_an_upside_down_body_is_warned_without_an_up_that_would_fix_it():
    points, names = _points("walk.bvh")
    upside_down = points * np.array([1.0, -1.0, -1.0])       # turned 180 degrees about x
    text = plausibility_warning(upside_down, names, load_map("cmu-bvh"), "w")
    assert "runs along -y of the file from the feet to the head" in text and "set \"up\"" not in text


def test_bone_proportions_are_checked():
    points, names = _points("walk.bvh")
    long_shin = points.copy()
    i, knee = names.index("RightFoot"), names.index("RightLeg")
    long_shin[:, i] = points[:, knee] + 1.5 * (points[:, i] - points[:, knee])
    problems = body_problems(long_shin, names, load_map("cmu-bvh"), "w")
    assert len(problems) == 1 and problems[0].startswith("the right knee-ankle bone (")


def test_the_command_line_tries_the_pages_maps_in_the_pages_order():
    order = json.loads((ROOT / "contract/joint-maps/order.json").read_text())
    assert tried_maps("bvh") == order["bvh"] == ["cmu-bvh", "daz"]
    assert tried_maps("asf-amc") == ["cmu-asf"] and tried_maps("npz") == ["smpl"]
    # the order file is not a map: it is never offered as one
    with pytest.raises(RetargetError, match=r"no joint map named 'order' \(built in: cmu-asf, cmu-asf-bvh, cmu-bvh, "
                                            r"daz, smpl\)"):
        builtin_map("order")
    source = BvhFolderSource(FIXTURES)
    assert [m.name for m in source.maps[".bvh"]] == order["bvh"]


def test_the_command_line_reads_a_daz_file(tmp_path, capsys):
    (tmp_path / "walk").mkdir()
    shutil.copy(DAZ_TAKE, tmp_path / "walk" / "13_41.bvh")
    assert main(["data", "--data", str(tmp_path), "--out", str(tmp_path / "out")]) == 0
    index = json.loads((tmp_path / "out" / "index.json").read_text())
    clip = json.loads((tmp_path / "out" / "walk_13_41.json").read_text())
    assert [c["name"] for c in index["clips"]] == ["walk_13_41"] and clip["source"]["joint_map"] == "daz"
    assert "warning" not in capsys.readouterr().err


def test_an_unknown_skeleton_names_every_map_tried_and_every_joint():
    points, names = _points("unknown_skeleton.bvh")
    many = names + [f"Finger{i:03d}" for i in range(150)]          # a large rig: far more than 400 characters
    points = np.concatenate([points, np.zeros((len(points), 150, 3))], axis=1)
    with pytest.raises(UnknownSkeletonError) as e:
        pick_map([load_map(m) for m in tried_maps("bvh")], many, "big.bvh")
    text = str(e.value)
    assert text.startswith("big.bvh: unknown skeleton for joint map cmu-bvh: no source joint for root (tried")
    assert "Also tried joint map daz: no source joint for root, chest," in text
    assert "Tried in this order: cmu-bvh, daz." in text
    joints = [n for n in many if "/end" not in n]                 # End Sites are not joints
    assert "The file's joints are: " + ", ".join(joints) + ". Give a joint map (docs/BRING_YOUR_OWN.md)" in text
    assert "…" not in text


def test_a_daz_skeleton_picks_the_daz_map():
    bvh = read_bvh(DAZ_TAKE)
    assert pick_map([load_map(m) for m in tried_maps("bvh")], bvh.names, "d").name == "daz"
    points, names = _points("walk.bvh")
    assert pick_map([load_map(m) for m in tried_maps("bvh")], names, "w").name == "cmu-bvh"
