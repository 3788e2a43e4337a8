"""The converted DeepMimic clips: geometry, loops, mirroring and the committed files."""
import numpy as np
import pytest

from export.data import deepmimic
from export.data.clip_json import read_clip
from export.data.skeleton import SKELETON
from export.ops.fk import forward_kinematics
from export.ops.mirror import mirror_positions, mirror_rotations
from export.paths import CLIPS_DIR
from export.tolerance import derive

ACTIONS = {"backflip", "cartwheel", "crawl", "dance_a", "dance_b", "getup_facedown", "getup_faceup", "jump",
           "kick", "punch", "roll", "run", "spin", "spinkick", "walk"}


def bone_lengths(positions):
    return np.stack([np.linalg.norm(positions[:, j] - positions[:, p], axis=-1) for p, j in SKELETON.bones], axis=1)


def test_every_action_and_the_walker_takes_are_converted(clips):
    assert {c.action for c in clips.values()} == ACTIONS
    assert sum(c.name.startswith("walker_") for c in clips.values()) == 5
    total = sum(len(c) for c in clips.values()) / 30
    assert 35 < total < 45, total  # "about 40 s" (33.5 s of the 15 actions, 6.2 s of walker takes)


def test_bone_lengths_are_constant_in_every_committed_clip():
    for path in sorted(CLIPS_DIR.glob("*.json")):
        if path.name == "index.json":
            continue
        lengths = bone_lengths(read_clip(path).positions)
        spread = lengths.max(axis=0) - lengths.min(axis=0)
        assert spread.max() < 1e-6, (path.name, spread.max())
        np.testing.assert_allclose(lengths[0], SKELETON.bone_lengths(), atol=1e-6)


def test_bone_lengths_are_exact_in_loop_repeats(clips):
    for clip in clips.values():
        if clip.repeat is None:
            continue
        lengths = bone_lengths(clip.repeat(3))
        assert (lengths.max(axis=0) - lengths.min(axis=0)).max() < 1e-9, clip.name


def test_walk_feet_touch_the_ground_and_the_figure_is_upright(clips):
    pos = clips["walk"].positions
    lowest = pos[..., 1].min(axis=1)
    assert np.all(np.abs(lowest) < 0.03), lowest.round(3)
    feet = [SKELETON.index(n) for n in ("right_toe", "left_toe", "right_ankle", "left_ankle")]
    assert np.allclose(pos[:, feet, 1].min(axis=1), lowest)  # the lowest point is a foot
    head, root = SKELETON.index("head"), SKELETON.index("root")
    assert np.all(pos[:, head, 1] > pos[:, root, 1] + 0.5)
    assert np.all(pos[:, head, 1] > 1.4)
    # no horizontal root translation, root height kept
    assert np.allclose(pos[:, root, [0, 2]], 0)
    assert np.all((pos[:, root, 1] > 0.8) & (pos[:, root, 1] < 0.95))


def test_mirroring_equals_reconversion_with_left_and_right_swapped():
    path = deepmimic.pybullet_data_dir() / "data" / "motions" / "humanoid3d_punch.txt"  # asymmetric
    motion, _ = deepmimic.load(path)
    original = motion.positions(keep_horizontal_root=True)
    root, local = mirror_rotations(motion.root_pos, motion.local, SKELETON)
    reconverted = forward_kinematics(root, local, SKELETON)
    np.testing.assert_allclose(mirror_positions(original, SKELETON), reconverted, atol=1e-9)
    assert np.abs(original - reconverted).max() > 0.1  # the motion really is asymmetric


def test_repeated_loops_have_no_jump_larger_than_their_largest_step(clips):
    for clip in clips.values():
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


def test_committed_clips_match_a_fresh_conversion(clips):
    """Clips store float32 of a float64 conversion (export/tolerance.py): the tolerance is derived
    from the fresh conversion's float32 rounding gap, so a last-bit difference between machines
    passes and a real change does not."""
    for name, clip in clips.items():
        committed = read_clip(CLIPS_DIR / f"{name}.json")
        assert committed.split == clip.split, name
        fresh = clip.positions.astype(np.float64)
        tol = derive(float(np.abs(fresh - fresh.astype(np.float32)).max()))
        assert committed.positions.shape == fresh.shape, name
        worst = float(np.abs(committed.positions - fresh).max())
        assert worst <= tol, f"{name}: committed and fresh differ by {worst:.3g} m (tolerance {tol:.3g})"


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
