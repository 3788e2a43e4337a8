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

# The held-out people (issue 27, item 4), on the served vocabulary (data/vocabulary.py):
# - walk (9 people): 7, 8 and 10 are held out, 5, 6, 12, 16, 35 and 105 trained on. 7 and 8 have
#   skeletons within 2 cm on every bone (SOURCE.md), so they may be one person: both are held out.
# - run (3): 49 (49_04 is the only run longer than 2 s besides two of 16's); 16 and 35 trained on.
# - jump (5): 13 and 49 held out; 1, 16 and 105 trained on (and 14's reach takes are "reach").
# - dance (6): 49 (ballet), 61 (salsa) and 93 (3.4 s of Lindy Hop) held out; 5, 55 and 60 trained on.
#   With three training people the balance rule gives each a third of the dance draws
#   (data/balance.py): 55's 33 s can carry that, 93's 3.4 s could not (it would be drawn 100 times
#   as often as its share). 93's skeleton is within 2 cm of 14's and 35's (trained on), so it may be
#   one of them: only its 3.4 s of dance is then at risk, which is why it is the dancer held out.
# - kick (2): 10's soccer kicks held out, 135's karate kicks trained on.
# - calisthenics (3: 13, 14, and 49's balance take) and reach (13, 14): 13 and 49 held out, 14 trained on.
# - basketball (one person, 6) and the DeepMimic actions: trained on only, never evaluated.
# Seven people are held out; 748 of the 2656 CMU seconds (salsa partner 61 alone is 458 s).
TEST_PEOPLE = frozenset({7, 8, 10, 13, 49, 61, 93})

# Actions whose held-out people need a word when results are printed (different kicks; salsa partners).
HELD_OUT_NOTES = {
    "kick": "soccer kicks (subject 10) are held out; the karate kicks (subject 135) are trained on",
    "dance": "subjects 60 and 61 are the two partners of the same salsa recordings: 61 is held out, 60 is "
             "trained on; a ballet dancer (49) and a social dancer (93, 3.4 s) are held out too",
    "walk": "subjects 7 and 8 may be one person (skeletons within 2 cm on every bone): both are held out",
}
# An action with at least this many people keeps at least two on each side (issue 27, item 4).
TWO_EACH_FROM = 4


def person_rules(test_people=TEST_PEOPLE, notes=HELD_OUT_NOTES) -> list[str]:
    """The person split in words, for the clip index."""
    people = ", ".join(str(p) for p in sorted(test_people, key=lambda p: (type(p).__name__, p)))
    return [
        f"split by person: the takes of subjects {people} are test clips (the whole clip), for every action "
        "they perform; every other take is a train clip (the whole clip)",
        "no person is on both sides, so no training window, mirror or repeat comes from a test person",
        "every action has a train person; an action with a test person is evaluated, one without (a single "
        f"performer) is trained on only; an action with {TWO_EACH_FROM} or more people has two on each side",
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


def person_split_problems(clips: list[Clip], train_only: frozenset = frozenset()) -> list[str]:
    """Why `clips` are not a clean split by person (empty when they are): nobody on both sides, every
    action with a training person, and an action with TWO_EACH_FROM or more people two on each side,
    counting only people who could be held out (not those of a train-only source, `train_only`).
    An action without a test person is allowed: it is trained on and never evaluated (evaluated_actions)."""
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
        people = {role: {c.subject for c in clips if c.action == action and c.split.role == role}
                  for role in ("train", "test")}
        if not people["train"]:
            problems.append(f"{action}: no train person")
        movable = {r: p - set(train_only) for r, p in people.items()}
        if len(movable["train"] | movable["test"]) >= TWO_EACH_FROM and \
                min(len(movable["train"]), len(movable["test"])) < 2:
            problems.append(f"{action}: {len(movable['train'] | movable['test'])} people, but "
                            f"{len(movable['train'])} train and {len(movable['test'])} test (two of each needed)")
    return problems


def evaluated_actions(clips: list[Clip]) -> list[str]:
    """The actions with a held-out person: the only ones evaluated (the others are trained on only)."""
    return sorted({c.action for c in clips if c.split.role == "test"})


def short_horizons(clips: list[Clip], history: int, horizons: list[int]) -> list[tuple[str, int]]:
    """(action, horizon) pairs, horizons in frames, for which no test clip of the action holds
    `history` + horizon frames: evaluation skips them and says so, it never pads a take."""
    out = []
    for action in evaluated_actions(clips):      # the others are never evaluated at any horizon
        longest = max((b - a for c in clips if c.action == action for a, b in c.split.test), default=0)
        out += [(action, h) for h in sorted(horizons) if history + h > longest]
    return out
