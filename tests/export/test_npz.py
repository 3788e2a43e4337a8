"""npz joint positions, folder sources (labels, joint maps) and the data/train commands on a user folder."""
import json
import shutil
from pathlib import Path

import numpy as np
import pytest

from export.cli import main
from export.data.bvh import joint_positions, read_bvh
from export.data.npz import NpzFormatError, load_npz
from export.data.retarget import load_map, retarget
from export.data.sources import BvhFolderSource, NpzFolderSource, clip_name, source_for

FIXTURES = Path(__file__).resolve().parents[1] / "fixtures"


def bvh_walk():
    bvh = read_bvh(FIXTURES / "walk.bvh")
    return retarget(joint_positions(bvh), bvh.names, bvh.frame_time, load_map("cmu-bvh"), "walk")


def test_smpl22_npz_retargets_like_the_bvh_it_was_made_from(tmp_path):
    # the fixture holds the walk's points in SMPL order, z-up, float32, with mocap_framerate = 100
    (tmp_path / "walk").mkdir()
    shutil.copy(FIXTURES / "smpl22_walk.npz", tmp_path / "walk" / "take.npz")
    clips = source_for(tmp_path).clips()
    assert [(c.name, c.action, c.fps, len(c)) for c in clips] == [("walk_take", "walk", 30.0, 46)]
    np.testing.assert_allclose(clips[0].positions, bvh_walk(), atol=1e-5)


def test_sidecar_and_npz_keys_for_fps_up_and_names(tmp_path):
    motion = load_npz(FIXTURES / "smpl22_walk.npz")
    y_up = np.stack([motion.points[..., 0], motion.points[..., 2], -motion.points[..., 1]], axis=-1)
    order = load_map("smpl").orders["22"]
    shuffled = list(reversed(range(22)))
    np.savez(tmp_path / "a.npz", positions=y_up[:, shuffled].reshape(len(y_up), -1), up_axis="y",
             joint_names=np.array([order[i] for i in shuffled]))
    (tmp_path / "a.json").write_text(json.dumps({"fps": 100}))
    got = load_npz(tmp_path / "a.npz")
    assert got.fps == 100 and got.up == "y" and got.names[0] == "right_wrist" and got.points.shape == (151, 22, 3)
    (tmp_path / "a.json").write_text(json.dumps({"fps": 100, "up": "y"}))
    src = NpzFolderSource(tmp_path)
    np.testing.assert_allclose(src._positions(tmp_path / "a.npz"), bvh_walk(), atol=1e-5)


@pytest.mark.parametrize("arrays, message", [
    ({"poses": np.zeros((5, 156)), "trans": np.zeros((5, 3)), "betas": np.zeros(16)},
     "no joint positions: expected an array named one of joints, positions, joint_positions, Jtr [frames, joints, 3]; "
     "found betas, poses, trans. It holds SMPL body-model parameters"),
    ({"joints": np.zeros((5, 22, 2)), "fps": 30}, "array 'joints' must be numbers of shape [frames, joints, 3]"),
    ({"joints": np.zeros((5, 22, 3))}, "no frame rate: add one of mocap_framerate"),
    ({"joints": np.full((5, 22, 3), np.nan), "fps": 30}, "contains NaN"),
    ({"joints": np.zeros((5, 22, 3)), "fps": -1}, "frame rate must be positive"),
    ({"joints": np.zeros((5, 22, 3)), "fps": 30, "up": "x"}, "up axis must be \"y\" or \"z\""),
])
def test_npz_without_what_is_needed_names_the_problem(tmp_path, arrays, message):
    np.savez(tmp_path / "bad.npz", **arrays)
    with pytest.raises(NpzFormatError) as e:
        load_npz(tmp_path / "bad.npz")
    assert "bad.npz: " in str(e.value) and message in str(e.value), str(e.value)


def test_not_an_npz_is_named(tmp_path):
    (tmp_path / "x.npz").write_text("HIERARCHY\n")
    with pytest.raises(NpzFormatError, match="x.npz: not a readable .npz file"):
        load_npz(tmp_path / "x.npz")
    np.save(tmp_path / "y.npy", np.zeros(3))
    (tmp_path / "y.npy").rename(tmp_path / "y.npz")
    with pytest.raises(NpzFormatError, match="y.npz: a single .npy array"):
        load_npz(tmp_path / "y.npz")


