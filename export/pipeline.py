"""Train, export and describe models: the path from data to public/models shared by every method."""
from __future__ import annotations

import json
from pathlib import Path

import torch

from .config import model_hash
from .data.build import build as build_clips, written_by
from .data.clip import Clip
from .data.sources import FPS, MotionSource, default_source
from .data.windows import windows
from .manifest import manifest_document, read_manifest, write_manifest
from .methods import method_for
from .methods.base import Method
from .onnx.export import write as write_graph
from .ops.envelope import envelope
from .paths import CLIPS_DIR, MODELS_DIR, RUNS_DIR
from .train.loop import TrainConfig, fit, seed_everything


def train(cfg: dict, clips: list[Clip], run_dir: Path | None = None, resume: bool = False,
          progress: bool = True, stop_at: int | None = None, **train_overrides) -> tuple[Method, torch.nn.Module]:
    method = method_for(cfg)
    tc = TrainConfig.from_cfg(cfg, **train_overrides)
    seed_everything(tc.seed)  # the initial weights are part of what the seed fixes
    data = method.prepare(clips)
    method.envelope = training_envelope(clips, method.history_frames)
    model = method.build(data)
    if method.trainable:
        fit(method, model, data, tc, run_dir, resume, progress, stop_at)
    return method, model


def training_envelope(clips: list[Clip], history_frames: int) -> dict:
    """The envelope of the canonical training histories (export/ops/envelope.py), in the manifest."""
    ws = windows(clips, "train", history_frames + 1, history_frames)
    return envelope([w.positions[:history_frames] for w in ws], FPS)


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


def say_what_is_replaced(source: MotionSource, clips_dir: Path, models_dir: Path) -> None:
    """Training on other data replaces the site's clips and models: say so before doing it."""
    index = clips_dir / "index.json"
    if not index.exists():
        return
    old = json.loads(index.read_text())
    if old.get("written_by", "default") != written_by(source):
        manifest = models_dir / "manifest.json"
        models = [m["id"] for m in json.loads(manifest.read_text())["models"]] if manifest.exists() else []
        print(f"replacing {clips_dir} ({len(old.get('clips', []))} clips from {old.get('written_by', 'the default data')}) "
              f"and {models_dir} ({', '.join(models) or 'no models'}) with {written_by(source)}", flush=True)


def build_models(configs: list[tuple[str, dict]], source: MotionSource | None = None,
                 out_dir: Path = MODELS_DIR, clips_dir: Path = CLIPS_DIR, progress: bool = True,
                 only: list[str] | None = None, resume: bool = False) -> dict:
    """Convert the data, then train and export every config (or only the ids in `only`, keeping
    the other entries of the existing manifest); write the manifest. Returns it. With `resume`, each
    model continues its checkpoint in runs/<id>/ (a finished one is only exported): models trained
    side by side with `python -m export train` are then exported in one manifest."""
    source = source or default_source()
    clips = source.clips()
    say_what_is_replaced(source, clips_dir, out_dir)
    index = build_clips(source, clips_dir, clips, replace=True)
    actions = sorted({c.action for c in clips})
    previous = {}
    if only and (out_dir / "manifest.json").exists():
        previous = {m["id"]: m for m in read_manifest(out_dir / "manifest.json")["models"]}
    entries = []
    for name, cfg in configs:
        if only and cfg["id"] not in only and cfg["id"] in previous:
            entries.append(previous[cfg["id"]])
            continue
        method, model = train(cfg, clips, RUNS_DIR / cfg["id"], resume=resume, progress=progress)
        entries.append(export(method, model, cfg, out_dir, actions, index["data_hash"], name))
    doc = manifest_document(entries, actions, index["data_hash"])
    write_manifest(doc, out_dir / "manifest.json")
    keep = {g["file"] for e in entries for g in e["graphs"].values()}
    keep |= {f for e in entries for f in e.get("files", {}).values()} | {"manifest.json"}
    for stale in list(out_dir.glob("*.onnx")) + list(out_dir.glob("*.json")):
        if stale.name not in keep:
            stale.unlink()
    return doc
