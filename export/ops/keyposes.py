"""Keyposes (Keyposes paper, section 3.1): the poses between which linear interpolation
reconstructs a motion, their cluster labels, pruning, and the duration classes (3.2.1).

TypeScript twin: web/src/sampling/keyposes.ts; contract/vectors/keyposes.json ties them.
"""
from __future__ import annotations

import numpy as np

# Error of a frame = the L2 norm of the whole pose difference (all joints, 3J numbers), metres,
# as the paper's "L2 error between P and P-hat". A segment stops splitting once the mean error of
# its interior frames is below the threshold. 0.3 m on 18 joints is a root-mean-square joint
# error of 0.3 / sqrt(18) = 7 cm, between the paper's H3.6M setting (500 mm over 32 joints,
# 8.8 cm) and its CMU setting (250 mm over 38 joints, 4 cm). Measured on the 15 DeepMimic clips at
# 30 Hz: 171 keyposes, 4 to 25 per clip, 6.3 frames apart.
THRESHOLD = 0.3

# Duration classes (section 3.2.1) scaled from the paper's 25 Hz to our 30 Hz (x 1.2, rounded):
# half-open frame intervals [bounds[c], bounds[c+1]) and the length each class stands for
# (paper: 3, 6, 12, 16, 25 frames -> 4, 7, 14, 19, 30).
DURATION_BOUNDS = (1, 5, 12, 17, 30)
DURATION_LENGTHS = (4, 7, 14, 19, 30)


def frame_errors(positions: np.ndarray, a: int, b: int) -> np.ndarray:
    """Error of every frame in [a, b] against the linear interpolation of frames a and b."""
    p = np.asarray(positions, dtype=np.float64)
    w = ((np.arange(a, b + 1) - a) / (b - a))[:, None, None]
    rec = p[a] * (1.0 - w) + p[b] * w
    d = p[a:b + 1] - rec
    return np.sqrt((d * d).reshape(len(d), -1).sum(-1))


# How a segment decides it needs no further keypose: "mean" (the paper's text, what every model here is
# trained and served with) or "max" (the authors' released code; an evaluation variant only, issue 18).
RULES = ("mean", "max")


def extract(positions: np.ndarray, threshold: float = THRESHOLD, rule: str = "mean") -> list[int]:
    """Keypose frame indices of a motion [F, J, 3]: first and last frame, then recursively the frame
    of largest error inside each segment until the segment's mean interior error is below threshold
    (rule="max": until its largest interior error is, which finds more keyposes).

    Ties go to the earliest frame (both languages). A motion of one frame has one keypose.
    """
    positions = np.asarray(positions, dtype=np.float64)
    if positions.ndim != 3 or positions.shape[-1] != 3:
        raise ValueError(f"positions must be [frames, joints, 3], got shape {list(positions.shape)}")
    if not threshold > 0:
        raise ValueError(f"the keypose threshold must be positive, got {threshold}")
    if rule not in RULES:
        raise ValueError(f"the keypose rule must be one of {RULES}, got {rule!r}")
    stop = np.mean if rule == "mean" else np.max
    n = len(positions)
    if n < 2:
        return list(range(n))
    keys = {0, n - 1}
    stack = [(0, n - 1)]
    while stack:
        a, b = stack.pop()
        if b - a < 2:
            continue
        inner = frame_errors(positions, a, b)[1:-1]
        if stop(inner) < threshold:
            continue
        m = a + 1 + int(np.argmax(inner))
        keys.add(m)
        stack += [(a, m), (m, b)]
    return sorted(keys)


def nearest_centre(values: np.ndarray, centres: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """k-means' own rule: the label of each pose [n, J, 3] is the centre [K, J, 3] at the smallest
    L2 distance. Returns labels [n] and each one's margin (second-smallest minus smallest distance)."""
    v = np.asarray(values, dtype=np.float64).reshape(len(values), -1)
    c = np.asarray(centres, dtype=np.float64).reshape(len(centres), -1)
    d = np.sqrt(((v[:, None, :] - c[None, :, :]) ** 2).sum(-1))
    labels = np.argmin(d, axis=1)
    part = np.sort(d, axis=1)
    margins = part[:, 1] - part[:, 0] if d.shape[1] > 1 else np.full(len(d), np.inf)
    return labels, margins


def prune(labels: list[int] | np.ndarray) -> list[int]:
    """Indices of the keyposes to keep: drop each intermediate keypose whose label equals both its
    predecessor's and its successor's (section 3.2). A run of one label keeps its first and last
    keypose, so a held pose keeps its duration; the first and last keyposes are always kept."""
    labels = list(labels)
    return [i for i in range(len(labels))
            if i == 0 or i == len(labels) - 1 or not (labels[i - 1] == labels[i] == labels[i + 1])]


def bound_gaps(frames: list[int], longest: int) -> list[int]:
    """Keypose frames with a frame added every `longest` frames wherever two are more than `longest`
    apart (the remainder last), so no gap exceeds the longest duration class and each added step is
    played at its own length (a labelled variant of section 3.2's pruning, `split_holds`; training only:
    the predictors' durations are the classes' lengths, never longer)."""
    if longest < 1:
        raise ValueError(f"the longest gap must be at least 1 frame, got {longest}")
    out = list(frames[:1])
    for a, b in zip(frames, frames[1:]):
        out += list(range(a + longest, b, longest)) + [b]
    return out


def duration_class(frames: int, bounds: tuple[int, ...] = DURATION_BOUNDS) -> int:
    """The class whose half-open interval holds `frames` (the last class is open above)."""
    if frames < bounds[0]:
        raise ValueError(f"a keypose duration must be at least {bounds[0]} frame, got {frames}")
    return int(np.searchsorted(np.asarray(bounds), frames, side="right") - 1)
