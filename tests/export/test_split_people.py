"""The split by person (CMU, on the served vocabulary): nobody is on both sides, every evaluated action has a
test and a train person (two of each where it has four or more people), training never sees a test person."""
import numpy as np
import pytest

from export.data import split
from export.data.clip import Clip, Split
from export.data.windows import windows


@pytest.fixture(scope="module")
def clips(default_clips):
    return [c for c in default_clips.values() if c.subject != "deepmimic"]


def test_the_split_is_disjoint_by_person_and_every_evaluated_action_has_a_test_and_a_train_person(clips):
    assert split.person_split_problems(clips) == []
    test = {c.subject for c in clips if c.split.role == "test"}
    train = {c.subject for c in clips if c.split.role == "train"}
    assert test == set(split.TEST_PEOPLE) and not test & train and len(test) >= 6
    assert {c.split.role for c in clips} == {"train", "test"}
    people = {a: {r: {c.subject for c in clips if c.action == a and c.split.role == r} for r in ("train", "test")}
              for a in {c.action for c in clips}}
    # every folded label is evaluated except basketball (one person, trained on only)
    assert split.evaluated_actions(clips) == ["calisthenics", "dance", "jump", "kick", "reach", "run", "walk"]
    assert people["basketball"] == {"train": {6}, "test": set()}
    for action in split.evaluated_actions(clips):
        assert people[action]["train"] and people[action]["test"], action
    for action in ("walk", "jump", "dance"):          # four or more people: two on each side
        assert min(len(people[action]["train"]), len(people[action]["test"])) >= 2, action
    assert people["walk"]["test"] == {7, 8, 10} and people["dance"]["test"] == {49, 61, 93}
    # the salsa partners: one on each side, never both on one
    salsa = {c.subject: c.split.role for c in clips if c.source.get("action_fine") == "dance_salsa"}
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
    assert ("run", 60) in out          # 49_04, the longest test run, is 2.09 s = 63 frames at 30 Hz
    assert ("run", 30) not in out
    assert all(h == 150 or a == "run" for a, h in out), out
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
    assert "kick: no test person" not in problems          # trained on only: allowed, and not evaluated
    assert split.evaluated_actions(made) == ["walk"]
    four = [clip("jump", s, 40, "test" if s == 10 else "train") for s in (10, 11, 12, 13)]
    assert split.person_split_problems(four) == ["jump: 4 people, but 3 train and 1 test (two of each needed)"]
    assert split.person_split_problems([clip("spin", 20, 40, "test")]) == ["spin: no train person"]
    with pytest.raises(ValueError, match="no subject"):
        split.assign_person(Clip("x", "walk", 30.0, np.zeros((40, 18, 3)), False, Split("train", [], [])))


def test_rules_and_notes_are_written_out():
    rules = split.person_rules()
    assert "8, 10, 13, 49, 61, 93" in rules[0]
    assert any(r.startswith("kick: soccer kicks (subject 10) are held out") for r in rules)
    assert split.RULES and callable(split.assign)   # the per-clip split of the default data stays
