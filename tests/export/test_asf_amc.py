"""The ASF/AMC reader: forward kinematics by hand, errors that name the problem, and the CMU data itself
(the same take read as ASF/AMC and as cgspeed BVH; every skeleton's leg; one take of each ASF/AMC source)."""
import json
import re
from pathlib import Path

import numpy as np
import pytest

from export.data.asf_amc import (AsfAmcFormatError, joint_positions, parse_amc, parse_asf, read_amc, read_asf,
                                 read_asf_amc)
from export.data.bvh import joint_positions as bvh_positions, read_bvh

CMU = Path(__file__).resolve().parents[2] / "data" / "cmu"
UNIT = 0.0254 / 0.45   # CMU's "length 0.45": one unit is 1/0.45 inch

FIXTURES = Path(__file__).resolve().parents[1] / "fixtures"
# A hand-made skeleton (a leg: thigh, shin; and an arm) and its motion; tests/web/asf-amc.test.ts reads them too.
ASF = (FIXTURES / "tiny.asf").read_text()

AMC = (FIXTURES / "tiny.amc").read_text()

# By hand, in file units (x UNIT for metres); points are root, thigh end, shin end, arm end.
EXPECTED = np.array([
    # frame 1: the rest pose
    [[0, 0, 0], [0, -9, 0], [0, -13.5, 0], [2, 0, 0]],
    # frame 2: root at (1, 2, 3), turned 90 degrees about y: the arm (+x) points to -z; the leg (-y) stays
    [[1, 2, 3], [1, -7, 3], [1, -11.5, 3], [1, 2, 1]],
    # frame 3: thigh rx 90 is about its local x, which its axis (z 90) turns onto world y, and the thigh
    # lies along y, so it stays (without C it would swing to -z). The shin's rx 90 (C = I) turns it to
    # -z, which the thigh's 90 degrees about y turns to -x.
    [[0, 0, 0], [0, -9, 0], [-4.5, -9, 0], [2, 0, 0]],
    # frame 4: root RX 90 then RY 90 about the fixed axes (R = Ry Rx): -y -> -z -> -x, +x stays then -> -z.
    # The other order (Rx Ry) would put the arm at +y.
    [[0, 0, 0], [-9, 0, 0], [-13.5, 0, 0], [0, 0, -2]],
], dtype=float)


def test_forward_kinematics_by_hand():
    asf = parse_asf(ASF, "tiny.asf")
    amc = parse_amc(AMC, asf, "tiny.amc")
    assert asf.names == ["root", "thigh", "shin", "arm"]
    assert list(amc.frames) == [1, 2, 3, 4] and amc.degrees
    np.testing.assert_allclose(joint_positions(asf, amc), EXPECTED * UNIT, atol=1e-12)


def test_units_radians_crlf_blank_lines_and_any_bone_order():
    asf = parse_asf(ASF.replace("length 0.45", "length 1").replace("angle deg", "angle rad")
                    .replace("axis 0 0 90", f"axis 0 0 {np.pi / 2!r}"), "inch.asf")
    assert asf.metres == pytest.approx(0.0254)
    # :RADIANS, CRLF, a blank line, bones in another order per frame (the line-by-line reader)
    amc = AMC.replace(":DEGREES", ":RADIANS").replace(" 90", f" {np.pi / 2!r}")
    amc = amc.replace("3\nroot 0 0 0 0 0 0\nthigh", "3\n\nthigh").replace(
        f"shin {np.pi / 2!r}\n", f"shin {np.pi / 2!r}\nroot 0 0 0 0 0 0\n")
    got = joint_positions(asf, parse_amc(amc.replace("\n", "\r\n"), asf, "rad.amc"))
    np.testing.assert_allclose(got, EXPECTED * 0.0254, atol=1e-12)


