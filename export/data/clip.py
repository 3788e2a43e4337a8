"""A clip: joint positions on the project skeleton at the project frame rate, with its split."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from .skeleton import SKELETON, Skeleton


@dataclass
class Split:
    role: str                                  # "train", "train+test" or "test"
    train: list[tuple[int, int]]               # half-open frame ranges
    test: list[tuple[int, int]]


@dataclass
class Clip:
    name: str
    action: str
    fps: float
    positions: np.ndarray                      # [F, J, 3] metres, y-up, world frame (root translation kept)
    loops: bool
    split: Split
    source: dict = field(default_factory=dict)
    cycle_frames: int | None = None            # a looping clip stores exactly one cycle
    skeleton: Skeleton = SKELETON
    subject: int | str | None = None           # the person: the split keeps each on one side
    take: str | None = None                    # the source's name of the take (CMU "05_02")
    # Rotation-space repeat with blended seams (ops/loop.py); None when only positions exist.
    repeat: Callable[[int], np.ndarray] | None = field(default=None, repr=False, compare=False)

    def __len__(self) -> int:
        return len(self.positions)

    def part(self, which: str) -> list[np.ndarray]:
        """The clip's train or test parts as position arrays."""
        ranges = self.split.train if which == "train" else self.split.test
        return [self.positions[a:b] for a, b in ranges]
