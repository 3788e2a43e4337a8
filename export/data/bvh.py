"""BVH motion capture files: parse the text, then forward kinematics to named joint positions.

Our own parser (tested in tests/export/test_bvh.py) rather than a PyPI library: bvhio 1.5.4 loops
forever on a truncated file (its line reader never sees the end of the file), and the others are
unmaintained or pull in plotting stacks. The grammar is line-based and the same as three.js's
BVHLoader reads in the browser (web/src/motion/bvh.ts checks the same rules first), so a file
either loads in both languages or fails in both with the same message:

    HIERARCHY
    ROOT name / JOINT name / End Site     each on its own line, then "{" on its own line
    OFFSET x y z
    CHANNELS n <n of Xposition Yposition Zposition Xrotation Yrotation Zrotation>   (not in End Site)
    ... children ... "}"
    MOTION
    Frames: n
    Frame Time: seconds
    n lines of one number per channel, in hierarchy order

Semantics: the root's local translation is OFFSET plus its position channels; a non-root joint's
position channels replace its OFFSET on the axes they name (a rig that gives every joint 6 channels
writes the joint's local position there, repeating the OFFSET at rest: adding the two doubles every
bone. three.js's BVHLoader (0.187) does add them, so bvh.ts takes the OFFSET back out). A joint's
local rotation is the product of its rotation channels in the order listed (degrees, about the
joint's own axes), and an End Site is a fixed point named "<joint>/end".
"""
from __future__ import annotations

import re
import warnings
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from scipy.spatial.transform import Rotation

# Limits that keep a hostile or accidental file from exhausting memory (the browser has the same).
MAX_JOINTS = 1000
MAX_DEPTH = 200
MAX_SOURCE_FRAMES = 100_000
MAX_BYTES = 64 * 1024 * 1024

CHANNELS = ("Xposition", "Yposition", "Zposition", "Xrotation", "Yrotation", "Zrotation")
_NUMBER = r"[-+]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][-+]?[0-9]+)?"  # ASCII digits, as in JavaScript
_NUMBER_RE = re.compile(_NUMBER)
_COUNT_RE = re.compile(r"[0-9]+")
# ASCII whitespace only, in both languages, so exotic characters fail the same way in both.
_WS = " \t\f\v"
_SPLIT_RE = re.compile(r"[ \t\f\v\n]+")
_BAD_CHAR_RE = re.compile(r"[^0-9eE+\-. \t\f\v\n]")  # frame data holds nothing else
_SPACE_BYTES = np.frombuffer(b" \t\f\v\n", dtype=np.uint8)


class BvhFormatError(ValueError):
    """The file is not a BVH this project can read; the message names the file, the line and why."""


@dataclass
class Bvh:
    names: list[str]               # joints in file order; End Sites as "<joint>/end"
    parents: list[int]
    offsets: np.ndarray            # [N, 3] in the file's units
    channels: list[list[str]]      # per joint; [] for End Sites
    frame_time: float              # seconds
    motion: np.ndarray             # [F, C] channel values, file order

    @property
    def fps(self) -> float:
        return 1.0 / self.frame_time

    def __len__(self) -> int:
        return len(self.motion)


class _Lines:
    """Non-empty stripped lines with their 1-based line numbers (BVHLoader skips empty lines too)."""

    def __init__(self, text: str, where: str):
        self.items = [(i + 1, s.strip(_WS)) for i, s in enumerate(re.split(r"\r\n|\r|\n", text)) if s.strip(_WS)]
        self.pos = 0
        self.where = where

    def next(self, expecting: str) -> tuple[int, str]:
        if self.pos >= len(self.items):
            raise BvhFormatError(f"{self.where}: the file ends where {expecting} was expected (truncated?)")
        item = self.items[self.pos]
        self.pos += 1
        return item

    def fail(self, line: int, text: str) -> BvhFormatError:
        return BvhFormatError(f"{self.where}: line {line}: {text}")


def _split(s: str) -> list[str]:
    return [t for t in _SPLIT_RE.split(s) if t]


def _number(tok: str) -> float | None:
    return float(tok) if _NUMBER_RE.fullmatch(tok) else None