def test_fast_and_line_by_line_readers_agree_on_a_real_take():
    asf = read_asf(CMU / "data/sxaxmz+CMU-Dataset-Partially-Labelled/Rotations/asf/16.asf")
    text = (CMU / "data/sxaxmz+CMU-Dataset-Partially-Labelled/Rotations/Testing/16_08  - run.amc").read_text()
    fast = parse_amc(text, asf, "run.amc")
    slow = parse_amc(text.replace("\n1\n", "\n\n1\n", 1), asf, "run.amc")  # a blank line: line by line
    assert len(fast) == 239
    assert set(fast.values) == set(slow.values)
    for k in fast.values:
        np.testing.assert_array_equal(fast.values[k], slow.values[k])


def amc_error(edit, asf_text=ASF):
    with pytest.raises(AsfAmcFormatError) as e:
        parse_amc(edit(AMC), parse_asf(asf_text, "tiny.asf"), "x.amc")
    return str(e.value)


def asf_error(edit):
    with pytest.raises(AsfAmcFormatError) as e:
        parse_asf(edit(ASF), "x.asf")
    return str(e.value)


@pytest.mark.parametrize("edit, message", [
    (lambda t: "hello\n" + t, "x.asf: not an ASF file"),
    (lambda t: t[: t.index(":bonedata")], "x.asf: no :bonedata"),
    (lambda t: t[: t.index(":hierarchy")], "x.asf: no :hierarchy"),
    (lambda t: t.replace("     length 4.5\n", ""), "x.asf: line 27: the bone block has no \"length\""),
    (lambda t: t.replace("direction 0 -1 0\n     length 9", "direction 0 -1\n     length 9"),
     "x.asf: line 19: direction needs 3 numbers, found \"0 -1\""),
    (lambda t: t.replace("length 9", "length nine"), "line 20: length needs 1 number, found \"nine\""),
    (lambda t: t.replace("dof rx\n", "dof tx\n"), "line 33: dof \"tx\" is not supported"),
    (lambda t: t.replace("axis 0 0 90  XYZ", "axis 0 0 90  XYQ"), "line 21: axis order \"XYQ\""),
    (lambda t: t.replace("thigh shin\n", "thigh shine\n"), "line 45: hierarchy names \"shine\", which is not a bone"),
    (lambda t: t.replace("root thigh arm", "root thigh"), "x.asf: bone \"arm\" is not in :hierarchy"),
    (lambda t: t.replace("name shin", "name thigh"), "line 27: bone name \"thigh\" appears twice"),
    (lambda t: t[: t.rindex("  end\n:hierarchy")], "bone block opened at line 35 has no \"end\""),
    (lambda t: t.replace("order TX TY TZ RX RY RZ", "order TX TY TZ RX RY RW"), "line 11: root order"),
])
def test_broken_asf_names_the_problem(edit, message):
    text = asf_error(edit)
    assert text.startswith("x.asf: ") and message in text, text


@pytest.mark.parametrize("edit, message", [
    (lambda t: t.replace("shin 90", "shin 90 0"), "x.amc: line 15: bone \"shin\" needs 1 number, found \"90 0\""),
    (lambda t: t.replace("thigh 90 0 0", "thigh 90 0 1.5.3"), "line 14: bone \"thigh\" needs 3 numbers, found \"90 0 1.5.3\""),
    (lambda t: t.replace("thigh 90 0 0", "thigh 90 0 nan"), "line 14: bone \"thigh\" needs 3 numbers"),
    (lambda t: t.replace("root 1 2 3 0 90 0", "root 1 2 3 0 90"), "line 9: the root needs 6 numbers"),
    (lambda t: t.replace("shin 90", "shine 90"), "line 15: \"shine\" is not a bone with dofs in the ASF"),
    (lambda t: t.replace("3\nroot", "5\nroot"), "line 12: frame 5 follows frame 2 (frames must count up by one)"),
    (lambda t: t.replace("thigh 90 0 0\n", ""), "line 15: frame 3 (line 12) has no values for thigh"),
    (lambda t: t.replace("shin 90\n", "shin 90\nshin 90\n"), "line 16: bone \"shin\" appears twice in frame 3"),
    (lambda t: t.split("1\nroot")[0], "x.amc: no frames"),
    (lambda t: t.replace(":DEGREES", ":DEGREEZ"), "line 3: unknown keyword \":DEGREEZ\""),
    (lambda t: t.replace("1\nroot 0", "root 0", 1), "line 4: \"root 0 0 0 0 0 0\" comes before the first frame number"),
    (lambda t: t.replace("\n4\n", "\n4.5\n"), "line 16: \"4.5\" is not a bone with dofs in the ASF (frame numbers are whole numbers"),
])
def test_broken_amc_names_the_line_and_the_problem(edit, message):
    text = amc_error(edit)
    assert text.startswith("x.amc: ") and message in text, text


