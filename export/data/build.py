"""`python -m export data`: convert a motion source into clips + an index with the split.

Training reads every clip of the source in memory; what is written is what the site serves
(`served`): for the default data, the DeepMimic clips and, per action and held-out person, its two
longest held-out takes, each cut to its first SERVE_FRAMES frames (so every served held-out clip's
ground truth covers the horizons the models predict); for a user's folder, every clip. The data hash
is over the source files (export/data/default.py source_hash), never over converted floats.
"""
from __future__ import annotations

import dataclasses
import json
from pathlib import Path

from ..contract import validate
from ..paths import CLIPS_DIR
from .clip import Clip, Split
from .clip_json import write_clip
from .default import DEEPMIMIC_SUBJECT
from .skeleton import SKELETON
from .sources import FPS, MotionSource, source_hash

SERVE_FRAMES = 300          # 10 s: room for a 10-frame history and a 5 s horizon, within the 1.5 MB budget
SERVE_PER_PERSON = 2        # held-out takes served per action and person
DEFAULT_ACTION = "walk"     # the site opens on the longest served held-out take of this action


class ReplaceRefused(ValueError):
    """The output folder holds clips another source wrote; converting would delete them."""


def served(clips: list[Clip]) -> list[Clip]:
    """The clips the site serves (see the module docstring). A cut clip keeps its name and its
    test range becomes the frames it keeps; `source.frames` records which frames of the take."""
    if not any(c.subject is not None and c.subject != DEEPMIMIC_SUBJECT for c in clips):
        return clips                                    # a user's folder: serve what it has
    out = [c for c in clips if c.subject == DEEPMIMIC_SUBJECT]
    groups: dict[tuple[str, object], list[Clip]] = {}
    for c in clips:
        if c.split.role == "test":
            groups.setdefault((c.action, c.subject), []).append(c)
    for _, takes in sorted(groups.items(), key=lambda kv: (kv[0][0], str(kv[0][1]))):
        for c in sorted(takes, key=lambda t: (-len(t), t.name))[:SERVE_PER_PERSON]:
            n = min(len(c), SERVE_FRAMES)
            source = {**c.source, "frames": [0, n]} if n < len(c) else c.source
            out.append(dataclasses.replace(c, positions=c.positions[:n], split=Split("test", [], [(0, n)]),
                                           source=source))
    return out


def default_history(clips: list[Clip], history_frames: int = 10) -> dict | None:
    """The history the site opens on: the longest served held-out take of DEFAULT_ACTION, from its start."""
    tests = [c for c in clips if c.split.role == "test" and c.action == DEFAULT_ACTION and len(c) > history_frames]
    if not tests:
        return None
    best = max(tests, key=lambda c: (len(c), c.name))
    return {"clip": best.name, "start": 0}


def index_document(clips: list[Clip], data_hash: str, rules: list[str], notes: dict[str, str],
                   written_by: str) -> dict:
    doc = {
        "format": "motion-futures/clip-index",
        "version": 2,
        "fps": FPS,
        "skeleton": {**SKELETON.to_contract(), "offsets": SKELETON.offsets.tolist()},
        "split_rules": rules,
        "data_hash": data_hash,
        "written_by": written_by,
        "clips": [
            {"name": c.name, "file": f"{c.name}.json", "action": c.action, "loops": c.loops,
             **({"cycle_frames": c.cycle_frames} if c.cycle_frames else {}),
             **({"subject": c.subject} if c.subject is not None else {}),
             **({"take": c.take} if c.take is not None else {}),
             **({"dataset": c.source["dataset"]} if c.source.get("dataset") else {}),
             "frames": len(c), "role": c.split.role,
             "train": [list(r) for r in c.split.train], "test": [list(r) for r in c.split.test]}
            for c in clips
        ],
    }
    if notes:
        doc["notes"] = notes
    default = default_history(clips)
    if default:
        doc["default"] = default
    return doc


def written_by(source: MotionSource) -> str:
    root = getattr(source, "root", None)
    return f"{source.name}" + (f" ({Path(root).resolve()})" if root is not None and source.name != "default" else "")


def check_replace(out_dir: Path, writer: str, replace: bool) -> None:
    """Refuse to overwrite clips that another source wrote, naming them, unless asked to replace."""
    index = Path(out_dir) / "index.json"
    if replace or not index.exists():
        return
    try:
        doc = json.loads(index.read_text())
    except (OSError, json.JSONDecodeError):
        doc = {}
    if doc.get("written_by", "default") != writer:
        names = [c.get("name", "?") for c in doc.get("clips", [])]
        shown = ", ".join(names[:6]) + (f" and {len(names) - 6} more" if len(names) > 6 else "")
        raise ReplaceRefused(f"{out_dir} holds {len(names)} clips written from {doc.get('written_by', 'the default data')} "
                             f"({shown}); converting {writer} there would delete them. Give another --out, or "
                             "--replace to replace them")


def build(source: MotionSource, out_dir: Path = CLIPS_DIR, clips: list[Clip] | None = None, replace: bool = False) -> dict:
    """Write the served clips and the index (with the split) into out_dir; returns the index."""
    out_dir = Path(out_dir)
    writer = written_by(source)
    check_replace(out_dir, writer, replace)
    clips = source.clips() if clips is None else clips
    shown = served(clips)
    out_dir.mkdir(parents=True, exist_ok=True)
    paths = []
    for clip in shown:
        path = out_dir / f"{clip.name}.json"
        write_clip(clip, path)
        paths.append(path)
    index = index_document(shown, source_hash(source), source.split_rules(), source.notes(), writer)
    validate(index, "clip-index", out_dir / "index.json")
    (out_dir / "index.json").write_text(json.dumps(index, indent=1) + "\n")
    # Drop clips a previous run of this source wrote that it no longer has.
    keep = {p.name for p in paths} | {"index.json"}
    for stale in out_dir.glob("*.json"):
        if stale.name not in keep:
            stale.unlink()
    return index
