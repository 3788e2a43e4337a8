"""The BVH reader: grammar, forward kinematics of known rotations, and errors that name the problem."""
from pathlib import Path

import numpy as np
import pytest

from export.data.bvh import MAX_SOURCE_FRAMES, BvhFormatError, joint_positions, parse_bvh, read_bvh

FIXTURES = Path(__file__).resolve().parents[1] / "fixtures"

TWO_BONES = """HIERARCHY
ROOT Hips
{
  OFFSET 0 0 0
  CHANNELS 6 Xposition Yposition Zposition Zrotation Yrotation Xrotation
  JOINT Knee
  {
    OFFSET 0 -10 0
    CHANNELS 3 Zrotation Xrotation Yrotation
    End Site
    {
      OFFSET 0 -5 0
    }
  }
}
MOTION
Frames: 3
Frame Time: 0.5
1 2 3 0 0 0 0 0 0
0 100 0 90 0 0 0 0 0
0 0 0 0 0 0 90 90 0
"""


def test_tpose_fixture_positions_are_the_offsets_summed():
    bvh = read_bvh(FIXTURES / "tpose.bvh")
    assert len(bvh) == 48 and bvh.fps == pytest.approx(120, rel=1e-4)
    assert "Head/end" in bvh.names and "LeftHand/end" in bvh.names
    p = joint_positions(bvh)[0]
    at = {n: p[i] for i, n in enumerate(bvh.names)}
    np.testing.assert_allclose(at["Hips"], [0, 90, 0])
    np.testing.assert_allclose(at["LeftFoot"], [9, 0, 0])            # 90 - 8 - 42 - 40
    np.testing.assert_allclose(at["RightHand"], [-71, 90 + 28, 0])   # -(18 + 28 + 25), 90 + 24 + 4
    np.testing.assert_allclose(at["Head/end"], [0, 90 + 24 + 28, 0])


def test_translation_is_offset_plus_channels_and_rotations_compose_in_channel_order():
    bvh = parse_bvh(TWO_BONES, "two.bvh")
    p = joint_positions(bvh)
    knee, end = bvh.names.index("Knee"), bvh.names.index("Knee/end")
    # frame 0: translation only
    np.testing.assert_allclose(p[0, 0], [1, 2, 3])
    np.testing.assert_allclose(p[0, end], [1, 2 - 15, 3])
    # frame 1: root Zrotation 90 turns -y into +x
    np.testing.assert_allclose(p[1, knee], [10, 100, 0], atol=1e-12)
    np.testing.assert_allclose(p[1, end], [15, 100, 0], atol=1e-12)
    # frame 2: knee "Zrotation Xrotation Yrotation" = 90, 90, 0: R = Rz(90) Rx(90) (intrinsic):
    # Rx(90) turns (0, -5, 0) to (0, 0, -5), which Rz keeps. The other order, Rx Rz, would give (5, 0, 0).
    np.testing.assert_allclose(p[2, end], [0, -10, -5], atol=1e-12)


def test_crlf_tabs_blank_lines_and_a_bom_are_fine():
    text = "\ufeff" + TWO_BONES.replace("\n", "\r\n").replace("  ", "\t") + "\r\n\r\n"
    a, b = parse_bvh(text), parse_bvh(TWO_BONES)
    np.testing.assert_array_equal(a.motion, b.motion)
    assert a.names == b.names


@pytest.mark.parametrize("edit, message", [
    (lambda t: "hello world\n" + t, "not a BVH file"),
    (lambda t: "", "not a BVH file"),
    (lambda t: t[: t.index("MOTION")], "file ends where"),
    (lambda t: t[: len(t) - 20], "Frames: 3\" but the file has 2 frame lines (truncated?)"),
    (lambda t: t + "1 2 3 4 5 6 7 8 9\n", "has 4 frame lines"),
    (lambda t: t.replace("OFFSET 0 -10 0", "OFFSET 0 -10"), "line 8: expected \"OFFSET x y z\""),
    (lambda t: t.replace("CHANNELS 3 Zrotation", "CHANNELS 4 Zrotation"), "CHANNELS says 4 but lists 3"),
    (lambda t: t.replace("Xrotation Yrotation\n", "Xrotation Wrotation\n"), "unknown channel \"Wrotation\""),
    (lambda t: t.replace("0 100 0 90", "0 1e999 0 90"), "line 20: \"1e999\" is not a finite number"),
    (lambda t: t.replace("0 100 0 90", "0 NaN 0 90"), "\"NaN\" is not a finite number"),
    (lambda t: t.replace("0 100 0 90", "0 1.5.3 0 90"), "\"1.5.3\" is not a finite number"),
    (lambda t: t.replace("0 100 0 90", "0 0x10 0 90"), "\"0x10\" is not a finite number"),
    (lambda t: t.replace("0 100 0 90 0 0 0 0 0", "0 100 0 90 0 0 0 0"), "line 20: a frame needs 9 numbers"),
    (lambda t: t.replace("Frame Time: 0.5", "Frame Time: 0"), "Frame Time must be positive"),
    (lambda t: t.replace("JOINT Knee", "JOINT Hips"), "joint name \"Hips\" appears twice"),
    (lambda t: t.replace("  JOINT Knee\n  {", "  JOINT Knee {"), "expected \"{\" on its own line"),
    (lambda t: t.replace("Frames: 3", f"Frames: {MAX_SOURCE_FRAMES + 1}"), "more than this reader takes"),
])
def test_broken_files_name_the_problem(edit, message):
    with pytest.raises(BvhFormatError) as e:
        parse_bvh(edit(TWO_BONES), "x.bvh")
    assert str(e.value).startswith("x.bvh: ") and message in str(e.value), str(e.value)


