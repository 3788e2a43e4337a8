"""public/models/manifest.json: what the browser needs to run every model."""
from __future__ import annotations

import json
import re
from pathlib import Path

from .contract import load_json, validate
from .data.skeleton import SKELETON
from .data.sources import FPS
from .ops.envelope import SHARED


def share_speed_envelope(models: list[dict]) -> tuple[dict, list[dict]]:
    """One speed envelope for every model (issue 30): the speed quantities and tempo's reference poses of
    the model with the shortest history, whose training windows include every other model's last frames.
    Returned once, beside the models' envelopes without it: the manifest stores it once at its top level
    ("speed_envelope"; six copies of tempo's poses were 90 kB of the site's gzipped size) and its readers
    (read_manifest, web/src/contract/validate.ts) put it back into every envelope."""
    with_env = [m for m in models if "envelope" in m.get("params", {})]
    if not with_env:
        return {}, models
    source = min(with_env, key=lambda m: m["params"]["history_frames"])["params"]["envelope"]
    shared = {q: source[q] for q in (*SHARED, "tempo_poses") if q in source}
    out = []
    for m in models:
        if m in with_env:
            env = {q: v for q, v in m["params"]["envelope"].items() if q not in shared}
            m = {**m, "params": {**m["params"], "envelope": env}}
        out.append(m)
    return shared, out


def expand_speed_envelope(doc: dict) -> dict:
    """The manifest as its models use it: the shared speed envelope inside every model's envelope."""
    shared = doc.get("speed_envelope")
    if not shared:
        return doc
    models = [{**m, "params": {**m["params"], "envelope": {**m["params"]["envelope"], **shared}}}
              if "envelope" in m.get("params", {}) else m for m in doc["models"]]
    return {**{k: v for k, v in doc.items() if k != "speed_envelope"}, "models": models}


def manifest_document(models: list[dict], actions: list[str], data_hash: str) -> dict:
    shared, models = share_speed_envelope(models)
    return {
        "format": "motion-futures/manifest",
        "version": 1,
        "fps": FPS,
        "skeleton": {**SKELETON.to_contract(), "offsets": SKELETON.offsets.tolist()},
        "actions": actions,
        "data_hash": data_hash,
        **({"speed_envelope": shared} if shared else {}),
        "models": models,
    }


def write_manifest(doc: dict, path: Path) -> None:
    validate(doc, "manifest", path)
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    Path(path).write_text(_numbers_on_one_line(json.dumps(doc, indent=1)) + "\n")


_NUMBERS = re.compile(r"\[\s*(-?[0-9][0-9.eE+-]*(?:,\s*-?[0-9][0-9.eE+-]*)*)\s*\]")


def _numbers_on_one_line(text: str) -> str:
    """An array of plain numbers on one line: tempo's reference poses would take a line per number."""
    return _NUMBERS.sub(lambda m: "[" + ",".join(m.group(1).split(",")).replace(" ", "").replace("\n", "") + "]", text)


def read_manifest(path: Path) -> dict:
    return expand_speed_envelope(load_json(path, "manifest"))


def entry(models: list[dict] | dict, model_id: str) -> dict:
    doc = models if isinstance(models, list) else models["models"]
    for m in doc:
        if m["id"] == model_id:
            return m
    raise ValueError(f"unknown model {model_id!r}; the manifest has {[m['id'] for m in doc]}")
