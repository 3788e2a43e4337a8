"""The action vocabulary the served models are conditioned on (issue 27, item 3).

CMU's trial index gives 18 fine labels (data/cmu/index.json "action"), 5 of which have a single
performer and 7 only two. A label a model is conditioned on must have a training person, and it can
only be evaluated where it also has a held-out person; a label with one or two people teaches a model
one person's way of doing it. So fine labels that name variants of one action are folded into one
label, which gives each label more people (people per label from data/cmu/SOURCE.md):

| label        | folds (CMU fine labels; DeepMimic clips)                                   | people |
|--------------|-----------------------------------------------------------------------------|--------|
| walk         | walk, walk_slow, walk_brisk_long_stride, walk_turn, walk_styled; DM walk + walkers | 9 + DM |
| run          | run_jog, run_turn; DM run                                                   | 3 + DM |
| jump         | jump_forward, jump_in_place, jump_turn; DM jump                             | 5 + DM |
| dance        | dance_ballet_modern, dance_social, dance_salsa; DM dance_a, dance_b         | 6 + DM |
| kick         | kick (soccer, karate); DM kick                                              | 2 + DM |
| calisthenics | calisthenics, balance (49_18: "balance on one leg, outstretched arms", the   | 3      |
|              | only take of its label: an exercise pose like the calisthenics' stretches)   |        |
| reach        | jump_reach_grab ("jump up to grab, reach for, tiptoe": mostly reaching, so   | 2      |
|              | it is not folded into jump, whose futures must leave the ground)            |        |
| basketball   | basketball (one person: trained on, never evaluated)                        | 1      |

Speed variants (slow, brisk, styled) and turns are folded because the history carries them: a
model that follows the history's speed and heading needs no label for them, and the label then
has 9 people instead of 1-4. Every other DeepMimic action (backflip, cartwheel, crawl, getup_*,
punch, roll, spin, spinkick) keeps its own label: one performer each, train-only, never evaluated.

The report groups the labels into five action groups (walk, run, jump, dance, other), so that no
failure hides in an all-action mean.
"""
from __future__ import annotations

# fine label (CMU index.json "action", or a DeepMimic clip's action) -> served label
FOLD = {
    "walk": "walk", "walk_slow": "walk", "walk_brisk_long_stride": "walk", "walk_turn": "walk",
    "walk_styled": "walk",
    "run_jog": "run", "run_turn": "run", "run": "run",
    "jump_forward": "jump", "jump_in_place": "jump", "jump_turn": "jump", "jump": "jump",
    "dance_ballet_modern": "dance", "dance_social": "dance", "dance_salsa": "dance",
    "dance_a": "dance", "dance_b": "dance",
    "kick": "kick",
    "calisthenics": "calisthenics", "balance": "calisthenics",
    "jump_reach_grab": "reach",
    "basketball": "basketball",
}

GROUPS = ("walk", "run", "jump", "dance", "other")


def label(fine: str) -> str:
    """The served label of a fine label; a label the table does not fold keeps its name."""
    return FOLD.get(fine, fine)


def group(action: str) -> str:
    """The report's action group of a served label (or of a fine label, folded first)."""
    a = label(action)
    return a if a in GROUPS else "other"