def test_arm_dofs_in_the_amc_of_a_bone_without_dofs_is_an_error():
    text = amc_error(lambda t: t.replace("shin 0\n2", "shin 0\narm 5\n2"))
    assert "line 8: \"arm\" is not a bone with dofs in the ASF" in text


def test_unreadable_files_are_named(tmp_path):
    with pytest.raises(AsfAmcFormatError, match="missing.asf: cannot be read"):
        read_asf(tmp_path / "missing.asf")
    with pytest.raises(AsfAmcFormatError, match="missing.amc: cannot be read"):
        read_amc(tmp_path / "missing.amc", parse_asf(ASF))


# --- the CMU data -------------------------------------------------------------------------------------

def index():
    return json.loads((CMU / "index.json").read_text())


def mean_of(names, points, spec):
    return np.mean([points[:, names.index(n)] for n in spec.split("+")], axis=0)


def test_asf_amc_and_cgspeed_bvh_of_take_05_02_agree_in_legs_and_root():
    entry = next(e for e in index() if e["take"] == "05_02")
    names, p = read_asf_amc(CMU / entry["asf"], CMU / entry["file"])
    bvh = read_bvh(CMU / "crosscheck/05_02.bvh")
    q = bvh_positions(bvh)[1:] * UNIT          # frame 0 is cgspeed's T-pose
    assert p.shape[0] == q.shape[0] == entry["frames"] == 1123
    # cgspeed leaves out the thorax, so only the legs and the root line up
    pairs = {"lhipjoint+rhipjoint": "LeftUpLeg+RightUpLeg", "lhipjoint": "LeftUpLeg", "rhipjoint": "RightUpLeg",
             "lfemur": "LeftLeg", "rfemur": "RightLeg", "ltibia": "LeftFoot", "rtibia": "RightFoot",
             "lfoot": "LeftToeBase", "rfoot": "RightToeBase", "root": "Hips"}
    worst = max(np.abs(mean_of(names, p, a) - mean_of(bvh.names, q, b)).max() for a, b in pairs.items())
    assert worst < 1e-3, worst     # measured: 5e-6 m


def checks_skeletons():
    """CHECKS.txt's list of ASF skeletons: path -> (femur, tibia, leg) of the left leg in metres."""
    rows = {}
    for line in (CMU / "CHECKS.txt").read_text().splitlines():
        m = re.match(r"\s+data/(\S+\.asf)\s+femur ([\d.]+) tibia ([\d.]+) leg ([\d.]+)$", line)
        if m:
            rows[m[1]] = tuple(float(m[i]) for i in (2, 3, 4))
    return rows


def test_every_asf_skeleton_has_the_leg_checks_measured():
    want = checks_skeletons()
    used = {e["asf"].removeprefix("data/") for e in index() if e["asf"]}
    assert len(want) == 12 and set(want) == used
    for path, (femur, tibia, leg) in want.items():
        asf = read_asf(CMU / "data" / path)
        bone = {b.name: b.length * asf.metres for b in asf.bones}
        assert (round(bone["lfemur"], 3), round(bone["ltibia"], 3)) == (femur, tibia), path
        assert 0.74 <= bone["lfemur"] + bone["ltibia"] <= 0.90, path


