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
