"""The DeepMimic source's own split (a user's DeepMimic folder keeps it): walker takes test-only, test tails."""
import numpy as np
import pytest

from export.contract import load_json
from export.data.build import served
from export.data.windows import windows
from export.paths import CLIPS_DIR


@pytest.fixture(scope="module")
def clips(deepmimic):
    return deepmimic


def test_roles(clips):
    roles = {name: c.split.role for name, c in clips.items()}
    assert all(roles[n] == "test" for n in roles if n.startswith("walker_"))
    tailed = {n for n, r in roles.items() if r == "train+test"}
    assert tailed == {"spin", "getup_faceup"}  # the only clips with >= 40 test frames after keeping 60%
    for n in tailed:
        c = clips[n]
        (a, b), = c.split.test
        (ta, tb), = c.split.train
        assert ta == 0 and tb == a and b == len(c) and b - a >= 40 and tb >= 0.6 * len(c)
        assert c.repeat is None  # a repeat would run training into the test tail


def test_no_training_window_touches_a_test_frame(clips):
    ws = windows(list(clips.values()), "train", length=70, history=10, mirror=True)
    assert len(ws) > 500
    test_frames = {name: {f for a, b in c.split.test for f in range(a, b)} for name, c in clips.items()}
    for w in ws:
        assert not test_frames[w.clip] & set(w.frames.tolist()), (w.clip, w.mirrored)
    assert not any(w.clip.startswith("walker_") for w in ws)


def test_test_windows_come_only_from_test_frames(clips):
    ws = windows(list(clips.values()), "test", length=40, history=10)
    assert {w.clip for w in ws} == {n for n, c in clips.items() if c.split.test}
    for w in ws:
        c = clips[w.clip]
        assert all(any(a <= f < b for a, b in c.split.test) for f in w.frames), w.clip


def test_windows_face_plus_z_at_the_last_history_frame(clips):
    from export.ops.facing import facing_angle
    from export.data.skeleton import SKELETON
    for w in windows(list(clips.values()), "train", length=20, history=10, stride=7, mirror=True)[::5]:
        assert abs(facing_angle(w.positions[9], SKELETON)) < 1e-9


def test_split_file_lists_every_served_clip_and_its_role(default_clips):
    index = load_json(CLIPS_DIR / "index.json", "clip-index")
    listed = {c["name"]: c for c in index["clips"]}
    shown = {c.name: c for c in served(list(default_clips.values()))}
    assert set(listed) == set(shown)
    for name, c in shown.items():
        assert listed[name]["role"] == c.split.role and listed[name].get("subject") == c.subject
        assert [tuple(r) for r in listed[name]["test"]] == c.split.test