def test_an_unknown_joint_count_asks_for_names(tmp_path):
    (tmp_path / "walk").mkdir()
    np.savez(tmp_path / "walk" / "x.npz", joints=np.zeros((40, 31, 3)), fps=30)
    with pytest.raises(ValueError, match="31 joints is not a joint order the smpl map knows \\(22, 24, 52, 55\\)"):
        source_for(tmp_path).clips()


def test_labels_from_folders_or_a_map_and_test_only_clips(tmp_path):
    shutil.copy(FIXTURES / "walk.bvh", tmp_path / "w1.bvh")
    (tmp_path / "jumps").mkdir()
    shutil.copy(FIXTURES / "knee.bvh", tmp_path / "jumps" / "Knee Take.bvh")
    with pytest.raises(ValueError, match="w1.bvh: no action label: put it in a sub-folder named after its action"):
        source_for(tmp_path).clips()
    (tmp_path / "labels.json").write_text(json.dumps({"w1": {"action": "walk", "test_only": True}}))
    clips = {c.name: c for c in source_for(tmp_path).clips()}
    assert set(clips) == {"w1", "jumps_knee_take"}
    assert clips["w1"].action == "walk" and clips["w1"].split.role == "test"
    assert clips["jumps_knee_take"].action == "jumps" and clips["jumps_knee_take"].split.role == "train"
    assert clips["w1"].source["file"] == "w1.bvh" and clips["w1"].source["joint_map"] == "cmu-bvh"


def test_a_folder_joint_map_is_used(tmp_path):
    (tmp_path / "walk").mkdir()
    shutil.copy(FIXTURES / "walk_zup.bvh", tmp_path / "walk" / "z.bvh")
    (tmp_path / "joint-map.json").write_text(json.dumps({"up": "z"}))
    clip, = BvhFolderSource(tmp_path).clips()
    np.testing.assert_allclose(clip.positions, bvh_walk(), atol=1e-9)


def test_folder_errors(tmp_path):
    with pytest.raises(FileNotFoundError, match="no such folder"):
        source_for(tmp_path / "nope")
    with pytest.raises(ValueError, match="no motion files this version can read"):
        source_for(tmp_path)
    # a folder of several kinds is read by one source (tests/export/test_sources_folders.py)


def test_clip_names_follow_the_contract():
    assert clip_name(Path("Walk/01 01.bvh")) == "walk_01_01"
    assert clip_name(Path("_x/ä.npz")) == "x__"


def test_data_and_train_commands_on_a_folder_of_bvh_files(tmp_path, capsys):
    data = tmp_path / "data"
    for action, files in {"walk": ["walk.bvh", "walk_zup.bvh"], "stand": ["tpose.bvh", "knee.bvh"]}.items():
        (data / action).mkdir(parents=True)
        for f in files:
            shutil.copy(FIXTURES / f, data / action / f)
    (data / "joint-map.json").write_text(json.dumps({"joints": {"head": ["Head"]}}))
    # walk_zup.bvh read as y-up is a (lying) clip too; the point here is the path from files to training
    assert main(["data", "--data", str(data), "--out", str(tmp_path / "clips")]) == 0
    index = json.loads((tmp_path / "clips" / "index.json").read_text())
    assert sorted(c["name"] for c in index["clips"]) == ["stand_knee", "stand_tpose", "walk_walk", "walk_walk_zup"]
    assert main(["train", "--config", "regression.json", "--data", str(data), "--steps", "3",
                 "--run-dir", str(tmp_path / "run")]) == 0
    assert (tmp_path / "run" / "weights.pt").exists()
    # a broken file in the folder is one readable line, not a traceback
    (data / "walk" / "broken.bvh").write_text("HIERARCHY\nROOT Hips\n{\n")
    capsys.readouterr()
    assert main(["data", "--data", str(data), "--out", str(tmp_path / "clips")]) == 2
    assert "broken.bvh: the file ends where OFFSET was expected (truncated?)" in capsys.readouterr().err
