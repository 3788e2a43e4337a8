"""User folders for `python -m export data --data FOLDER`: ASF/AMC folders (CMU's own form), and mixed folders
(BVH + ASF/AMC + npz + other files) in which every skipped file is named with the reason."""
import json
import shutil
from pathlib import Path

import numpy as np
import pytest

from export.cli import main
from export.data.asf_amc import AsfAmcFormatError, read_asf_amc
from export.data.retarget import load_map, retarget
from export.data.sources import (AsfAmcFolderSource, BvhFolderSource, FolderSource, NpzFolderSource, source_for,
                                 source_hash)

ROOT = Path(__file__).resolve().parents[2]
FIXTURES = ROOT / "tests" / "fixtures"
SXAXMZ = ROOT / "data/cmu/data/sxaxmz+CMU-Dataset-Partially-Labelled/Rotations"
CMU_FILES = {   # two CMU takes and their skeletons, as CMU names them
    "05.asf": SXAXMZ / "asf/05.asf",
    "16.asf": SXAXMZ / "asf/16.asf",
    "05_02.amc": SXAXMZ / "Training/05_02 - dance, expressive arms, pirouette.amc",
    "16_08.amc": SXAXMZ / "Testing/16_08  - run.amc",
}


def amc_head(src: Path, frames: int) -> str:
    """The AMC's header and its first `frames` frames (a small copy of a CMU take)."""
    lines = src.read_text().splitlines(keepends=True)
    stop = next(i for i, s in enumerate(lines) if s.strip() == str(frames + 1))
    return "".join(lines[:stop])


def put(folder: Path, rel: str, src: str, frames: int = 160) -> Path:
    path = folder / rel
    path.parent.mkdir(parents=True, exist_ok=True)
    if src.endswith(".amc"):
        path.write_text(amc_head(CMU_FILES[src], frames))
    elif src in CMU_FILES:
        shutil.copy(CMU_FILES[src], path)
    else:
        shutil.copy(FIXTURES / src, path)
    return path


def make(folder: Path, files: dict[str, str]) -> Path:
    for rel, src in files.items():
        put(folder, rel, src)
    return folder


def expected(asf: str, amc: Path, fps: float = 120.0) -> np.ndarray:
    names, points = read_asf_amc(CMU_FILES[asf], amc)
    return retarget(points, names, 1 / fps, load_map("cmu-asf"), "expected")


@pytest.fixture
def asf_folder(tmp_path):
    """CMU's layout: skeletons at the top, motions in sub-folders named after their actions."""
    return make(tmp_path / "cmu_asf", {"05.asf": "05.asf", "dance/05_02.amc": "05_02.amc",
                                       "run/16.asf": "16.asf", "run/16_08.amc": "16_08.amc"})


def test_an_asf_amc_folder_reads_each_motion_with_its_subjects_skeleton_at_120_fps(asf_folder):
    src = source_for(asf_folder)
    assert isinstance(src, AsfAmcFolderSource) and src.name == "asf-amc"
    assert src.skeleton_of(asf_folder / "dance/05_02.amc") == (asf_folder / "05.asf", "")
    assert src.skeleton_of(asf_folder / "run/16_08.amc") == (asf_folder / "run/16.asf", "")
    clips = {c.name: c for c in src.clips()}
    assert sorted(clips) == ["dance_05_02", "run_16_08"]
    assert [clips[n].action for n in sorted(clips)] == ["dance", "run"]
    for name, asf in (("dance_05_02", "05.asf"), ("run_16_08", "16.asf")):
        c = clips[name]
        assert c.fps == 30.0 and len(c) == 40 and c.source["joint_map"] == "cmu-asf"   # 160 frames at 120 fps
        assert c.source["dataset"] == "ASF/AMC motion capture (cmu_asf)"
        np.testing.assert_allclose(c.positions, expected(asf, asf_folder / c.source["file"]), atol=1e-12)
    assert src.skipped == []
    assert set(src.data_files()) == {asf_folder / p for p in ("05.asf", "dance/05_02.amc", "run/16.asf", "run/16_08.amc")}


