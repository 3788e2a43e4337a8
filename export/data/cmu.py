"""The CMU motion-capture subset in data/cmu/: 67 takes of 12 actions by 15 people, in three file forms.

data/cmu/SOURCE.md says where every file comes from, index.json describes every take (its action,
subject and frame rate come from there, never from a file name: some names carry wrong labels) and
CHECKS.txt lists what was measured, glitches included. Per take:
1. read it with its form's reader, in metres: ASF/AMC (data/asf_amc.py), cgspeed BVH (CMU's 1/0.45
   inch unit) or the Daz-style BVH (centimetres), and drop the T-pose both BVH kinds add as frame 0;
2. trim what is not motion: leading frames whose channels are all zero (07_12's first frame), the
   first 3 frames of the Daz-style takes (a jump of the hands into place), and any frames before a
   jump faster than 10 m/s in the first 0.05 s (08_07 holds still for 6 frames, then jumps);
3. repair isolated spikes (a point that jumps away for at most 3 frames and comes back), by rule;
   both rules look only at the points the joint map reads, the others never reach a clip. (In this
   subset no such point has a spike: CHECKS.txt's "isolated" runs there are single steps just over
   10 m/s inside real fast motion, or jumps of a whole limb or body that do not come back.)
4. retarget with the form's joint map at the index's frame rate (the salsa BVH headers say 120 fps,
   the takes are 60), and split by person (data/split.py).
"""
from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..paths import ROOT
from . import split
from .asf_amc import read_asf, read_amc, joint_positions as asf_positions
from .bvh import joint_positions as bvh_positions, read_bvh
from .clip import Clip, Split
from .retarget import load_map, resolve, retarget
from .sources import FPS, MotionSource

CMU_DIR = ROOT / "data" / "cmu"
LICENSE = "CMU terms: free for research and commercial use; see DATA_NOTICE.md"
SPIKE_SPEED = 10.0      # m/s: faster than a body point moves, outside a kick
SPIKE_FRAMES = 3        # at most this many frames away; longer fast runs are real motion (kicks)
START_SECONDS = 0.05    # a jump this early is the capture settling, not motion


@dataclass(frozen=True)
class Form:
    key: str
    label: str          # for source.dataset
    joint_map: str
    unit: float         # metres per file unit (ASF/AMC: the reader converts)
    tpose: bool         # frame 0 is an added T-pose
    trim: int           # motion frames to drop at the start


FORMS = {
    "ASF/AMC": Form("asf", "ASF/AMC", "cmu-asf", 1.0, False, 0),
    "BVH (cgspeed": Form("cgspeed", "cgspeed BVH", "cmu-bvh", 0.0254 / 0.45, True, 0),
    "BVH (Daz-style": Form("daz", "Daz-style BVH retarget", "daz", 0.01, True, 3),
}


def form_of(entry: dict) -> Form:
    for prefix, form in FORMS.items():
        if entry["format"].startswith(prefix):
            return form
    raise ValueError(f"{CMU_DIR / 'index.json'}: take {entry.get('take')}: unknown format {entry['format']!r}")


@dataclass
class Take:
    entry: dict                     # the take's index.json entry
    form: Form
    names: list[str]
    points: np.ndarray              # [F, N, 3] metres, y up, at entry["fps"]
    trimmed: int = 0                # motion frames dropped at the start
    repaired: list[tuple[str, int, int]] = field(default_factory=list)  # (point, first, last) frame of `points`

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


def read_take(entry: dict, root: Path = CMU_DIR, repair: bool = True) -> Take:
    """One take's points in metres before retargeting, T-pose dropped and glitches trimmed."""
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
    drop = _leading_zero_rows(rows) + form.trim
    # Only the points the joint map reads reach a clip; fingers, thumbs and eyes are not captured
    # (CMU) or not used, and their glitches must not cut a take.
    used = sorted({i for idx in resolve(load_map(form.joint_map), names, str(path)) if idx for i in idx})
    drop += start_jump(points[drop:, used], float(entry["fps"]))
    take = Take(entry, form, names, points[drop:], trimmed=drop)
    if repair:
        fixed, repaired = repair_spikes(take.points[:, used], [names[i] for i in used], take.fps)
        take.points[:, used] = fixed
        take.repaired = repaired
    return take


def start_jump(points: np.ndarray, fps: float, speed: float = SPIKE_SPEED, seconds: float = START_SECONDS) -> int:
    """Frames to drop at the start: those before the last jump faster than `speed` in the first
    `seconds` (08_07 holds its first 6 frames still, then the whole body jumps 9 cm into its walk)."""
    steps = int(round(seconds * fps))
    v = np.linalg.norm(np.diff(points[:steps + 1], axis=0), axis=-1) * fps
    fast = np.flatnonzero((v > speed).any(axis=1))
    return int(fast[-1]) + 1 if len(fast) else 0


def repair_spikes(points: np.ndarray, names: list[str], fps: float, speed: float = SPIKE_SPEED,
                  max_frames: int = SPIKE_FRAMES) -> tuple[np.ndarray, list[tuple[str, int, int]]]:
    """Points that jump away faster than `speed` and come back faster than `speed` within
    `max_frames` frames are a marker glitch: their frames are replaced by the straight line between
    the frames before and after. "Come back" means the way from the frame before to the frame after
    is less than half the way through the spike; real fast motion (a kick) goes somewhere, so it
    never qualifies, and a run faster than `speed` for more than `max_frames` frames is kept as is."""
    out = points.copy()
    step = np.linalg.norm(np.diff(points, axis=0), axis=-1) * fps     # [F-1, N]: step t goes into frame t+1
    fast = step > speed
    repaired = []
    for j in np.flatnonzero(fast.any(axis=0)):
        t = 0
        while t < len(fast):
            if not fast[t, j]:
                t += 1
                continue
            run = np.argmin(np.append(fast[t:, j], False))          # consecutive fast steps from t
            if run > max_frames:
                t += run                                            # sustained: real motion
                continue
            # the jump away is step t; look for the jump back, step t + k, k <= max_frames
            for k in range(1, max_frames + 1):
                a, b = t, t + k + 1                                 # the frames kept on either side
                if b >= len(points) or not fast[t + k, j]:
                    continue
                chord = np.linalg.norm(points[b, j] - points[a, j])
                way = np.linalg.norm(np.diff(points[a:b + 1, j], axis=0), axis=-1).sum()
                if chord < 0.5 * way:
                    w = (np.arange(1, b - a) / (b - a))[:, None]
                    out[a + 1:b, j] = points[a, j] * (1 - w) + points[b, j] * w
                    repaired.append((names[j], a + 1, b - 1))
                    t = b - 1
                    break
            t += 1
    repaired.sort(key=lambda r: (r[1], r[0]))
    return out, repaired


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
        problems = split.person_split_problems(out)
        if problems:
            raise ValueError(f"{self.name}: the split by person fails: {'; '.join(problems)}")
        return out
