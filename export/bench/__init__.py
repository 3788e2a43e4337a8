"""`python -m export bench` (`make bench`): the browser performance benchmark of issue 9.

1. native.py plans the cases from public/models/manifest.json (generic over methods), runs them with
   the Python predictor on native onnxruntime, and times each graph alone on the inputs it got;
2. bench/run.mjs builds the site, serves it with `vite preview` and drives Chromium through the
   same cases, graphs and the main page (bench/browser.ts);
3. report.py checks the issue's targets and writes bench/results.json and docs/PERFORMANCE.md.
"""
from __future__ import annotations

import datetime
import gzip
import json
import os
import platform
import subprocess
import time
from collections import defaultdict
from pathlib import Path

import onnxruntime

from ..manifest import read_manifest
from ..paths import MODELS_DIR
from . import native as nat
from .report import markdown, targets

ROOT = Path(__file__).resolve().parents[2]
WORK_DIR = ROOT / "runs" / "bench"
JSON_PATH = ROOT / "bench" / "results.json"
MD_PATH = ROOT / "docs" / "PERFORMANCE.md"
EARLIER_PATH = ROOT / "bench" / "earlier.json"   # earlier runs' summaries, one per change made from the benchmark


def dist_sizes(dist: Path, largest: int = 6) -> dict:
    """Raw and gzipped (each file alone, level 9) size of a built site."""
    files = [p for p in sorted(dist.rglob("*")) if p.is_file()]
    if not files:
        raise FileNotFoundError(f"{dist}: no built site to measure")
    rows = []
    for p in files:
        data = p.read_bytes()
        rows.append({"file": str(p.relative_to(dist)), "bytes": len(data), "gzip_bytes": len(gzip.compress(data, 9))})
    rows.sort(key=lambda r: -r["gzip_bytes"])
    # The served clips have their own budget (issue 17); everything else shares the site's.
    clips = [r for r in rows if r["file"].startswith("clips/")]
    return {"files": len(rows), "bytes": sum(r["bytes"] for r in rows), "gzip_bytes": sum(r["gzip_bytes"] for r in rows),
            "clips_gzip_bytes": sum(r["gzip_bytes"] for r in clips),
            "other_gzip_bytes": sum(r["gzip_bytes"] for r in rows if r not in clips),
            "largest": rows[:largest]}


def profile_summary(graph: str, events: list[dict], runs: int) -> dict:
    """onnxruntime's profile events -> time per op type and per run (ms, averaged over `runs`).
    Node events have cat 'Node', a name ending in '_kernel_time', args.op_name and dur in µs."""
    by_op: dict[str, float] = defaultdict(float)
    run_us = 0.0
    for e in events:
        if e.get("cat") == "Node" and str(e.get("name", "")).endswith("_kernel_time"):
            by_op[e.get("args", {}).get("op_name", "?")] += float(e.get("dur", 0))
        elif e.get("cat") == "Session" and e.get("name") == "model_run":
            run_us += float(e.get("dur", 0))
    if runs < 1:
        raise ValueError("profile needs at least one run")
    op_ms = {op: us / runs / 1e3 for op, us in sorted(by_op.items(), key=lambda kv: -kv[1])}
    return {"graph": graph, "op_ms": op_ms, "node_ms": sum(op_ms.values()), "run_ms": run_us / runs / 1e3}


def machine(browser: dict, load_start: float) -> dict:
    cpu, vector = "unknown", []
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name") and cpu == "unknown":
                cpu = line.split(":", 1)[1].strip()
            if line.startswith("flags") and not vector:
                flags = set(line.split(":", 1)[1].split())
                vector = [f for f in ("sse4_2", "avx2", "fma", "avx512f") if f in flags]
    except OSError:
        pass
    return {"cpu": cpu, "vector": vector, "cores": os.cpu_count(), "os": f"{platform.system()} {platform.release()}",
            "chromium": browser.get("chromium"), "renderer": browser.get("renderer"), "node": browser.get("node"),
            "onnxruntime_web": browser.get("onnxruntime_web"),
            "session_optimization": browser.get("session_optimization", "all"), "python": platform.python_version(),
            "onnxruntime": onnxruntime.__version__, "load_start": load_start, "load_end": os.getloadavg()[0]}


