"""The split by person (CMU): nobody is on both sides, every action is tested, training never sees a test person."""
import numpy as np
import pytest

from export.data import split
from export.data.clip import Clip, Split
from export.data.cmu import CmuSource
from export.data.windows import windows


@pytest.fixture(scope="module")
def clips():
    return CmuSource().clips()


def test_the_split_is_disjoint_by_person_and_every_action_has_a_test_and_a_train_person(clips):
    assert split.person_split_problems(clips) == []
    test = {c.subject for c in clips if c.split.role == "test"}
    train = {c.subject for c in clips if c.split.role == "train"}
    assert test == set(split.TEST_PEOPLE) and not test & train
    assert {c.split.role for c in clips} == {"train", "test"}
    for action in {c.action for c in clips}:
        people = {c.split.role: c.subject for c in clips if c.action == action}
        assert set(people) == {"train", "test"}, action
    # the salsa partners: one on each side, never both on one
    salsa = {c.subject: c.split.role for c in clips if c.action == "dance_salsa"}
    assert salsa == {60: "train", 61: "test"}


def test_test_people_have_every_take_in_test_as_a_whole_clip(clips):
    for c in clips:
        if c.subject in split.TEST_PEOPLE:
            assert c.split.role == "test" and c.split.test == [(0, len(c))] and c.split.train == [], c.name
        else:
            assert c.split.role == "train" and c.split.train == [(0, len(c))] and c.split.test == [], c.name


def test_no_training_window_comes_from_a_test_person(clips):
    subject = {c.name: c.subject for c in clips}
    ws = windows(clips, "train", length=70, history=10, mirror=True)
    assert len(ws) > 10_000
    assert not {subject[w.clip] for w in ws} & split.TEST_PEOPLE
    assert {subject[w.clip] for w in windows(clips, "test", length=70, history=10)} == set(split.TEST_PEOPLE)


def test_horizons_no_test_take_is_long_enough_for_are_exceptions(clips):
    out = split.short_horizons(clips, history=10, horizons=[30, 60, 150])
    assert ("run_jog", 60) in out          # 49_04, the only test run, is 2.09 s = 63 frames at 30 Hz
    assert ("run_jog", 30) not in out
    assert all(h == 150 or a == "run_jog" for a, h in out), out
    # the rule itself, on made-up clips
    made = [clip("a", 1, 100, "test"), clip("a", 2, 300, "train"), clip("b", 3, 50, "test")]
    assert split.short_horizons(made, history=10, horizons=[40, 90]) == [("b", 90)]


def clip(action, subject, frames, role):
    c = Clip(name=f"{action}_{subject}", action=action, fps=30.0, positions=np.zeros((frames, 18, 3)),
             loops=False, split=Split("train", [], []), subject=subject)
    return split.assign_person(c, {subject} if role == "test" else set())


def test_the_checks_catch_a_person_on_both_sides_and_an_untested_action():
    made = [clip("walk", 1, 40, "test"), clip("walk", 2, 40, "train"), clip("kick", 3, 40, "train")]
    made.append(split.assign_person(Clip("walk_1b", "kick", 30.0, np.zeros((40, 18, 3)), False,
                                         Split("train", [], []), subject=1), set()))
    problems = split.person_split_problems(made)
    assert "subject 1 is on both sides (test, train)" in problems
    assert "kick: no test person" in problems
    with pytest.raises(ValueError, match="no subject"):
        split.assign_person(Clip("x", "walk", 30.0, np.zeros((40, 18, 3)), False, Split("train", [], [])))


def test_rules_and_notes_are_written_out():
    rules = split.person_rules()
    assert "8, 10, 13, 49, 61, 93" in rules[0]
    assert any(r.startswith("kick: soccer kicks (subject 10) are held out") for r in rules)
    assert split.RULES and callable(split.assign)   # the per-clip split of the default data stays