def test_a_sidecar_or_labels_set_an_amcs_frame_rate_and_action(asf_folder):
    (asf_folder / "run/16_08.json").write_text(json.dumps({"fps": 60}))
    (asf_folder / "labels.json").write_text(json.dumps({"dance/05_02.amc": {"action": "ballet", "test_only": True}}))
    src = source_for(asf_folder)
    clips = {c.name: c for c in src.clips()}
    assert len(clips["run_16_08"]) == 80                    # 160 frames at 60 fps: twice as long
    np.testing.assert_allclose(clips["run_16_08"].positions,
                               expected("16.asf", asf_folder / "run/16_08.amc", fps=60.0), atol=1e-12)
    assert clips["dance_05_02"].action == "ballet" and clips["dance_05_02"].split.role == "test"
    assert asf_folder / "run/16_08.json" in src.data_files() and src.skipped == []
    (asf_folder / "run/16_08.json").write_text(json.dumps({"fps": "fast"}))
    with pytest.raises(ValueError, match=r'16_08.json: the sidecar of an .amc is \{"fps": <frames per second>\}'):
        source_for(asf_folder).clips()


def test_the_skeleton_rule_single_asf_and_skips_with_reasons(tmp_path):
    data = make(tmp_path / "d", {
        "walk/my take.amc": "16_08.amc", "walk/any name.asf": "16.asf",   # no subject prefix: the only .asf
        "jump/07_01.amc": "05_02.amc", "jump/05x.asf": "05.asf", "jump/16.asf": "16.asf",   # no 07.asf, two others
        "spin/09_01.amc": "05_02.amc"})                                    # no .asf anywhere above it
    src = AsfAmcFolderSource(data)
    assert src.skeleton_of(data / "walk/my take.amc") == (data / "walk/any name.asf", "")
    assert [c.name for c in src.clips()] == ["walk_my_take"]
    assert src.skipped == [
        (data / "jump/05x.asf", "a skeleton that no .amc file here uses"),
        (data / "jump/07_01.amc", "no skeleton: no 07.asf beside it or in a folder above, and 2 .asf files to "
                                  "choose from (05x.asf, 16.asf)"),
        (data / "jump/16.asf", "a skeleton that no .amc file here uses"),
        (data / "spin/09_01.amc", "no skeleton: no 09.asf beside it or in a folder above, and no .asf file there at all"),
    ]


def test_an_amc_that_does_not_fit_its_skeleton_is_an_error_naming_it(tmp_path):
    data = tmp_path / "d"
    put(data, "walk/05_02.amc", "05_02.amc")
    put(data, "walk/05.asf", "05.asf")
    asf = data / "walk/05.asf"
    asf.write_text(asf.read_text().replace("rfemur", "rthigh"))     # a skeleton whose bones have other names
    with pytest.raises(AsfAmcFormatError, match=r"walk/05_02.amc: line \d+: \"rfemur\" is not a bone with dofs"):
        source_for(data).clips()


@pytest.fixture
def mixed(tmp_path):
    data = make(tmp_path / "mixed", {
        "walk/walk.bvh": "walk.bvh", "walk/smpl.npz": "smpl22_walk.npz",
        "05.asf": "05.asf", "dance/05_02.amc": "05_02.amc",               # 05.asf is two folders up
        "extra/99_01.amc": "05_02.amc",                    # no 99.asf, and two others beside it to choose from
        "extra/16.asf": "16.asf", "extra/35.asf": "16.asf"})
    (data / "README.txt").write_text("my takes\n")
    (data / "walk/notes.json").write_text("{}\n")
    (data / "walk/take.c3d").write_bytes(b"\0\1")
    return data


SKIPPED = {
    "README.txt": "not a motion file this version reads (DeepMimic humanoid3d_*.txt, *.bvh, *.amc with its *.asf "
                  "skeleton, *.npz)",
    "extra/16.asf": "a skeleton that no .amc file here uses",
    "extra/35.asf": "a skeleton that no .amc file here uses",
    "extra/99_01.amc": "no skeleton: no 99.asf beside it or in a folder above, and 2 .asf files to choose from "
                       "(16.asf, 35.asf)",
    "walk/notes.json": "not a motion file this version reads (DeepMimic humanoid3d_*.txt, *.bvh, *.amc with its *.asf "
                       "skeleton, *.npz)",
    "walk/take.c3d": "not a motion file this version reads (DeepMimic humanoid3d_*.txt, *.bvh, *.amc with its *.asf "
                     "skeleton, *.npz)",
}