def run_browser(plan_path: Path, out_path: Path) -> dict:
    cmd = ["node", str(ROOT / "bench" / "run.mjs"), str(plan_path), str(out_path)]
    proc = subprocess.run(cmd, cwd=ROOT)
    if proc.returncode != 0:
        raise RuntimeError(f"the browser side of the benchmark failed ({' '.join(cmd)}: exit {proc.returncode})")
    return json.loads(out_path.read_text())


def bench(models_dir: Path = MODELS_DIR, runs: int = 20, warmup: int = 5, json_path: Path = JSON_PATH,
          md_path: Path = MD_PATH, work_dir: Path = WORK_DIR) -> dict:
    t0, load_start = time.time(), os.getloadavg()[0]
    models_dir, work_dir = Path(models_dir), Path(work_dir)
    work_dir.mkdir(parents=True, exist_ok=True)
    manifest = read_manifest(models_dir / "manifest.json")
    cases = nat.plan(manifest)
    sizes = nat.sizes(manifest, models_dir)
    print(f"bench: native onnxruntime, {len(cases)} cases x {runs} runs", flush=True)
    native = nat.native(manifest, cases, models_dir, work_dir / "graphs", runs, warmup)
    plan = {"runs": runs, "warmup": warmup, "dist": str(work_dir / "dist"), "cases": cases,
            "models": [{"id": e["id"], "files": [g["file"] for g in e["graphs"].values()] + list((e.get("files") or {}).values()),
                        "k50": any(c["id"] == "k" for c in e["controls"])} for e in manifest["models"]],
            "graphs": [{k: g[k] for k in ("id", "file", "feeds")} | {"variants": [
                {"name": v["name"], "file": v["file"]} for v in g["variants"] if "file" in v]} for g in native["graphs"]]}
    plan_path, browser_path = work_dir / "plan.json", work_dir / "browser.json"
    plan_path.write_text(json.dumps(plan))
    print("bench: browser (vite build, vite preview, Chromium)", flush=True)
    browser = run_browser(plan_path, browser_path)
    for g in native["graphs"]:
        del g["feeds"]  # the inputs are for the browser; the results keep the timings
    profiles = [profile_summary(p["graph"], p["events"], p["runs"]) for p in browser.pop("profiles", [])]
    dist = dist_sizes(Path(plan["dist"]))
    doc = {"date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
           "machine": machine(browser, load_start), "runs": runs, "warmup": warmup, "cases": cases, "sizes": sizes,
           "dist": dist, "native": native, "browser": browser, "profiles": profiles,
           "json_path": str(json_path.relative_to(ROOT)) if json_path.is_relative_to(ROOT) else str(json_path),
           "notes": browser.get("notes", []),
           "earlier": json.loads(EARLIER_PATH.read_text()) if EARLIER_PATH.exists() else []}
    doc["targets"] = targets(native, browser, sizes, dist, cases)
    doc["seconds"] = time.time() - t0
    json_path.parent.mkdir(parents=True, exist_ok=True)
    json_path.write_text(json.dumps(doc, indent=1))
    md = markdown(doc)
    md_path.parent.mkdir(parents=True, exist_ok=True)
    md_path.write_text(md + "\n")
    return doc


def native_only(models_dir: Path = MODELS_DIR, runs: int = 20, warmup: int = 5) -> dict:
    """The native half alone (no browser): cases, sizes and native timings."""
    manifest = read_manifest(Path(models_dir) / "manifest.json")
    cases = nat.plan(manifest)
    native = nat.native(manifest, cases, Path(models_dir), WORK_DIR / "graphs", runs, warmup)
    for g in native["graphs"]:
        del g["feeds"]
    return {"runs": runs, "warmup": warmup, "cases": cases, "sizes": nat.sizes(manifest, Path(models_dir)), "native": native}