def test_deep_nesting_is_refused_not_recursed_into_a_crash():
    depth = 5000
    text = "HIERARCHY\nROOT r\n{\nOFFSET 0 0 0\nCHANNELS 0\n"
    text += "".join(f"JOINT j{i}\n{{\nOFFSET 0 1 0\nCHANNELS 0\n" for i in range(depth)) + "}\n" * (depth + 1)
    text += "MOTION\nFrames: 1\nFrame Time: 0.1\n\n"
    with pytest.raises(BvhFormatError, match="not a body skeleton"):
        parse_bvh(text, "deep.bvh")


def test_unreadable_path_is_named(tmp_path):
    with pytest.raises(BvhFormatError, match="missing.bvh: cannot be read"):
        read_bvh(tmp_path / "missing.bvh")


SIX = """HIERARCHY
ROOT Hips
{
  OFFSET 0 0 0
  CHANNELS 6 Xposition Yposition Zposition Zrotation Yrotation Xrotation
  JOINT Knee
  {
    OFFSET 0 -10 0
    CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation
    End Site
    {
      OFFSET 0 -5 0
    }
  }
}
MOTION
Frames: 2
Frame Time: 0.5
1 2 3 0 0 0 0 -10 0 0 0 0
1 2 3 90 0 0 0 -7 4 0 0 0
"""


def test_position_channels_on_a_non_root_joint_replace_its_offset():
    bvh = parse_bvh(SIX, "six.bvh")
    p = joint_positions(bvh)
    knee = bvh.names.index("Knee")
    # the root still adds its channels to its OFFSET; the knee's channels are its local position
    np.testing.assert_allclose(p[:, 0], [[1, 2, 3], [1, 2, 3]])
    np.testing.assert_allclose(p[0, knee], [1, 2 - 10, 3])            # not 2 - 20: the OFFSET is not added
    np.testing.assert_allclose(p[1, knee], [1 + 7, 2, 3 + 4], atol=1e-12)   # (0, -7, 4) turned by Rz(90)


def test_a_rig_with_six_channels_on_every_joint_keeps_its_bone_lengths_and_travel():
    """six_channels.bvh: every joint's position channels repeat its OFFSET (a game rig's way). Its bones
    must be as long as its OFFSETs, and its body (root travel included) is walk.bvh's, in centimetres."""
    bvh = read_bvh(FIXTURES / "six_channels.bvh")
    assert all(len(c) == 6 for c in bvh.channels if c)
    p = joint_positions(bvh)
    for j, parent in enumerate(bvh.parents):
        if parent >= 0:
            bone = np.linalg.norm(p[:, j] - p[:, parent], axis=-1)
            np.testing.assert_allclose(bone, np.linalg.norm(bvh.offsets[j]), rtol=0, atol=1e-9, err_msg=bvh.names[j])
    walk = read_bvh(FIXTURES / "walk.bvh")
    assert walk.names == bvh.names
    # the fixtures write 4 decimals: walk.bvh's root in CMU units (5.6 cm each), so 3e-4 cm apart at most
    np.testing.assert_allclose(p, joint_positions(walk) * (2.54 / 0.45), rtol=0, atol=1e-3)
    travel = p[-1, 0, 2] - p[0, 0, 2]
    assert travel == pytest.approx(180.0, abs=0.01)                   # 1.2 m/s for 1.5 s, not half of it
