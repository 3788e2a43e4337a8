"""The native half of the benchmark: plan the cases, run them with the Python predictor on native
onnxruntime (one thread, the sessions of export/onnx/export.py), capture each graph's inputs, time
each graph alone, and describe each ONNX file (size, gzipped size, parameters, nodes, op types).

The predictors are twins with one shared PRNG, so the browser side (bench/) calls the same graphs
with the same batch sizes and the same inputs; the per-graph ratio browser/native compares like
with like.
"""
from __future__ import annotations

import base64
import gzip
import logging
import statistics
import time
from collections import Counter
from pathlib import Path

import numpy as np
import onnx
import onnxruntime

from ..data.clip_json import read_clip
from ..onnx.export import session
from ..paths import CLIPS_DIR
from ..sample.predictor import predictor_for
from ..sample.request import Request

# One history for every model: a test clip (unseen motion), long enough for the longest history.
# The held-out walk where the site opens it: past its standing start (web/src/motion/moving-start.ts),
# where every method, Keyposes included, accepts the history.
HISTORY = {"clip": "cmu_10_04", "start": 15}
SEED = 1
KS = (1, 10, 50)
# The issues' caps on a model's ONNX files together, gzipped (MB = 10^6 bytes).
CAPS_MB = {"wat": 0.45, "wat_transformer": 0.55, "lcp_vae": 0.25, "keyposes": 0.3}
PREFERRED_ACTIONS = ("run", "jump", "walk", "kick", "punch")
# The batch at which the optimisation variants of each graph are timed (the K=10 target's batch).
VARIANT_BATCH = 10


def cap_mb(entry: dict) -> float | None:
    if entry["method"] == "wat" and "transformer" in (entry["id"] + str(entry.get("config", ""))).lower():
        return CAPS_MB["wat_transformer"]
    return CAPS_MB.get(entry["method"])


def three_actions(entry: dict, actions: list[str]) -> list[str]:
    """The default action sequence extended to three actions, each different from the one before."""
    spec = next(c for c in entry["controls"] if c["id"] == "actions")
    seq = list(spec.get("default") or [])[:3]
    known = list(entry["params"].get("actions") or actions)
    # everyday actions first (a walk-run-jump style sequence), then the rest in the model's order
    known = [a for a in PREFERRED_ACTIONS if a in known] + [a for a in known if a not in PREFERRED_ACTIONS]
    for a in known:
        if len(seq) >= 3:
            break
        if not seq or seq[-1] != a:
            seq.append(a)
    if len(seq) < 3:
        raise ValueError(f"model {entry['id']}: cannot make a three-action sequence from {known}")
    return seq


def plan(manifest: dict) -> list[dict]:
    """Per model: K = 1, 10, 50 with the default controls (K = 1 only for a model without a K
    control); a model with an action-sequence control uses its default sequence there, plus a
    K = 10 row with a three-action sequence."""
    cases = []
    for entry in manifest["models"]:
        ids = {c["id"] for c in entry["controls"]}
        actions_spec = next((c for c in entry["controls"] if c["id"] == "actions"), None)
        default_actions = list(actions_spec.get("default") or []) if actions_spec else []
        for k in (KS if "k" in ids else (1,)):
            cases.append({"id": f"{entry['id']}/k{k}", "model": entry["id"], "k": k, "actions": len(default_actions),
                          **HISTORY, "request": Request(k=k, seed=SEED, actions=default_actions).to_json()})
        if actions_spec:
            seq = three_actions(entry, manifest["actions"])
            cases.append({"id": f"{entry['id']}/k10-a{len(seq)}", "model": entry["id"], "k": 10, "actions": len(seq),
                          **HISTORY, "request": Request(k=10, seed=SEED, actions=seq).to_json()})
    return cases


def graph_facts(path: Path) -> dict:
    """Size, gzipped size (level 9), parameters (initializer and constant elements), nodes, op types."""
    data = path.read_bytes()
    model = onnx.load_from_string(data)
    params = sum(int(np.prod(t.dims)) for t in model.graph.initializer)
    for node in model.graph.node:
        if node.op_type == "Constant":
            params += sum(int(np.prod(a.t.dims)) for a in node.attribute if a.type == onnx.AttributeProto.TENSOR)
    ops = Counter(n.op_type for n in model.graph.node)
    return {"file": path.name, "bytes": len(data), "gzip_bytes": len(gzip.compress(data, 9)), "params": params,
            "nodes": len(model.graph.node), "ops": dict(ops.most_common())}


