"""Fixed-length windows (history + future) cut from the split, canonicalised at the last history frame.

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
from .clip import Clip
from .skeleton import SKELETON


@dataclass
class Window:
    clip: str
    action: str
    positions: np.ndarray      # [T, J, 3], facing +z at frame history-1
    frames: np.ndarray         # [T] frame index in the source clip
    mirrored: bool = False


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
    out: list[Window] = []
    for clip in clips:
        if wrap and _repeatable(clip, part):
            m = len(clip)
            cycles = int(np.ceil((m + length) / m)) + 1
            seq = clip.repeat(cycles)
            for start in range(0, m, stride):
                idx = np.arange(start, start + length)
                out.append(_make(clip, seq[idx], idx % m, history))
            continue
        ranges = clip.split.train if part == "train" else clip.split.test
        for a, b in ranges:
            for start in range(a, b - length + 1, stride):
                idx = np.arange(start, start + length)
                out.append(_make(clip, clip.positions[idx], idx, history))
    if mirror:
        # Mirror first, then face +z again: the mirror plane is the body's own sagittal plane.
        out += [Window(w.clip, w.action, canonicalise(mirror_positions(w.positions, SKELETON), history - 1,
                                                      SKELETON)[0], w.frames, True) for w in out]
    return out


def _make(clip: Clip, positions: np.ndarray, frames: np.ndarray, history: int) -> Window:
    canonical, _ = canonicalise(positions, history - 1, clip.skeleton)
    return Window(clip.name, clip.action, canonical, frames)
