"""The converted clips (the CMU subset and the DeepMimic clips): geometry, travel, loops, mirroring and
the committed (served) files."""
import gzip
import json

import numpy as np
import pytest

from export.data import deepmimic
from export.data.clip_json import read_clip
from export.data.skeleton import SKELETON
from export.ops.fk import forward_kinematics
from export.ops.mirror import mirror_positions, mirror_rotations
from export.contract import load_json
from export.data.build import served
from export.data.sources import default_source, source_hash
from export.ops.floor import foot_height
from export.paths import CLIPS_DIR
from export.tolerance import derive

ACTIONS = {"backflip", "cartwheel", "crawl", "dance_a", "dance_b", "getup_facedown", "getup_faceup", "jump",
           "kick", "punch", "roll", "run", "spin", "spinkick", "walk"}


CLIPS_BUDGET = 1_500_000      # bytes gzipped (issue 17): the served clips' own budget


def bone_lengths(positions):
    return np.stack([np.linalg.norm(positions[:, j] - positions[:, p], axis=-1) for p, j in SKELETON.bones], axis=1)


def test_every_deepmimic_action_and_the_walker_takes_are_converted(deepmimic):
    assert {c.action for c in deepmimic.values()} == ACTIONS
    assert sum(c.name.startswith("walker_") for c in deepmimic.values()) == 5
    total = sum(len(c) for c in deepmimic.values()) / 30
    assert 35 < total < 45, total  # "about 40 s" (33.5 s of the 15 actions, 6.2 s of walker takes)


def test_the_default_data_is_cmu_by_person_and_deepmimic_for_training(clips):
    cmu = [c for c in clips.values() if c.name.startswith("cmu_")]
    dm = [c for c in clips.values() if c.name.startswith("deepmimic_")]
    assert len(cmu) == 242 and len(dm) == 20 and len(clips) == 262
    assert all(c.split.role == "train" and c.subject == "deepmimic" for c in dm)   # one capture each
    # both sources' labels fold into the served vocabulary (export/data/vocabulary.py)
    assert {c.action for c in dm} & {c.action for c in cmu} == {"walk", "run", "jump", "dance", "kick"}
    assert {c.action for c in cmu} == {"walk", "run", "jump", "dance", "kick", "calisthenics", "reach", "basketball"}


def test_bone_lengths_are_constant_in_every_committed_clip():
    for path in sorted(CLIPS_DIR.glob("*.json")):
        if path.name == "index.json":
            continue
        lengths = bone_lengths(read_clip(path).positions)
        spread = lengths.max(axis=0) - lengths.min(axis=0)
        assert spread.max() < 1e-6, (path.name, spread.max())
        np.testing.assert_allclose(lengths[0], SKELETON.bone_lengths(), atol=1e-6)


def test_bone_lengths_are_exact_in_loop_repeats(deepmimic):
    for clip in deepmimic.values():
        if clip.repeat is None:
            continue
        lengths = bone_lengths(clip.repeat(3))
        assert (lengths.max(axis=0) - lengths.min(axis=0)).max() < 1e-9, clip.name


def test_walk_travels_with_its_feet_on_the_floor_and_the_figure_upright(deepmimic, clips):
    # DeepMimic's floor is its simulation's ground plane (its toes ride 1 cm above it); a CMU take's is
    # estimated (ops/floor.py)
    for pos, off in ((deepmimic["walk"].positions, 0.02), (clips["cmu_08_02"].positions, 0.01)):
        feet = foot_height(pos)
        assert np.abs(np.median(feet)) < off and feet.min() > -0.04, (np.median(feet), feet.min())
        head, root = SKELETON.index("head"), SKELETON.index("root")
        assert np.all(pos[:, head, 1] > pos[:, root, 1] + 0.5) and np.all(pos[:, head, 1] > 1.3)
        # the root travels over the floor (clip version 2) at a walking pace, and keeps its height
        speed = np.linalg.norm(np.diff(pos[:, root, [0, 2]], axis=0), axis=-1).mean() * 30
        assert 0.7 < speed < 2.0, speed
        assert np.all((pos[:, root, 1] > 0.75) & (pos[:, root, 1] < 0.95))


def test_loop_repeats_accumulate_the_travel(deepmimic):
    walk = deepmimic["walk"]
    rep = walk.repeat(3)
    m = walk.cycle_frames
    one = rep[m, 0, [0, 2]] - rep[0, 0, [0, 2]]
    two = rep[2 * m, 0, [0, 2]] - rep[m, 0, [0, 2]]
    # each cycle goes on from where the last one ended, turned by the loop's own heading change
    assert np.linalg.norm(one) > 0.5 and abs(np.linalg.norm(two) - np.linalg.norm(one)) < 0.05 * np.linalg.norm(one)


