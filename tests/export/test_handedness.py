"""Handedness (issue 30, export/ops/handedness.py): every window of the served clips is a real body,
its reflection (labels kept) is not, and swapping left and right labels fixes the reflection."""
import json

import numpy as np

from export.data.clip_json import read_clip
from export.data.skeleton import SKELETON
from export.ops.handedness import handedness, swap_left_right
from export.ops.mirror import mirror_positions
from export.paths import CLIPS_DIR

INDEX = json.loads((CLIPS_DIR / "index.json").read_text())
CLIPS = [read_clip(CLIPS_DIR / f"{c['name']}.json").positions for c in INDEX["clips"]]


def windows(frames: int = 30):
    for p in CLIPS:
        for a in range(0, len(p) - frames + 1, frames):
            yield p[a:a + frames]


def test_real_bodies_are_not_reflected_and_their_mirror_images_are():
    count = 0
    for w in windows():
        count += 1
        assert not handedness(w)[0]
        assert not handedness(mirror_positions(w, SKELETON))[0]   # a mirrored motion swaps the labels: still real
        for axis in range(3):                                     # through any plane, labels kept
            flip = np.ones(3)
            flip[axis] = -1.0
            reflected = w * flip
            assert handedness(reflected)[0], axis
            assert not handedness(swap_left_right(reflected))[0], axis
    assert count >= 40


def test_the_score_does_not_change_when_the_body_turns():
    w = next(windows())
    c, s = np.cos(1.1), np.sin(1.1)
    turn = np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])
    assert abs(handedness(w @ turn.T)[1] - handedness(w)[1]) < 1e-9