def sizes(manifest: dict, models_dir: Path) -> list[dict]:
    out = []
    for entry in manifest["models"]:
        graphs = {role: graph_facts(models_dir / spec["file"]) for role, spec in entry["graphs"].items()}
        files = {role: (models_dir / f).stat().st_size for role, f in (entry.get("files") or {}).items()}
        gz = sum(g["gzip_bytes"] for g in graphs.values())
        cap = cap_mb(entry)
        out.append({"model": entry["id"], "method": entry["method"], "graphs": graphs, "files": files,
                    "onnx_bytes": sum(g["bytes"] for g in graphs.values()), "onnx_gzip_bytes": gz,
                    "params": sum(g["params"] for g in graphs.values()), "cap_mb": cap,
                    "within_cap": None if cap is None else gz <= cap * 1e6})
    return out


class _Timed:
    """Wraps a predictor's GraphRunner.run: records each call (role, batch, ms) and keeps the
    first inputs seen per (role, batch), to time that graph alone on both sides."""

    def __init__(self, run, feeds: dict):
        self.run, self.calls, self.feeds = run, [], feeds

    def __call__(self, role, feeds):
        batch = int(next(iter(feeds.values())).shape[0])
        self.feeds.setdefault((role, batch), {k: np.array(v, np.float32) for k, v in feeds.items()})
        t0 = time.perf_counter()
        out = self.run(role, feeds)
        self.calls.append({"role": role, "batch": batch, "ms": (time.perf_counter() - t0) * 1e3})
        return out


def load_ms(entry: dict, models_dir: Path) -> float:
    """Creating every graph's session (what the browser's load does after fetching)."""
    t0 = time.perf_counter()
    for spec in entry["graphs"].values():
        session(models_dir / spec["file"])
    return (time.perf_counter() - t0) * 1e3


def run_case(case: dict, predictor, runs: int, warmup: int, feeds: dict) -> dict:
    n = predictor.params["history_frames"]
    history = read_clip(CLIPS_DIR / f"{case['clip']}.json").positions[case["start"]:case["start"] + n]
    req = Request.from_json(case["request"])
    timed = _Timed(predictor.runner.run, feeds)
    predictor.runner.run = timed
    try:
        e2e, per_run = [], []
        for i in range(warmup + runs):
            timed.calls = []
            t0 = time.perf_counter()
            pred = predictor.predict(history, req)
            ms = (time.perf_counter() - t0) * 1e3
            if i >= warmup:
                e2e.append(ms)
                per_run.append(timed.calls)
    finally:
        predictor.runner.run = timed.run
    return {"id": case["id"], "ms": e2e, "timings": per_run, "lengths": [int(x) for x in pred.lengths],
            "frames": int(pred.futures.shape[1])}


def time_graph(source: Path | bytes, feeds: dict[str, np.ndarray], runs: int, warmup: int,
               level: onnxruntime.GraphOptimizationLevel | None = None) -> tuple[list[float], dict]:
    """Milliseconds per session.run (after warm-up) of one graph on one thread, and its outputs."""
    opts = onnxruntime.SessionOptions()
    opts.intra_op_num_threads, opts.inter_op_num_threads, opts.log_severity_level = 1, 1, 3
    if level is not None:
        opts.graph_optimization_level = level
    src = str(source) if isinstance(source, Path) else source
    sess = onnxruntime.InferenceSession(src, opts, providers=["CPUExecutionProvider"])
    out, ms = None, []
    for i in range(warmup + runs):
        t0 = time.perf_counter()
        res = sess.run(None, feeds)
        if i >= warmup:
            ms.append((time.perf_counter() - t0) * 1e3)
        out = out or {o.name: r for o, r in zip(sess.get_outputs(), res)}
    return ms, out


def encode(a: np.ndarray) -> dict:
    """A float32 tensor for the browser: dims and the little-endian bytes, base64."""
    a = np.ascontiguousarray(a, dtype="<f4")
    return {"dims": list(a.shape), "base64": base64.b64encode(a.tobytes()).decode("ascii")}


