"""Train, export and describe models: the path from data to public/models shared by every method."""
from __future__ import annotations

import json
from pathlib import Path

import torch

from .config import model_hash
from .data.build import build as build_clips
from .data.clip import Clip
from .data.sources import MotionSource, default_source
from .manifest import manifest_document, write_manifest
from .methods import method_for
from .methods.base import Method
from .onnx.export import write as write_graph
from .paths import CLIPS_DIR, MODELS_DIR, RUNS_DIR
from .train.loop import TrainConfig, fit, seed_everything


def train(cfg: dict, clips: list[Clip], run_dir: Path | None = None, resume: bool = False,
          progress: bool = True, stop_at: int | None = None, **train_overrides) -> tuple[Method, torch.nn.Module]:
    method = method_for(cfg)
    tc = TrainConfig.from_cfg(cfg, **train_overrides)
    seed_everything(tc.seed)  # the initial weights are part of what the seed fixes
    data = method.prepare(clips)
    model = method.build(data)
    if method.trainable:
        fit(method, model, data, tc, run_dir, resume, progress, stop_at)
    return method, model


def export(method: Method, model: torch.nn.Module, cfg: dict, out_dir: Path, actions: list[str],
           data_hash: str, config_name: str | None = None) -> dict:
    """Write the model's graphs and files into out_dir and return its manifest entry."""
    out_dir.mkdir(parents=True, exist_ok=True)
    graphs = {}
    for role, graph in method.graphs(model).items():
        graphs[role] = write_graph(graph, out_dir / f"{cfg['id']}.{role}.onnx")
    files = {}
    for role, doc in method.files(model).items():
        name = f"{cfg['id']}.{role}.json"
        (out_dir / name).write_text(json.dumps(doc, separators=(",", ":")) + "\n")
        files[role] = name
    entry = {"id": cfg["id"], "method": cfg["method"], "label": cfg.get("label", cfg["id"]),
             "description": cfg.get("description", ""), "hash": model_hash(cfg, data_hash),
             "graphs": graphs, "params": method.params(model), "controls": method.controls(actions)}
    if config_name:
        entry["config"] = config_name
    if files:
        entry["files"] = files
    return entry


def build_models(configs: list[tuple[str, dict]], source: MotionSource | None = None,
                 out_dir: Path = MODELS_DIR, clips_dir: Path = CLIPS_DIR, progress: bool = True,
                 only: list[str] | None = None) -> dict:
    """Convert the data, then train and export every config (or only the ids in `only`, keeping
    the other entries of the existing manifest); write the manifest. Returns it."""
    clips = (source or default_source()).clips()
    index = build_clips(clips, clips_dir)
    actions = sorted({c.action for c in clips})
    previous = {}
    if only and (out_dir / "manifest.json").exists():
        previous = {m["id"]: m for m in json.loads((out_dir / "manifest.json").read_text())["models"]}
    entries = []
    for name, cfg in configs:
        if only and cfg["id"] not in only and cfg["id"] in previous:
            entries.append(previous[cfg["id"]])
            continue
        method, model = train(cfg, clips, RUNS_DIR / cfg["id"], progress=progress)
        entries.append(export(method, model, cfg, out_dir, actions, index["data_hash"], name))
    doc = manifest_document(entries, actions, index["data_hash"])
    write_manifest(doc, out_dir / "manifest.json")
    keep = {g["file"] for e in entries for g in e["graphs"].values()}
    keep |= {f for e in entries for f in e.get("files", {}).values()} | {"manifest.json"}
    for stale in list(out_dir.glob("*.onnx")) + list(out_dir.glob("*.json")):
        if stale.name not in keep:
            stale.unlink()
    return doc
