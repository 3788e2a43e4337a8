"""The CMU motion-capture subset in data/cmu/ (version 2): 242 takes of 18 actions by 18 people, in four file forms.

data/cmu/SOURCE.md says where every file comes from, index.json describes every take (its action,
subject and frame rate come from there, never from a file name: some names carry wrong labels) and
CHECKS.txt lists what was measured, glitches included. Per take:
1. read it with its form's reader, in metres: ASF/AMC (data/asf_amc.py), cgspeed BVH (CMU's 1/0.45
   inch unit), the BVH converted from ASF/AMC (16_01: ASF names and units, no T-pose frame, its own
   joint map cmu-asf-bvh) or the Daz-style BVH (centimetres); drop the T-pose the cgspeed and Daz
   BVH add as frame 0. The frame rate is the index's `fps`, never a BVH header's: the salsa
   headers say 120 fps for 60 fps takes, 16_01's says 30 for a 120 fps take.
2. clean it by one rule (`clean`), on the points the joint map reads only (fingers, thumbs, toe
   ends and eyes are not captured or not used, and their glitches must not cut a take). Speeds
   are a point's step between frames x fps, in m/s:
   - zero: leading frames whose channels are all zero are dropped (07_12's first frame);
   - start: the frames before the last step faster than SPIKE_SPEED = 10 m/s within the first
     START_SECONDS = 0.05 s are dropped: the capture settling, with no good frame before it to
     interpolate from (the Daz-style hands jumping into place in frames 1-3, 16_15/16_23/16_28's
     hand jumping ~100 m/s in frames 2-7, 08_07's body jumping 9 cm after 6 still frames);
   - spike: a point that jumps away faster than 10 m/s and jumps back faster than 10 m/s at most
     SPIKE_FRAMES = 3 frames later is a glitch (mostly wrist, hand or toe flips); its frames are
     replaced by the straight line between the frames before and after;
   - impossible: a step faster than IMPOSSIBLE_SPEED = 25 m/s is a glitch whatever its length (no
     body point moves that fast; a kicking foot reaches ~19 m/s): the shortest window of at most
     GLITCH_SECONDS = 0.25 s around it across which the point comes back is replaced by the straight
     line (subject 5's knee and toe flips of 30-50 m/s, the salsa foot flips of 1-8 frames);
   - cut: an impossible step with no such window is a jump to another state that never comes back;
     the take is cut at it and the longer side is kept (subject 5's dances only);
   - "comes back" means the straight line from the frame before to the frame after is shorter
     than RETURN_SHARE = half the way the point travels through the glitch and is itself no faster
     than 10 m/s. Everything else is motion and kept: runs faster than 10 m/s for more than
     3 frames under 25 m/s (kicks), and single fast steps that go somewhere (a step just over
     10 m/s inside fast motion; 16_01's wrist moves 11 cm in one frame, at 13.6 m/s, and stays).
   Applied at 30 Hz to the final clips, the same rule finds nothing (tests/export/test_cleaning.py).
3. retarget with the form's joint map at the index's frame rate; the split by person is assigned
   by data/split.py.
"""
from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path
from typing import NamedTuple

import numpy as np

from ..paths import ROOT
from . import split
from .asf_amc import read_asf, read_amc, joint_positions as asf_positions
from .bvh import joint_positions as bvh_positions, read_bvh
from .clip import Clip, Split
from .retarget import load_map, resolve, retarget
from .sources import FPS, MotionSource

CMU_DIR = ROOT / "data" / "cmu"
LICENSE = "CMU terms: free for research and commercial use, not for resale; see DATA_NOTICE.md"
SPIKE_SPEED = 10.0        # m/s: a step this fast starts a glitch if the point comes back
SPIKE_FRAMES = 3          # a point away for at most this many frames, both jumps fast, is a spike
IMPOSSIBLE_SPEED = 25.0   # m/s: no body point moves this fast (a kicking foot reaches ~19)
GLITCH_SECONDS = 0.25     # the longest an impossible jump may stay away and be interpolated
RETURN_SHARE = 0.5        # comes back: the straight line is under this share of the way through
START_SECONDS = 0.05      # a fast step this early is the capture settling, not motion
UNIT = 0.0254 / 0.45      # CMU's ASF "length 0.45": one unit is 1/0.45 inch


