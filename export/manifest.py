"""public/models/manifest.json: what the browser needs to run every model."""
from __future__ import annotations

import json
from pathlib import Path

from .contract import load_json, validate
from .data.skeleton import SKELETON
from .data.sources import FPS


def manifest_document(models: list[dict], actions: list[str], data_hash: str) -> dict:
    return {
        "format": "motion-futures/manifest",
        "version": 1,
        "fps": FPS,
        "skeleton": {**SKELETON.to_contract(), "offsets": SKELETON.offsets.tolist()},
        "actions": actions,
        "data_hash": data_hash,
        "models": models,
    }


def write_manifest(doc: dict, path: Path) -> None:
    validate(doc, "manifest", path)
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    Path(path).write_text(json.dumps(doc, indent=1) + "\n")


def read_manifest(path: Path) -> dict:
    return load_json(path, "manifest")


def entry(models: list[dict] | dict, model_id: str) -> dict:
    doc = models if isinstance(models, list) else models["models"]
    for m in doc:
        if m["id"] == model_id:
            return m
    raise ValueError(f"unknown model {model_id!r}; the manifest has {[m['id'] for m in doc]}")