def test_a_mixed_folder_reads_every_kind_and_names_every_skipped_file_with_its_reason(mixed, capsys):
    src = source_for(mixed)
    assert type(src) is FolderSource and src.name == "folder"
    clips = {c.name: c for c in src.clips()}
    assert {n: (c.action, c.source["joint_map"]) for n, c in clips.items()} == {
        "walk_walk": ("walk", "cmu-bvh"), "walk_smpl": ("walk", "smpl"), "dance_05_02": ("dance", "cmu-asf")}
    # the npz holds the same walk as the BVH (tests/fixtures/make_fixtures.py)
    np.testing.assert_allclose(clips["walk_smpl"].positions, clips["walk_walk"].positions, atol=1e-5)
    assert {p.relative_to(mixed).as_posix(): why for p, why in src.skipped} == SKIPPED
    err = capsys.readouterr().err
    for rel, why in SKIPPED.items():
        assert f"mixed: skipped {rel}: {why}" in err
    files = {p.relative_to(mixed).as_posix() for p in src.data_files()}
    assert files == {"walk/walk.bvh", "walk/smpl.npz", "05.asf", "dance/05_02.amc"}


def test_python_m_export_data_on_an_asf_amc_folder_and_on_a_mixed_folder(asf_folder, mixed, tmp_path, capsys):
    assert main(["data", "--data", str(asf_folder), "--out", str(tmp_path / "a")]) == 0
    index = json.loads((tmp_path / "a" / "index.json").read_text())
    assert sorted(c["name"] for c in index["clips"]) == ["dance_05_02", "run_16_08"]
    assert all(c["frames"] == 40 and c["dataset"] == "ASF/AMC motion capture (cmu_asf)" for c in index["clips"])
    assert index["written_by"].startswith("asf-amc (")
    assert (tmp_path / "a" / "run_16_08.json").exists()
    capsys.readouterr()
    assert main(["data", "--data", str(mixed), "--out", str(tmp_path / "m")]) == 0
    out = capsys.readouterr()
    assert "wrote 3 clips" in out.out
    assert all(f"skipped {rel}: {why}" in out.err for rel, why in SKIPPED.items())
    index = json.loads((tmp_path / "m" / "index.json").read_text())
    assert sorted(c["name"] for c in index["clips"]) == ["dance_05_02", "walk_smpl", "walk_walk"]


def test_the_data_hash_covers_an_amcs_skeleton(asf_folder):
    before = source_hash(source_for(asf_folder))
    asf = asf_folder / "05.asf"
    asf.write_text(asf.read_text().replace("length 0.45", "length 0.4500"))
    assert source_hash(source_for(asf_folder)) != before


def test_one_kind_folders_keep_their_source_and_what_is_not_a_motion_file_is_refused(tmp_path):
    put(tmp_path / "b", "walk/a.bvh", "walk.bvh")
    (tmp_path / "b" / "walk" / "a.txt").write_text("x")
    assert type(source_for(tmp_path / "b")) is BvhFolderSource        # the same written_by as before
    put(tmp_path / "n", "walk/a.npz", "smpl22_walk.npz")
    assert type(source_for(tmp_path / "n")) is NpzFolderSource
    (tmp_path / "s").mkdir()
    put(tmp_path / "s", "05.asf", "05.asf")
    (tmp_path / "s" / "notes.txt").write_text("x")
    with pytest.raises(ValueError, match=r"no motion files this version can read \(DeepMimic humanoid3d_\*.txt, "
                                         r"\*.bvh, \*.amc with its \*.asf skeleton, \*.npz\)"):
        source_for(tmp_path / "s")
    # a folder whose only motions are skipped says why
    put(tmp_path / "o", "walk/07_01.amc", "05_02.amc")
    with pytest.raises(FileNotFoundError, match=r"no .amc files it can read \(skipped walk/07_01.amc: no skeleton"):
        source_for(tmp_path / "o").clips()