@dataclass(frozen=True)
class Form:
    key: str
    label: str          # for source.dataset
    joint_map: str
    unit: float         # metres per file unit (ASF/AMC: the reader converts)
    tpose: bool         # frame 0 is an added T-pose


FORMS = {
    "ASF/AMC": Form("asf", "ASF/AMC", "cmu-asf", 1.0, False),
    "BVH (cgspeed": Form("cgspeed", "cgspeed BVH", "cmu-bvh", UNIT, True),
    "BVH (converted from the ASF/AMC": Form("converted", "BVH converted from ASF/AMC", "cmu-asf-bvh", UNIT, False),
    "BVH (Daz-style": Form("daz", "Daz-style BVH retarget", "daz", 0.01, True),
}


def form_of(entry: dict) -> Form:
    for prefix, form in FORMS.items():
        if entry["format"].startswith(prefix):
            return form
    raise ValueError(f"{CMU_DIR / 'index.json'}: take {entry.get('take')}: unknown format {entry['format']!r}")


@dataclass(frozen=True)
class Glitch:
    point: str
    first: int          # the first frame replaced; for a cut, the first frame after the jump
    last: int           # the last frame replaced (first - 1 for a cut)
    speed: float        # its fastest step, m/s
    kind: str           # "spike", "impossible" or "cut"


@dataclass
class Take:
    entry: dict                     # the take's index.json entry
    form: Form
    names: list[str]
    points: np.ndarray              # [F, N, 3] metres, y up, at entry["fps"]
    trimmed: int = 0                # motion frames dropped at the start
    dropped: int = 0                # motion frames dropped at the end (a cut)
    repaired: list[Glitch] = field(default_factory=list)   # frames are those of `points`
    cuts: list[Glitch] = field(default_factory=list)        # frames are the file's motion frames

    @property
    def fps(self) -> float:
        return float(self.entry["fps"])


def load_index(root: Path = CMU_DIR) -> list[dict]:
    path = Path(root) / "index.json"
    try:
        entries = json.loads(path.read_text())
    except (OSError, json.JSONDecodeError) as e:
        raise ValueError(f"{path}: not readable JSON ({e})") from e
    need = ("file", "format", "subject", "take", "action", "fps", "frames")
    for i, e in enumerate(entries):
        missing = [k for k in need if k not in e]
        if missing:
            raise ValueError(f"{path}: entry {i}: no {', '.join(missing)}")
    return entries


def _leading_zero_rows(rows: np.ndarray) -> int:
    """How many rows at the start are all zero (a frame the capture never filled)."""
    nonzero = np.flatnonzero(np.any(rows != 0, axis=1))
    return int(nonzero[0]) if len(nonzero) else len(rows)


def read_raw(entry: dict, root: Path = CMU_DIR) -> tuple[Form, list[str], np.ndarray, np.ndarray]:
    """(form, point names, points [F, N, 3] in metres, channel rows [F, C]) of a take's motion frames."""
    root = Path(root)
    form = form_of(entry)
    path = root / entry["file"]
    if form.key == "asf":
        asf = read_asf(root / entry["asf"])
        amc = read_amc(path, asf)
        names = asf.names
        rows = np.concatenate([amc.values[k] for k in sorted(amc.values)], axis=1)
        points = asf_positions(asf, amc)
    else:
        bvh = read_bvh(path)
        names = bvh.names
        rows = bvh.motion[1:] if form.tpose else bvh.motion
        points = bvh_positions(bvh)[1 if form.tpose else 0:] * form.unit
    if len(points) != entry["frames"]:
        raise ValueError(f"{path}: {len(points)} motion frames, but {root / 'index.json'} says {entry['frames']}")
    return form, names, points, rows


