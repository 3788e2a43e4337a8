"""The train/test split, honest for data this small (one take per action, 25-133 frames per clip).

Rules (also written into public/clips/index.json, which every later step reads):
- Clips a source marks test-only (the walker takes) are test clips; they may be loop-repeated.
- A clip whose last 40% is at least MIN_TEST_FRAMES long gives its final
  n - ceil(0.6 n) frames to test and keeps the first ceil(0.6 n) for training. Such a clip is
  never loop-repeated, because a repeat would run the training part into the test tail.
- Every other clip is train-only.
"""
from __future__ import annotations

import math

from .clip import Clip, Split

MIN_TEST_FRAMES = 40
MIN_TRAIN_FRACTION = 0.6

RULES = [
    "walker/ clips (a second take of walking and turning) are test-only; they may be loop-repeated",
    f"a clip of n frames with n - ceil({MIN_TRAIN_FRACTION} n) >= {MIN_TEST_FRAMES} gives that final "
    "part to test and is never loop-repeated",
    "every other clip is train-only; looping train-only clips may be loop-repeated and mirrored",
    "no training window, loop repeat or mirror overlaps a test range",
]


def assign(clip: Clip, test_only: bool) -> Clip:
    n = len(clip)
    if test_only:
        clip.split = Split("test", [], [(0, n)])
        return clip
    train_frames = math.ceil(MIN_TRAIN_FRACTION * n)
    if n - train_frames >= MIN_TEST_FRAMES:
        clip.split = Split("train+test", [(0, train_frames)], [(train_frames, n)])
        clip.repeat = None
    else:
        clip.split = Split("train", [(0, n)], [])
    return clip


# --- The split by person (the CMU subset: several takes by several people per action) ---------------
#
# A person is either in test for every action they perform or in none, so no model has seen a test
# person move. Every test person's takes are whole test clips; every other take is a whole train clip.

# The held-out people: among the sets that give every action a test person and a train person, the one
# that holds out the least motion (254 of 733 s; the example {1, 8, 10, 14, 49, 61, 93} holds
# out 357 s, half the data, because subject 14's calisthenics takes alone are 163 s). Walk has two test
# people (8, 10) and jump_in_place two (13, 49); across all actions six people are held out.
TEST_PEOPLE = frozenset({8, 10, 13, 49, 61, 93})

# Actions whose held-out people need a word when results are printed (different kicks; salsa partners).
HELD_OUT_NOTES = {
    "kick": "soccer kicks (subject 10) are held out; the karate kicks (subject 135) are trained on",
    "dance_salsa": "subjects 60 and 61 are the two partners of the same salsa recordings: "
                   "61 is held out, 60 is trained on",
}


def person_rules(test_people=TEST_PEOPLE, notes=HELD_OUT_NOTES) -> list[str]:
    """The person split in words, for the clip index."""
    people = ", ".join(str(p) for p in sorted(test_people, key=lambda p: (type(p).__name__, p)))
    return [
        f"split by person: the takes of subjects {people} are test clips (the whole clip), for every action "
        "they perform; every other take is a train clip (the whole clip)",
        "no person is on both sides, so no training window, mirror or repeat comes from a test person",
        "every action has at least one test person and one train person",
        "a horizon longer than every test take of an action (history + horizon frames) is listed as an "
        "exception for that action, never padded",
    ] + [f"{action}: {note}" for action, note in sorted(notes.items())]


def assign_person(clip: Clip, test_people=TEST_PEOPLE) -> Clip:
    """Test (the whole clip) when the clip's person is a test person, else train (the whole clip)."""
    if clip.subject is None:
        raise ValueError(f"{clip.name}: no subject, so it cannot be split by person")
    n = len(clip)
    if clip.subject in test_people:
        clip.split = Split("test", [], [(0, n)])
    else:
        clip.split = Split("train", [(0, n)], [])
    return clip


def person_split_problems(clips: list[Clip]) -> list[str]:
    """Why `clips` are not a clean split by person (empty when they are)."""
    problems = []
    sides: dict[object, set[str]] = {}
    for c in clips:
        if c.split.role == "train+test":
            problems.append(f"{c.name}: a clip is either train or test in a split by person")
        sides.setdefault(c.subject, set()).add(c.split.role)
        if c.split.role == "test" and c.split.test != [(0, len(c))]:
            problems.append(f"{c.name}: a test person's clip is test as a whole")
    for person, roles in sorted(sides.items(), key=lambda kv: str(kv[0])):
        if len(roles) > 1:
            problems.append(f"subject {person} is on both sides ({', '.join(sorted(roles))})")
    for action in sorted({c.action for c in clips}):
        roles = {c.split.role for c in clips if c.action == action}
        for role in ("train", "test"):
            if role not in roles:
                problems.append(f"{action}: no {role} person")
    return problems


def short_horizons(clips: list[Clip], history: int, horizons: list[int]) -> list[tuple[str, int]]:
    """(action, horizon) pairs, horizons in frames, for which no test clip of the action holds
    `history` + horizon frames: evaluation skips them and says so, it never pads a take."""
    out = []
    for action in sorted({c.action for c in clips}):
        longest = max((b - a for c in clips if c.action == action for a, b in c.split.test), default=0)
        out += [(action, h) for h in sorted(horizons) if history + h > longest]
    return out