@pytest.mark.parametrize("take, asf, frames", [
    ("35_01", "SheffieldML+vargplvm/vargplvm/matlab/35.asf", 358),            # SheffieldML's own AMC
    ("35_18", "SheffieldML+vargplvm/vargplvm/matlab/35.asf", 175),            # sxaxmz's AMC on that skeleton
    ("105_02", "sxaxmz+CMU-Dataset-Partially-Labelled/105/105.asf", 1748),    # subject 105 (sxaxmz @ d602543)
    ("01_01", "cyun9601+CMU-MOCAP-Data/data/CMU/asfamc/subjects/01/01.asf", 2751),
])
def test_each_asf_amc_source_reads_with_its_own_skeleton(take, asf, frames):
    entry = next(e for e in index() if e["take"] == take)
    assert entry["asf"] == f"data/{asf}"
    skeleton = read_asf(CMU / entry["asf"])
    amc = read_amc(CMU / entry["file"], skeleton)
    assert len(amc) == entry["frames"] == frames and amc.frames[0] == 1
    # every frame gives exactly the skeleton's dofs (the fast reader took it: no gaps, no extra bones)
    assert set(amc.values) == {"root"} | {b.name for b in skeleton.bones if b.dof}
    p = joint_positions(skeleton, amc)
    names = skeleton.names
    leg = np.mean([np.median(np.linalg.norm(p[:, names.index(f"{s}hipjoint")] - p[:, names.index(f"{s}femur")], axis=-1)
                             + np.linalg.norm(p[:, names.index(f"{s}femur")] - p[:, names.index(f"{s}tibia")], axis=-1))
                   for s in "lr"])
    assert 0.74 <= leg <= 0.90
    # metres, y up: the root stands about a leg above the floor
    assert 0.6 * leg < np.median(p[:, 0, 1]) - np.percentile(p[:, names.index("ltibia"), 1], 5) < 1.3 * leg


# --- issue 30: an ASF that does not fit its AMC --------------------------------------------------

SXAXMZ = CMU / "data/sxaxmz+CMU-Dataset-Partially-Labelled/Rotations"


@pytest.mark.parametrize("asf, amc, warned", [
    ("01.asf", "05_07.amc", True), ("05.asf", "05_07.amc", False), ("5.ASF", "05_07.amc", False),
    ("tiny.asf", "tiny.amc", False), ("skeleton.asf", "05_07.amc", False), ("16.asf", "run.amc", False),
])
def test_another_subjects_skeleton_is_named(asf, amc, warned):
    from export.data.sources import skeleton_warning
    text = skeleton_warning(Path(asf), Path(amc))
    assert (text is not None) == warned
    if warned:
        assert text == ("05_07.amc: moved by 01.asf, the skeleton of subject 01, but the take's name says subject 05: "
                        "another subject's bone lengths and joint axes do not fit the motion (feet under the floor); "
                        "use 05.asf")


def test_the_command_line_warns_on_an_amc_moved_by_another_subjects_asf(tmp_path, capsys):
    from export.data.sources import AsfAmcFolderSource
    lines = (SXAXMZ / "Training/05_02 - dance, expressive arms, pirouette.amc").read_text().splitlines(keepends=True)
    stop = next(i for i, s in enumerate(lines) if s.strip() == "161")
    (tmp_path / "dance").mkdir()
    (tmp_path / "dance" / "05_02.amc").write_text("".join(lines[:stop]))
    (tmp_path / "16.asf").write_text((SXAXMZ / "asf/16.asf").read_text())   # the only skeleton: subject 16's
    source = AsfAmcFolderSource(tmp_path)
    clips = source.clips()
    assert len(clips) == 1 and len(source.warnings) == 1
    assert "05_02.amc: moved by 16.asf, the skeleton of subject 16, but the take's name says subject 05" \
        in capsys.readouterr().err