def preoptimised(path: Path, out_dir: Path) -> Path:
    """The graph after onnxruntime's offline optimisation at level 'extended' (fusions, constant
    folding; 'all' would add layout transforms tied to this CPU, which the docs say not to save)."""
    out = out_dir / f"{path.stem}.ext.onnx"
    opts = onnxruntime.SessionOptions()
    opts.graph_optimization_level = onnxruntime.GraphOptimizationLevel.ORT_ENABLE_EXTENDED
    opts.optimized_model_filepath = str(out)
    opts.log_severity_level = 3
    onnxruntime.InferenceSession(str(path), opts, providers=["CPUExecutionProvider"])
    return out


def quantised(path: Path, out_dir: Path) -> Path:
    """Dynamic int8 weights (MatMul/Gemm/GRU), activations quantised at run time."""
    from onnxruntime.quantization import QuantType, quantize_dynamic
    out = out_dir / f"{path.stem}.int8.onnx"
    root = logging.getLogger()
    level = root.level
    root.setLevel(logging.ERROR)  # quantize_dynamic warns on the root logger about pre-processing
    try:
        # DefaultTensorType: the exporter leaves some MatMul weights without a shape-inferred type
        quantize_dynamic(str(path), str(out), weight_type=QuantType.QInt8,
                         extra_options={"DefaultTensorType": onnx.TensorProto.FLOAT})
    finally:
        root.setLevel(level)
    return out


def rel_diff(a: dict, b: dict) -> float:
    """Largest |a - b| over the outputs, relative to each output's RMS (as the export parity check)."""
    worst = 0.0
    for name, x in a.items():
        y = np.asarray(b[name], np.float64).reshape(np.shape(x))
        rms = float(np.sqrt(np.mean(np.square(x)))) or 1.0
        worst = max(worst, float(np.max(np.abs(np.asarray(x, np.float64) - y))) / rms)
    return worst


def graphs(manifest: dict, feeds: dict, models_dir: Path, work_dir: Path, runs: int, warmup: int) -> list[dict]:
    """Every (model, graph, batch) the cases called, timed alone natively, with its inputs for the
    browser; at the K = 10 batch also the optimisation variants (pre-optimised, int8)."""
    out = []
    work_dir.mkdir(parents=True, exist_ok=True)
    for entry in manifest["models"]:
        for (model, role, batch), f in sorted(feeds.items()):
            if model != entry["id"]:
                continue
            path = models_dir / entry["graphs"][role]["file"]
            ms, served_out = time_graph(path, f, runs, warmup)
            g = {"id": f"{model}/{role}/b{batch}", "model": model, "role": role, "batch": batch,
                 "file": str(path.resolve()), "feeds": {k: encode(v) for k, v in f.items()},
                 "native_ms": ms, "variants": []}
            batches = sorted(b for (m, r, b) in feeds if m == model and r == role)
            if batch == min(batches, key=lambda b: abs(b - VARIANT_BATCH)):
                for name, make in (("pre-optimised (extended)", preoptimised), ("int8 weights", quantised)):
                    v = {"name": name}
                    try:
                        vpath = make(path, work_dir)
                        vms, vout = time_graph(vpath, f, runs, warmup)
                        v.update(file=str(vpath.resolve()), native_ms=vms, rel_diff=rel_diff(served_out, vout),
                                 **{k: graph_facts(vpath)[k] for k in ("bytes", "gzip_bytes", "nodes")})
                    except Exception as e:  # an attempt that fails is a result too
                        v["error"] = f"{type(e).__name__}: {e}"
                    g["variants"].append(v)
            out.append(g)
    return out


def native(manifest: dict, cases: list[dict], models_dir: Path, work_dir: Path, runs: int, warmup: int) -> dict:
    loads, results, feeds = {}, [], {}
    for entry in manifest["models"]:
        loads[entry["id"]] = statistics.median(load_ms(entry, models_dir) for _ in range(3))
        predictor = predictor_for(entry, manifest, models_dir)
        for case in (c for c in cases if c["model"] == entry["id"]):
            got: dict = {}
            results.append(run_case(case, predictor, runs, warmup, got))
            for (role, batch), f in got.items():
                feeds.setdefault((entry["id"], role, batch), f)
    return {"load_ms": loads, "cases": results,
            "graphs": graphs(manifest, feeds, models_dir, work_dir, runs, warmup)}