def test_mirroring_equals_reconversion_with_left_and_right_swapped():
    path = deepmimic.pybullet_data_dir() / "data" / "motions" / "humanoid3d_punch.txt"  # asymmetric
    motion, _ = deepmimic.load(path)
    original = motion.positions(keep_horizontal_root=True)
    root, local = mirror_rotations(motion.root_pos, motion.local, SKELETON)
    reconverted = forward_kinematics(root, local, SKELETON)
    np.testing.assert_allclose(mirror_positions(original, SKELETON), reconverted, atol=1e-9)
    assert np.abs(original - reconverted).max() > 0.1  # the motion really is asymmetric


def test_repeated_loops_have_no_jump_larger_than_their_largest_step(deepmimic):
    for clip in deepmimic.values():
        if clip.repeat is None:
            continue
        m = clip.cycle_frames
        own = np.linalg.norm(np.diff(clip.positions, axis=0), axis=-1).max()
        rep = clip.repeat(3)
        steps = np.linalg.norm(np.diff(rep, axis=0), axis=-1).max(axis=1)
        seams = steps[[m - 1, 2 * m - 1]]
        assert seams.max() <= own, (clip.name, seams, own)
        # blending may speed up frames near the seam a little (measured worst: walker turns)
        assert steps.max() <= 1.1 * own, (clip.name, steps.max(), own)
        # and the repeat is the clip itself away from the seams
        np.testing.assert_allclose(rep[m // 2 - 1:m // 2 + 1], clip.positions[m // 2 - 1:m // 2 + 1], atol=0.2)


def test_committed_clips_are_the_served_part_of_a_fresh_conversion(clips):
    """Clips store float32 of a float64 conversion (export/tolerance.py): the tolerance is derived
    from the fresh conversion's float32 rounding gap, so a last-bit difference between machines
    passes and a real change does not."""
    shown = served(list(clips.values()))
    index = load_json(CLIPS_DIR / "index.json", "clip-index")
    assert [c["name"] for c in index["clips"]] == [c.name for c in shown]
    for clip in shown:
        committed = read_clip(CLIPS_DIR / f"{clip.name}.json")
        assert committed.split == clip.split and committed.subject == clip.subject, clip.name
        fresh = clip.positions.astype(np.float64)
        tol = derive(float(np.abs(fresh - fresh.astype(np.float32)).max()))
        assert committed.positions.shape == fresh.shape, clip.name
        worst = float(np.abs(committed.positions - fresh).max())
        assert worst <= tol, f"{clip.name}: committed and fresh differ by {worst:.3g} m (tolerance {tol:.3g})"


def test_the_served_clips_hold_every_held_out_person_and_fit_their_budget(clips):
    index = load_json(CLIPS_DIR / "index.json", "clip-index")
    held = {(c["action"], c["subject"]) for c in index["clips"] if c["role"] == "test"}
    # every action and held-out person of the data has its served takes
    assert held == {(c.action, c.subject) for c in clips.values() if c.split.role == "test"}
    assert {a for a, _ in held} == {"walk", "run", "jump", "dance", "calisthenics", "kick", "reach"}
    gz = sum(len(gzip.compress(p.read_bytes(), 9)) for p in CLIPS_DIR.glob("*.json"))
    assert gz <= CLIPS_BUDGET, f"the served clips are {gz} bytes gzipped; their budget is {CLIPS_BUDGET}"
    # the site opens on a held-out walk whose ground truth covers WAT's longest future (90 frames)
    d = index["default"]
    entry = next(c for c in index["clips"] if c["name"] == d["clip"])
    assert entry["role"] == "test" and entry["action"] == "walk" and entry["frames"] - d["start"] >= 10 + 90


def test_data_hash_is_over_the_source_files():
    assert load_json(CLIPS_DIR / "index.json", "clip-index")["data_hash"] == source_hash(default_source())


def test_version_1_clips_still_read(tmp_path):
    doc = json.loads((CLIPS_DIR / "deepmimic_walk.json").read_text())
    doc["version"] = 1
    for key in ("subject", "take"):
        doc.pop(key, None)
    frames = np.asarray(doc["positions"])
    frames[:, :, [0, 2]] -= frames[:, :1, [0, 2]]        # v1 clips held the root above the origin
    doc["positions"] = frames.tolist()
    (tmp_path / "old.json").write_text(json.dumps(doc))
    clip = read_clip(tmp_path / "old.json")
    assert clip.subject is None and np.allclose(clip.positions[:, 0, [0, 2]], 0)
    assert np.allclose(bone_lengths(clip.positions), SKELETON.bone_lengths(), atol=1e-6)


@pytest.mark.parametrize("bad", ["nan_value", "short_frame"])
def test_malformed_deepmimic_file_gives_a_readable_error(tmp_path, bad):
    path = tmp_path / "humanoid3d_bad.txt"
    frame = [0.0333] + [0.0] * 43
    if bad == "nan_value":
        frame[5] = float("nan")
        text = '{"Loop": "none", "Frames": [' + ",".join([str(frame).replace("nan", "NaN")] * 3) + "]}"
    else:
        text = '{"Loop": "none", "Frames": [[0.1, 1, 2], [0.1, 1, 2]]}'
    path.write_text(text)
    with pytest.raises(deepmimic.DeepMimicFormatError, match="humanoid3d_bad.txt"):
        deepmimic.load(path)