def used_points(form: Form, names: list[str], where: str = "") -> list[int]:
    """The points the form's joint map reads: the only ones that reach a clip."""
    return sorted({i for idx in resolve(load_map(form.joint_map), names, where) if idx for i in idx})


def read_take(entry: dict, root: Path = CMU_DIR, repair: bool = True) -> Take:
    """One take's points in metres before retargeting, T-pose and leading zero frames dropped, and
    cleaned by rule (`clean`) unless `repair` is False."""
    form, names, points, rows = read_raw(entry, root)
    used = used_points(form, names, str(Path(root) / entry["file"]))
    zero = _leading_zero_rows(rows)
    if not repair:
        return Take(entry, form, names, points[zero:], trimmed=zero)
    c = clean(points[zero:, used], [names[i] for i in used], float(entry["fps"]))
    out = points[zero + c.first:zero + c.stop].copy()
    out[:, used] = c.points
    return Take(entry, form, names, out, trimmed=zero + c.first, dropped=len(points) - zero - c.stop,
                repaired=c.repaired, cuts=[Glitch(g.point, g.first + zero, g.last + zero, g.speed, g.kind)
                                           for g in c.cuts])


def start_jump(points: np.ndarray, fps: float, speed: float = SPIKE_SPEED, seconds: float = START_SECONDS) -> int:
    """Frames to drop at the start: those before the last step faster than `speed` in the first
    `seconds` (08_07 holds its first 6 frames still, then the whole body jumps 9 cm into its walk)."""
    steps = int(round(seconds * fps))
    v = np.linalg.norm(np.diff(points[:steps + 1], axis=0), axis=-1) * fps
    fast = np.flatnonzero((v > speed).any(axis=1))
    return int(fast[-1]) + 1 if len(fast) else 0


def _comes_back(p: np.ndarray, a: int, b: int, fps: float) -> bool:
    """Whether the straight line from frame a to frame b can stand for the frames between (module docstring)."""
    chord = float(np.linalg.norm(p[b] - p[a]))
    way = float(np.linalg.norm(np.diff(p[a:b + 1], axis=0), axis=-1).sum())
    return chord < RETURN_SHARE * way and chord * fps <= SPIKE_SPEED * (b - a)


def _window(p: np.ndarray, v: np.ndarray, s: int, fps: float) -> tuple[int, int, str] | None:
    """The frames (a, b) kept on either side of the glitch that starts with the fast step s, or None."""
    for b in range(s + 2, min(s + SPIKE_FRAMES + 2, len(p))):      # spike: s away, b - 1 back
        if v[b - 1] > SPIKE_SPEED and _comes_back(p, s, b, fps):
            return s, b, "spike"
    if v[s] > IMPOSSIBLE_SPEED:
        for length in range(2, max(2, int(round(GLITCH_SECONDS * fps))) + 1):   # shortest first
            for a in range(max(0, s - length + 1), min(s, len(p) - 1 - length) + 1):
                if _comes_back(p, a, a + length, fps):
                    return a, a + length, "impossible"
    return None


def repair_point(p: np.ndarray, fps: float) -> tuple[np.ndarray, list[tuple[int, int, float, str]]]:
    """One point's track [F, 3] with its spikes and impossible glitches replaced by straight lines,
    earliest first (a repair changes what the next one sees), and (first, last, speed, kind) of each
    glitch; an impossible step that never comes back is listed as (s + 1, s, speed, "cut")."""
    p = p.copy()
    v = np.linalg.norm(np.diff(p, axis=0), axis=-1) * fps      # v[t]: the step from frame t to t + 1
    found = []
    s = 0
    while True:
        ahead = np.flatnonzero(v[s:] > SPIKE_SPEED)
        if not len(ahead):
            return p, found
        s += int(ahead[0])
        w = _window(p, v, s, fps)
        if w is None:
            if v[s] > IMPOSSIBLE_SPEED:
                found.append((s + 1, s, float(v[s]), "cut"))
            s += 1
            continue
        a, b, kind = w
        found.append((a + 1, b - 1, float(v[a:b].max()), kind))
        t = (np.arange(1, b - a) / (b - a))[:, None]
        p[a + 1:b] = p[a] * (1 - t) + p[b] * t
        v[a:b] = np.linalg.norm(p[b] - p[a]) * fps / (b - a)
        s = b


