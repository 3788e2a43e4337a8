"""The evaluation variants of issue 18, item 6, and issue 19's bone projection: the max-error keypose rule
(an option of ops/keyposes.extract whose default stays the paper's mean rule), the predictor that uses it
only inside the evaluation, and the projection onto the history's bone lengths."""
import inspect

import numpy as np
import pytest

from export.data.skeleton import SKELETON
from export.ops import keyposes as kp
from export.ops.bones import bone_lengths
from export.sample import keyposes as served
from export.eval.variants import extraction_rule, keypose_counts, project_onto_history


def bump() -> np.ndarray:
    """One joint moving along x: 0 for 10 frames, a 1-frame spike of 1.0 m at frame 5, then a ramp of 0.2 m
    per frame for 10 frames. Whole-pose errors are the joint's x distance from the chord."""
    x = np.zeros(21)
    x[5] = 1.0
    x[11:] = 0.2 * np.arange(1, 11)
    out = np.zeros((21, 1, 3))
    out[:, 0, 0] = x
    return out


def test_the_default_is_the_papers_mean_rule_and_the_signature_keeps_it():
    assert inspect.signature(kp.extract).parameters["rule"].default == "mean"
    m = bump()
    assert kp.extract(m, 0.3) == kp.extract(m, 0.3, rule="mean")


def test_the_max_rule_splits_until_no_frame_is_off_by_the_threshold():
    m = bump()
    mean_keys, max_keys = kp.extract(m, 0.3), kp.extract(m, 0.3, rule="max")
    assert set(mean_keys) <= set(max_keys) and len(max_keys) > len(mean_keys)
    for a, b in zip(max_keys, max_keys[1:]):                   # every segment's largest error is below 0.3
        if b - a >= 2:
            assert kp.frame_errors(m, a, b)[1:-1].max() < 0.3
    with pytest.raises(ValueError, match="rule must be one of"):
        kp.extract(m, 0.3, rule="median")


def test_the_rule_is_swapped_only_inside_the_evaluation_block():
    before = served.kp
    m = bump()
    with extraction_rule("max"):
        assert served.kp is not before
        assert served.kp.extract(m, 0.3) == kp.extract(m, 0.3, rule="max")
        assert served.kp.nearest_centre is kp.nearest_centre
    assert served.kp is before
    with extraction_rule("mean"):
        assert served.kp is before


def test_keypose_counts_under_both_rules():
    m = np.repeat(bump(), SKELETON.num_joints, axis=1)
    got = keypose_counts([m], threshold=0.3)
    assert got["max"] >= got["mean"] >= 2


def test_projection_sets_the_histories_bone_lengths_and_keeps_directions():
    rng = np.random.default_rng(0)
    history = rng.normal(size=(5, SKELETON.num_joints, 3))
    futures = rng.normal(size=(2, 4, SKELETON.num_joints, 3))
    out = project_onto_history(futures, history)
    assert bone_lengths(out) == pytest.approx(np.broadcast_to(bone_lengths(history).mean(0), (2, 4, len(SKELETON.bones))))
    assert out[..., 0, :] == pytest.approx(futures[..., 0, :])        # the root stays where it is