def _node(lines: _Lines, header: tuple[int, str], depth: int, out: dict, parent: int) -> None:
    n, text = header
    tokens = _split(text)
    end_site = len(tokens) >= 2 and tokens[0].upper() == "END" and tokens[1].upper() == "SITE"
    if end_site:
        if parent < 0:
            raise lines.fail(n, "End Site cannot be the root")
        base = out["names"][parent] + "/end"
        name, k = base, 2
        while name in out["names"]:
            name, k = f"{base}{k}", k + 1
    else:
        kind = tokens[0].upper() if tokens else ""
        if kind not in ("ROOT", "JOINT") or len(tokens) < 2:
            raise lines.fail(n, f'expected "JOINT name", "End Site" or "}}", found "{text[:40]}"')
        if (kind == "ROOT") != (parent < 0):
            raise lines.fail(n, "only the first joint is a ROOT (one skeleton per file)" if parent >= 0
                             else f'the hierarchy must start with "ROOT name", found "{text[:40]}"')
        name = tokens[1]
        if name in out["names"]:
            raise lines.fail(n, f'joint name "{name}" appears twice')
    if depth > MAX_DEPTH or len(out["names"]) >= MAX_JOINTS:
        raise lines.fail(n, f"more than {MAX_JOINTS} joints or {MAX_DEPTH} levels: not a body skeleton")
    index = len(out["names"])
    out["names"].append(name)
    out["parents"].append(parent)

    n, text = lines.next('"{"')
    if text != "{":
        raise lines.fail(n, f'expected "{{" on its own line after "{header[1][:40]}"')
    n, text = lines.next("OFFSET")
    tokens = _split(text)
    values = [_number(t) for t in tokens[1:]]
    if not tokens or tokens[0] != "OFFSET" or len(values) != 3 or None in values:
        raise lines.fail(n, f'expected "OFFSET x y z" (three numbers), found "{text[:40]}"')
    out["offsets"].append(values)
    if end_site:
        out["channels"].append([])
        n, text = lines.next('"}"')
        if text != "}":
            raise lines.fail(n, 'an End Site holds only its OFFSET; expected "}"')
        return
    n, text = lines.next("CHANNELS")
    tokens = _split(text)
    if not tokens or tokens[0] != "CHANNELS" or len(tokens) < 2 or not _COUNT_RE.fullmatch(tokens[1]):
        raise lines.fail(n, f'expected "CHANNELS n names...", found "{text[:40]}"')
    names = tokens[2:]
    if int(tokens[1]) != len(names):
        raise lines.fail(n, f"CHANNELS says {tokens[1]} but lists {len(names)} names")
    bad = [c for c in names if c not in CHANNELS]
    if bad:
        raise lines.fail(n, f'unknown channel "{bad[0]}" (expected {", ".join(CHANNELS)})')
    out["channels"].append(names)
    while True:
        child = lines.next('"}"')
        if child[1] == "}":
            return
        _node(lines, child, depth + 1, out, index)


def parse_bvh(text: str, where: str = "BVH") -> Bvh:
    """Parse BVH text; raises BvhFormatError naming `where`, the line and the problem."""
    if len(text) > MAX_BYTES:
        raise BvhFormatError(f"{where}: {len(text) / 2**20:.0f} MB is larger than this reader takes "
                             f"({MAX_BYTES // 2**20} MB); cut the take shorter")
    lines = _Lines(text.removeprefix("\ufeff"), where)
    if not lines.items or lines.items[0][1] != "HIERARCHY":
        raise BvhFormatError(f'{where}: not a BVH file (it must start with a line "HIERARCHY")')
    lines.pos = 1
    out: dict = {"names": [], "parents": [], "offsets": [], "channels": []}
    _node(lines, lines.next('"ROOT name"'), 0, out, -1)
    n, text = lines.next('"MOTION"')
    if text != "MOTION":
        raise lines.fail(n, f'expected "MOTION" after the hierarchy, found "{text[:40]}"')
    n, text = lines.next('"Frames: n"')
    tokens = _split(text)
    if len(tokens) != 2 or tokens[0] != "Frames:" or not _COUNT_RE.fullmatch(tokens[1]):
        raise lines.fail(n, f'expected "Frames: n", found "{text[:40]}"')
    frames = int(tokens[1])
    if frames > MAX_SOURCE_FRAMES:
        raise lines.fail(n, f"{frames} frames is more than this reader takes ({MAX_SOURCE_FRAMES}); cut the take shorter")
    n, text = lines.next('"Frame Time: seconds"')
    tokens = _split(text)
    frame_time = _number(tokens[2]) if len(tokens) == 3 and tokens[:2] == ["Frame", "Time:"] else None
    if frame_time is None:
        raise lines.fail(n, f'expected "Frame Time: seconds", found "{text[:40]}"')
    if not frame_time > 0:
        raise lines.fail(n, f"Frame Time must be positive, found {frame_time}")
    width = sum(len(c) for c in out["channels"])
    rows = lines.items[lines.pos:]
    if len(rows) != frames:
        raise BvhFormatError(f'{where}: "Frames: {frames}" but the file has {len(rows)} frame lines'
                             + (" (truncated?)" if len(rows) < frames else ""))
    motion = _motion(rows, width, lines)
    return Bvh(names=out["names"], parents=out["parents"], offsets=np.asarray(out["offsets"], dtype=np.float64),
               channels=out["channels"], frame_time=frame_time, motion=motion)


