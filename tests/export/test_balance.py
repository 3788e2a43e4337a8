"""The balance rule (export/data/balance.py): people capped within an action, actions capped overall."""
import numpy as np
import pytest

from export.data import balance
from export.data.balance import ACTION_CAP, PERSON_CAP, capped_shares, example_weights, shares
from export.train.loop import batch_indices


def test_water_filling_by_hand():
    # 60 / 30 / 10 capped at 1/2: the first is set to 0.5, the other 0.5 split 3:1
    got = capped_shares({"a": 60, "b": 30, "c": 10}, 0.5)
    assert got == pytest.approx({"a": 0.5, "b": 0.375, "c": 0.125})
    # the excess can push a second one over: 80 / 15 / 5 at 0.4 -> 0.4, then 15:5 of 0.6 = 0.45 > 0.4 -> 0.4, 0.2
    assert capped_shares({"a": 80, "b": 15, "c": 5}, 0.4) == pytest.approx({"a": 0.4, "b": 0.4, "c": 0.2})
    # nothing above the cap: the natural shares
    assert capped_shares({"a": 1, "b": 1, "c": 2}, 0.5) == pytest.approx({"a": 0.25, "b": 0.25, "c": 0.5})
    with pytest.raises(ValueError, match="cannot all stay"):
        capped_shares({"a": 1, "b": 1}, 1 / 3)


def test_example_weights_cap_people_within_an_action_and_actions_overall():
    # walk: person 1 has 80 windows, 2 and 3 have 10 each; run: two people 5 / 5; jump, kick, spin: 5 each
    actions = ["walk"] * 100 + ["run"] * 10 + ["jump"] * 5 + ["kick"] * 5 + ["spin"] * 5
    people = [1] * 80 + [2] * 10 + [3] * 10 + [4] * 5 + [5] * 5 + [6] * 5 + [7] * 5 + [8] * 5
    w = example_weights(actions, people)
    assert w.mean() == pytest.approx(1.0)
    got = shares(w, actions, people)
    # walk has 100 of 125 windows: capped at 1/4; the other 3/4 go to run : jump : kick : spin = 10 : 5 : 5 : 5,
    # which puts run at 0.3, above the cap too: run 1/4, and the last 1/2 split equally over three
    assert got["actions"] == pytest.approx({"walk": 0.25, "run": 0.25, "jump": 1 / 6, "kick": 1 / 6, "spin": 1 / 6})
    # walk has three people: each exactly a third; run has two: natural shares
    assert got["people"]["walk"] == pytest.approx({"1": 1 / 3, "2": 1 / 3, "3": 1 / 3})
    assert got["people"]["run"] == pytest.approx({"4": 0.5, "5": 0.5})
    # within an (action, person) every example weighs the same
    assert np.ptp(w[:80]) == pytest.approx(0) and np.ptp(w[80:90]) == pytest.approx(0)


def test_an_action_with_two_people_keeps_their_natural_shares():
    actions = ["dance"] * 12 + ["walk"] * 4 + ["jump"] * 4 + ["kick"] * 4
    people = [60] * 9 + [5] * 3 + [1] * 4 + [2] * 4 + [3] * 4
    got = shares(example_weights(actions, people), actions, people)
    assert got["people"]["dance"] == pytest.approx({"60": 0.75, "5": 0.25})


def test_weighted_batches_follow_the_weights():
    w = np.array([3.0, 1.0, 0.0, 0.0])
    plan = batch_indices(4, 1000, 20, seed=0, weights=w)
    assert plan.shape == (20, 1000) and set(np.unique(plan)) == {0, 1}
    assert (plan == 0).mean() == pytest.approx(0.75, abs=0.01)
    assert np.array_equal(plan, batch_indices(4, 1000, 20, seed=0, weights=w))     # seeded
    with pytest.raises(ValueError, match="sampling weights"):
        batch_indices(4, 8, 2, seed=0, weights=np.ones(3))


def check_caps(weights, actions, people):
    """The issue's rule on the realised draws: with three or more training people no person supplies more
    than a third of an action's draws, and no action more than a quarter of all draws."""
    got = shares(weights, actions, people)
    for action, by_person in got["people"].items():
        if len(by_person) >= balance.MIN_PEOPLE:
            assert max(by_person.values()) <= PERSON_CAP + 1e-9, (action, by_person)
    assert max(got["actions"].values()) <= ACTION_CAP + 1e-9, got["actions"]
    return got


def test_the_default_training_windows_and_wat_pairs_keep_the_caps(default_clips):
    from export.data.windows import window_weights, windows
    from export.methods.wat import WatMethod
    from export.config import load_config, override
    clips = list(default_clips.values())
    ws = windows(clips, "train", 40, 10, stride=3, mirror=True)
    got = check_caps(window_weights(ws), [w.action for w in ws], [w.subject for w in ws])
    # the dominant ones really are capped: subject 105 walks most, salsa partner 60 dances most
    assert got["people"]["walk"]["105"] == pytest.approx(PERSON_CAP)
    assert got["actions"]["walk"] == pytest.approx(ACTION_CAP) and got["actions"]["dance"] == pytest.approx(ACTION_CAP)
    # WAT draws pairs by their instance's action and person: the same caps hold on its bank
    few = [c for c in clips if c.split.role == "train"][::6]
    method = WatMethod(override(load_config("wat_rnn.json"), **{"transitions.cross_per_history": 1}))
    data = method.prepare(few)
    bank_actions = [method.actions[a] for a in method.bank["action"][data.tensors["instance"]].numpy()]
    check_caps(data.weights, bank_actions, method.pair_people)