def repair_glitches(points: np.ndarray, names: list[str], fps: float) -> tuple[np.ndarray, list[Glitch]]:
    """Points [F, N, 3] with every point's spikes and impossible glitches repaired (`repair_point`),
    and the glitches, cuts included, in frame order."""
    out = points.copy()
    glitches = []
    for j in np.flatnonzero((np.linalg.norm(np.diff(points, axis=0), axis=-1) * fps > SPIKE_SPEED).any(axis=0)):
        out[:, j], found = repair_point(points[:, j], fps)
        glitches += [Glitch(names[j], *g) for g in found]
    glitches.sort(key=lambda g: (g.first, g.point))
    return out, glitches


def find_glitches(points: np.ndarray, names: list[str], fps: float) -> list[Glitch]:
    """What the rule would repair or cut in these points (empty for clean motion)."""
    return repair_glitches(points, names, fps)[1]


class Cleaned(NamedTuple):
    points: np.ndarray          # the cleaned points[first:stop]
    first: int                  # frames dropped at the start (start transient, or the short side of a cut)
    stop: int
    repaired: list[Glitch]      # frames counted from `first`
    cuts: list[Glitch]          # frames counted as in the input


def clean(points: np.ndarray, names: list[str], fps: float) -> Cleaned:
    """The rule of the module docstring on points [F, N, 3] (the points a joint map reads)."""
    start = start_jump(points, fps)
    fixed, glitches = repair_glitches(points[start:], names, fps)
    cuts = [g for g in glitches if g.kind == "cut"]
    # Keep the longest stretch between cuts (a cut at frame f separates f - 1 from f).
    edges = [0] + sorted({g.first for g in cuts}) + [len(fixed)]
    lo, hi = max(zip(edges[:-1], edges[1:]), key=lambda e: e[1] - e[0])
    repaired = [Glitch(g.point, max(g.first, lo) - lo, min(g.last, hi - 1) - lo, g.speed, g.kind)
                for g in glitches if g.kind != "cut" and g.last >= lo and g.first < hi]
    return Cleaned(fixed[lo:hi], start + lo, start + hi, repaired,
                   [Glitch(g.point, g.first + start, g.last + start, g.speed, g.kind) for g in cuts])


def clip_from_take(take: Take) -> Clip:
    e, form = take.entry, take.form
    where = f"data/cmu/{e['file']}"
    positions = retarget(take.points, take.names, 1.0 / take.fps, load_map(form.joint_map), where)
    return Clip(
        name=f"cmu_{e['take']}".lower(), action=e["action"], fps=FPS, positions=positions, loops=False,
        split=Split("train", [(0, len(positions))], []),
        source={"dataset": f"CMU Graphics Lab Motion Capture Database ({form.label})",
                "file": f"data/cmu/{e['file']}", "license": LICENSE, "joint_map": form.joint_map},
        subject=int(e["subject"]), take=e["take"],
    )


class CmuSource(MotionSource):
    """The CMU subset, split by person (data/split.py: TEST_PEOPLE)."""

    name = "cmu"

    def __init__(self, root: str | Path = CMU_DIR, test_people=split.TEST_PEOPLE):
        self.root = Path(root)
        self.test_people = frozenset(test_people)

    def takes(self) -> list[dict]:
        return load_index(self.root)

    def split_rules(self) -> list[str]:
        """The split in words, for the clip index (instead of split.RULES)."""
        return split.person_rules(self.test_people)

    def clips(self) -> list[Clip]:
        out = [split.assign_person(clip_from_take(read_take(e, self.root)), self.test_people) for e in self.takes()]
        names = [c.name for c in out]
        dupes = {n for n in names if names.count(n) > 1}
        if dupes:
            raise ValueError(f"{self.name}: clip names must be unique, repeated: {sorted(dupes)}")
        # The split is checked on the served labels, after data/vocabulary.py folds them (default.py).
        return out