def _motion(rows: list[tuple[int, str]], width: int, lines: _Lines) -> np.ndarray:
    """[rows, width] numbers, checked as strictly as per-token _number() but in bulk (numpy), so a
    100,000-frame take reads in seconds; any doubt falls through to the line-by-line diagnosis."""
    block = "\n".join(s for _, s in rows)
    if not _BAD_CHAR_RE.search(block):
        buf = np.frombuffer(block.encode("ascii"), dtype=np.uint8)
        space = np.isin(buf, _SPACE_BYTES)
        starts = np.flatnonzero(~space & np.concatenate([[True], space[:-1]]))
        per_line = np.bincount(np.searchsorted(np.flatnonzero(buf == 10), starts), minlength=len(rows))
        if len(per_line) == len(rows) and np.all(per_line == width):
            with warnings.catch_warnings():
                # numpy stops at a token it cannot read (e.g. "1.52.3"), with a warning or an
                # error depending on the version: either way, diagnose line by line below
                warnings.simplefilter("error", DeprecationWarning)
                try:
                    values = np.fromstring(block, sep=" ")  # text mode: any whitespace separates
                except (DeprecationWarning, ValueError):
                    values = np.zeros(0)
            if values.size == width * len(rows) and np.all(np.isfinite(values)):
                return values.reshape(len(rows), width)
    # Something is off: find the first bad line for the message.
    for n, s in rows:
        toks = _split(s)
        if len(toks) != width:
            raise lines.fail(n, f"a frame needs {width} numbers (one per channel), found {len(toks)}")
        for t in toks:
            v = _number(t)
            if v is None or not np.isfinite(v):
                raise lines.fail(n, f'"{t[:20]}" is not a finite number')
    raise lines.fail(rows[0][0], "unreadable frame data")  # pragma: no cover - the loop finds it


def read_bvh(path: Path) -> Bvh:
    path = Path(path)
    try:
        size = path.stat().st_size
        if size > MAX_BYTES:
            raise BvhFormatError(f"{path}: {size / 2**20:.0f} MB is larger than this reader takes "
                                 f"({MAX_BYTES // 2**20} MB); cut the take shorter")
        text = path.read_text(encoding="utf-8", errors="replace")
    except OSError as e:
        raise BvhFormatError(f"{path}: cannot be read ({e.strerror or e})") from e
    return parse_bvh(text, str(path))


def _axis_matrix(channel: str, degrees: np.ndarray) -> np.ndarray:
    return Rotation.from_euler(channel[0], degrees[:, None], degrees=True).as_matrix()


def joint_positions(bvh: Bvh) -> np.ndarray:
    """World positions [F, N, 3] of every joint and End Site, in the file's units and axes."""
    frames = len(bvh)
    out = np.zeros((frames, len(bvh.names), 3))
    # Rotation matrices [F, 3, 3] chained with matmul: far quicker than composing scipy Rotations.
    world: list[np.ndarray] = []
    col = 0
    for j, parent in enumerate(bvh.parents):
        local_pos = np.tile(bvh.offsets[j], (frames, 1))
        rot = np.broadcast_to(np.eye(3), (frames, 3, 3))
        for c in bvh.channels[j]:
            values = bvh.motion[:, col]
            col += 1
            if c.endswith("position") and parent < 0:
                local_pos[:, "XYZ".index(c[0])] += values
            elif c.endswith("position"):
                local_pos[:, "XYZ".index(c[0])] = values   # replaces the OFFSET (module docstring)
            else:
                rot = rot @ _axis_matrix(c, values)  # intrinsic: later channels turn about rotated axes
        if parent < 0:
            out[:, j] = local_pos
            world.append(rot)
        else:
            out[:, j] = out[:, parent] + (world[parent] @ local_pos[:, :, None])[:, :, 0]
            world.append(world[parent] @ rot)
    return out
