"""`python -m export data`: convert a motion source into public/clips (clips + index with the split)."""
from __future__ import annotations

import hashlib
import json
from pathlib import Path

from ..contract import validate
from ..paths import CLIPS_DIR
from . import split as split_rules
from .clip import Clip
from .clip_json import write_clip
from .skeleton import SKELETON
from .sources import FPS


def index_document(clips: list[Clip], data_hash: str) -> dict:
    return {
        "format": "motion-futures/clip-index",
        "version": 2,
        "fps": FPS,
        "skeleton": {**SKELETON.to_contract(), "offsets": SKELETON.offsets.round(7).tolist()},
        "split_rules": split_rules.RULES,
        "data_hash": data_hash,
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


def files_hash(paths: list[Path]) -> str:
    h = hashlib.sha256()
    for p in paths:
        h.update(p.name.encode() + b"\0" + p.read_bytes() + b"\0")
    return "sha256:" + h.hexdigest()


def build(clips: list[Clip], out_dir: Path = CLIPS_DIR) -> dict:
    """Write every clip and the index (with the split) into out_dir; returns the index."""
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    paths = []
    for clip in clips:
        path = out_dir / f"{clip.name}.json"
        write_clip(clip, path)
        paths.append(path)
    index = index_document(clips, files_hash(paths))
    validate(index, "clip-index", out_dir / "index.json")
    (out_dir / "index.json").write_text(json.dumps(index, indent=1) + "\n")
    # Drop clips a previous run wrote that this source no longer has.
    keep = {p.name for p in paths} | {"index.json"}
    for stale in out_dir.glob("*.json"):
        if stale.name not in keep:
            stale.unlink()
    return index
