"""Planted feet (export/ops/foot_plant.py): what it keeps, what it changes, and the predictor's switch."""
import json

import numpy as np
from hypothesis import given, settings, strategies as st

from export.data.clip_json import read_clip
from export.data.skeleton import SKELETON
from export.eval.realism.skating import contact_speeds
from export.ops.facing import root_relative, split_root
from export.ops.foot_plant import FOOT_JOINTS, FPS, FULL, NONE, SLIDING, SLOW, contact_weight, plant_feet, speed_weight
from export.paths import CLIPS_DIR
from export.sample.predictor import load_predictor
from export.sample.request import PredictError, Request

FEET = [SKELETON.index(n) for n in FOOT_JOINTS]


def _walk(frames: int = 40) -> np.ndarray:
    index = json.loads((CLIPS_DIR / "index.json").read_text())
    name = sorted(c["name"] for c in index["clips"] if c["action"] == "walk" and c["role"] == "test")[0]
    return read_clip(CLIPS_DIR / f"{name}.json").positions[:frames].astype(np.float64)


def _slide(m: np.ndarray, factor: float) -> np.ndarray:
    out = m[1:].copy()
    out[..., [0, 2]] += ((m[1:, 0, [0, 2]] - m[0, 0, [0, 2]]) * (factor - 1))[:, None]
    return out


@settings(max_examples=25, deadline=None)
@given(st.floats(0.0, 2.5))
def test_heights_and_root_relative_poses_are_kept_whatever_the_root_does(factor):
    m = _walk()
    f = _slide(m, factor)[None]
    out = plant_feet(m[0], f)
    assert np.array_equal(out[..., 1], f[..., 1])
    np.testing.assert_allclose(root_relative(split_root(out)), root_relative(split_root(f)), atol=1e-9)


def test_a_sliding_walk_gets_its_feet_back_on_the_ground():
    m = _walk()
    for factor in (0.4, 1.6, 1.9):
        f = _slide(m, factor)
        before, after = np.median(contact_speeds(f)), np.median(contact_speeds(plant_feet(m[0], f[None])[0]))
        assert before > 0.3 and after < 0.3 * before, (factor, before, after)


def test_a_fully_planted_joint_stands_still_in_the_world():
    m = _walk()
    f = _slide(m, 1.5)[None]
    before = np.concatenate([m[:1], f[0]])
    out = plant_feet(m[0], f)[0]
    seq = np.concatenate([m[:1], out])
    checked = 0
    for j in FEET:
        y = before[:, j, 1]
        for t in range(len(seq) - 1):
            # the only foot joint down at both frames, slow under the method's root: the root's step is
            # exactly its opposite
            others = [i for i in FEET if i != j and min(before[t, i, 1], before[t + 1, i, 1]) < NONE]
            slow = np.linalg.norm(before[t + 1, j, [0, 2]] - before[t, j, [0, 2]]) * FPS <= SLOW
            if y[t] <= FULL and y[t + 1] <= FULL and slow and not others:
                assert np.allclose(seq[t + 1, j, [0, 2]], seq[t, j, [0, 2]], atol=1e-9)
                checked += 1
    assert checked >= 5


def test_a_foot_swinging_low_and_fast_does_not_push_the_body():
    m = _walk()
    f = _slide(m, 1.0)[None].copy()
    swing = FEET[0]
    f[0, :, swing, 1] = 0.0                                   # one ankle kept on the floor ...
    f[0, :, swing, 0] += np.arange(1, len(f[0]) + 1) * (SLIDING + 0.5) / FPS   # ... sweeping forward fast
    out = plant_feet(m[0], f)
    lifted = f.copy()
    lifted[0, :, swing, 1] = 1.0                              # the same sweep in the air
    assert speed_weight(np.array([SLIDING + 0.5]))[0] == 0
    np.testing.assert_allclose(out[..., 0, [0, 2]], plant_feet(m[0], lifted)[..., 0, [0, 2]], atol=1e-12)
    # the body does not travel backwards: its path still goes the walk's way
    travel = out[0, -1, 0, [0, 2]] - m[0, 0, [0, 2]]
    walk = m[-1, 0, [0, 2]] - m[0, 0, [0, 2]]
    assert travel @ walk > 0.5 * walk @ walk


def test_a_body_in_the_air_keeps_the_methods_root():
    m = _walk()
    f = _slide(m, 1.7)
    f[..., 1] += 0.5                    # every joint far above the ramp
    present = m[0].copy()
    present[:, 1] += 0.5
    np.testing.assert_allclose(plant_feet(present, f[None])[0], f, atol=1e-12)
    assert contact_weight(np.array([FULL, NONE]))[0] == 1 and contact_weight(np.array([NONE]))[0] == 0


def test_the_predictor_plants_unless_told_not_to_and_checks_the_switch():
    p = load_predictor("wat-rnn")
    h = _walk(20)[-10:]
    req = dict(k=3, seed=4, actions=["walk"], horizon_frames=45)
    planted = p.predict(h, Request(**req)).futures
    raw = p.predict(h, Request(**req, plant_feet=False)).futures
    assert np.allclose(plant_feet(h[-1], raw), planted, atol=1e-4)
    assert not np.allclose(raw, planted, atol=1e-3)
    assert Request.from_json(Request(**req, plant_feet=False).to_json()).plant_feet is False
    try:
        p.predict(h, Request(**req, plant_feet="yes"))
    except PredictError as e:
        assert "plant_feet must be true or false" in str(e)
    else:
        raise AssertionError("a non-boolean plant_feet was accepted")
