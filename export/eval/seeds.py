"""`make results`, first half: train the extra training seeds and the ablations into runs/seeds/.

Each (config, seed) is trained through export/pipeline.py::train with the seed overridden,
exported with export/pipeline.py::export into runs/seeds/<model id>/seed<s>/, and described by
its own manifest.json, so the harness loads it exactly like public/models. public/models keeps
only the served seed-0 models. A directory whose manifest already carries the model hash this
code would produce is kept as it is. Their ONNX parity is checked with the rounding-derived limit
of export/onnx/parity.py (a long rollout may differ from torch by float32 rounding alone).
"""
from __future__ import annotations

import json
import time
from pathlib import Path
from unittest import mock

from ..config import model_hash, override
from ..data.clip import Clip
from ..manifest import manifest_document, read_manifest, write_manifest
from ..methods import method_for
from ..onnx import export as onnx_export
from ..onnx.parity import check_parity
from ..paths import CLIPS_DIR
from .harness import SEEDS_DIR, row_config, served_configs
from .rows import ROWS, Row


def data_hash() -> str:
    return json.loads((CLIPS_DIR / "index.json").read_text())["data_hash"]


def _current(directory: Path, model_id: str, want: str) -> bool:
    path = directory / "manifest.json"
    if not path.exists():
        return False
    entry = next((m for m in read_manifest(path)["models"] if m["id"] == model_id), None)
    return entry is not None and entry["hash"] == want


def train_seeds(clips: list[Clip], seeds: list[int], rows: list[Row] = ROWS, seeds_root: Path = SEEDS_DIR,
                progress=print) -> list[str]:
    """Train every seed of every model row that is not served from public/models; returns notes."""
    from ..pipeline import export, train
    dh = data_hash()
    actions = sorted({c.action for c in clips})
    served = served_configs()
    notes, seen = [], set()
    for row in rows:
        if row.kind != "model" or row.config in seen:
            continue
        seen.add(row.config)
        cfg, why = row_config(row)
        if cfg is None:   # nothing to evaluate it with yet, so nothing to train
            notes.append(f"{row.id}: not trained, {why}")
            continue
        if not method_for(cfg).trainable:
            continue   # the harness evaluates it at seed 0 only
        for seed in seeds:
            if seed == 0 and row.config in served:
                continue   # the served model in public/models is seed 0
            seeded = override(cfg, **{"train.seed": seed})
            out = seeds_root / cfg["id"] / f"seed{seed}"
            want = model_hash(seeded, dh)
            if _current(out, cfg["id"], want):
                continue
            start = time.time()
            method, model = train(seeded, clips, progress=False)
            # The served path's check (1e-4) sits in export/onnx/export.py, which every served model's
            # hash covers; these models get the rounding-derived limit by replacing it for this call.
            with mock.patch.object(onnx_export, "check_parity", check_parity):
                entry = export(method, model, seeded, out, actions, dh, row.config)
            write_manifest(manifest_document([entry], actions, dh), out / "manifest.json")
            progress(f"trained {cfg['id']} seed {seed} in {time.time() - start:.0f} s -> {out}")
    return notes
