"""Fixed-length windows (history + future) cut from the split, canonicalised at the last history frame
(root-relative poses and the root channel, export/ops/facing.py).

Training windows come only from train ranges; a looping train-only clip may be cut from its
blended repeat, so windows wrap around the loop. Test windows come only from test ranges
(test-only loops may also be repeated). Every window keeps the source frame index of each of
its frames, so tests can prove that no training window touches a test frame.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..ops.facing import canonicalise
from ..ops.mirror import mirror_positions
from .balance import example_weights
from .clip import Clip
from .skeleton import SKELETON


@dataclass
class Window:
    clip: str
    action: str
    positions: np.ndarray      # [T, J, 3] canonical: facing +z, root channel at 0, at frame history-1
    frames: np.ndarray         # [T] frame index in the source clip
    mirrored: bool = False
    subject: object = None     # the clip's person (data/balance.py weighs people within an action)


def _repeatable(clip: Clip, part: str) -> bool:
    if clip.repeat is None or not clip.loops:
        return False
    # Only whole-clip parts may wrap: a clip with a test tail is never repeated.
    ranges = clip.split.train if part == "train" else clip.split.test
    return ranges == [(0, len(clip))]


def windows(clips: list[Clip], part: str, length: int, history: int, stride: int = 1,
            mirror: bool = False, wrap: bool = True) -> list[Window]:
    """All windows of `length` frames from the `part` ("train" or "test") of each clip."""
    if part not in ("train", "test"):
        raise ValueError(f"part must be 'train' or 'test', got {part!r}")
    if not 0 < history < length:
        raise ValueError("history must be between 1 and the window length")
    cut: list[tuple[Clip, np.ndarray, np.ndarray]] = []       # (clip, world positions, source frames)
    for clip in clips:
        if wrap and _repeatable(clip, part):
            m = len(clip)
            cycles = int(np.ceil((m + length) / m)) + 1
            seq = clip.repeat(cycles)
            for start in range(0, m, stride):
                idx = np.arange(start, start + length)
                cut.append((clip, seq[idx], idx % m))
            continue
        ranges = clip.split.train if part == "train" else clip.split.test
        for a, b in ranges:
            for start in range(a, b - length + 1, stride):
                idx = np.arange(start, start + length)
                cut.append((clip, clip.positions[idx], idx))
    out = [Window(c.name, c.action, canonicalise(p, history - 1, c.skeleton)[0], idx, False, c.subject)
           for c, p, idx in cut]
    if mirror:
        # Mirror first, then face +z again: the mirror plane is the body's own sagittal plane.
        out += [Window(c.name, c.action, canonicalise(mirror_positions(p, SKELETON), history - 1, SKELETON)[0],
                       idx, True, c.subject) for c, p, idx in cut]
    return out


def window_weights(ws: list[Window]) -> np.ndarray:
    """Sampling weights of training windows by the balance rule (data/balance.py)."""
    return example_weights([w.action for w in ws], [w.subject for w in ws])
