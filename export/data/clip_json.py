"""The contract's clip format (contract/clip.schema.json): read and write."""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from ..contract import load_json, validate
from .clip import Clip, Split
from .skeleton import SKELETON

# Version 2 keeps the horizontal root translation (clips travel); version 1 files have the root above
# the origin in every frame and read as the same kind of world positions, just without travel.
CLIP_VERSION = 2


def _float32_text(values: np.ndarray) -> list[str]:
    # Shortest decimal that reads back as the same float32, so files are exact and small.
    return [np.format_float_positional(v, unique=True, trim="-") for v in values.astype(np.float32).ravel()]


def positions_json(positions: np.ndarray) -> str:
    f, j, _ = positions.shape
    nums = _float32_text(positions)
    frames = []
    for i in range(f):
        joints = ["[" + ",".join(nums[(i * j + k) * 3:(i * j + k) * 3 + 3]) + "]" for k in range(j)]
        frames.append("[" + ",".join(joints) + "]")
    return "[\n" + ",\n".join(frames) + "\n]"


def clip_document(clip: Clip) -> dict:
    doc = {
        "format": "motion-futures/clip",
        "version": CLIP_VERSION,
        "name": clip.name,
        "action": clip.action,
        "fps": clip.fps,
        "loops": clip.loops,
        "skeleton": clip.skeleton.to_contract(),
        "split": {"role": clip.split.role,
                  "train": [list(r) for r in clip.split.train],
                  "test": [list(r) for r in clip.split.test]},
        "source": clip.source,
        "positions": None,
    }
    if clip.cycle_frames is not None:
        doc["cycle_frames"] = clip.cycle_frames
    if clip.subject is not None:
        doc["subject"] = clip.subject
    if clip.take is not None:
        doc["take"] = clip.take
    return doc


def write_clip(clip: Clip, path: Path) -> None:
    doc = clip_document(clip)
    head = json.dumps(doc)
    text = head.replace('"positions": null', '"positions": ' + positions_json(clip.positions))
    parsed = json.loads(text)
    validate(parsed, "clip", path)
    Path(path).write_text(text + "\n")


def read_clip(path: Path) -> Clip:
    doc = load_json(path, "clip")
    if doc["skeleton"]["joints"] != list(SKELETON.names):
        raise ValueError(f"{path}: field skeleton/joints: not the project skeleton; retarget it first")
    split = doc["split"]
    return Clip(
        name=doc["name"], action=doc["action"], fps=doc["fps"], loops=doc["loops"],
        positions=np.asarray(doc["positions"], dtype=np.float32).astype(np.float64),
        split=Split(split["role"], [tuple(r) for r in split["train"]], [tuple(r) for r in split["test"]]),
        source=doc.get("source", {}), cycle_frames=doc.get("cycle_frames"),
        subject=doc.get("subject"), take=doc.get("take"),
    )
