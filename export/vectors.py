"""`python -m export vectors`: the shared test vectors in contract/vectors/.

Python writes them; tests/export checks the committed files still match this code, and
tests/web checks that TypeScript reproduces them. Each later method adds its own family.
"""
from __future__ import annotations

import json
from typing import Callable

import numpy as np

from .data.skeleton import SKELETON
from .ops.facing import canonicalise
from .paths import VECTORS_DIR
from .rng import Prng

PRNG_SEEDS = [0, 1, 42, 123456789, 4294967295]


def prng_vector() -> dict:
    cases = []
    for seed in PRNG_SEEDS:
        u = Prng(seed)
        n = Prng(seed)
        cases.append({
            "seed": seed,
            "u32": [u.next_u32() for _ in range(1000)],
            "normals": [n.normal() for _ in range(1000)],
        })
    return {"about": "seed -> first 1000 raw u32 draws (uniform = u32 / 2^32, exact) and, from a fresh "
                     "generator, the first 1000 normals (two uniforms each, tolerance 1e-12)",
            "cases": cases}


def facing_vector() -> dict:
    from .data.clip_json import read_clip
    from .paths import CLIPS_DIR
    cases = []
    for name, start in [("walker_turn_left1", 3), ("spin", 40), ("cartwheel", 20)]:
        window = read_clip(CLIPS_DIR / f"{name}.json").positions[start:start + 12].round(7)
        out, angle = canonicalise(window, at_frame=9, skeleton=SKELETON)
        cases.append({"clip": name, "start": start, "at_frame": 9, "window": window.tolist(),
                      "angle": angle, "canonical": out.tolist()})
    return {"about": "a window rotated about +y so that at_frame faces +z (tolerance 1e-9)", "cases": cases}


def e2e_vector() -> dict:
    """For every served model: manifest + history + request + seed -> futures and lengths.

    Stochastic methods add cases whose stored margins (to the stop threshold, to sampling CDF
    bounds) are at least E2E_MARGIN, because a 1e-6 runtime difference could flip such a
    decision; the deterministic baselines have no such decisions.
    """
    from .data.clip_json import read_clip
    from .manifest import read_manifest
    from .paths import CLIPS_DIR, MODELS_DIR
    from .sample.predictor import load_predictor
    from .sample.request import Request
    manifest = read_manifest(MODELS_DIR / "manifest.json")
    cases = []
    for entry in manifest["models"]:
        predictor = load_predictor(entry["id"])
        n = entry["params"]["history_frames"]
        for clip_name, start in [("walker_walk_forward", 3), ("spin", 90)]:
            history = read_clip(CLIPS_DIR / f"{clip_name}.json").positions[start:start + n]
            stochastic = any(c["id"] == "k" for c in entry["controls"])
            req = Request(k=4 if stochastic else 1, seed=7, horizon_frames=entry["params"]["future_frames"] + 15)
            pred = predictor.predict(history, req)
            cases.append({"model": entry["id"], "model_hash": entry["hash"], "clip": clip_name, "start": start,
                          "history": history.astype(np.float32).tolist(), "request": req.to_json(),
                          "lengths": pred.lengths.tolist(), "futures": np.round(pred.futures.astype(np.float64), 6).tolist()})
    return {"about": "TypeScript predictors must reproduce these: lengths (and sampled labels) exactly, "
                     "positions to 1e-4. Cases keep margins of at least E2E_MARGIN to any decision threshold.",
            "margin": E2E_MARGIN, "cases": cases}


E2E_MARGIN = 1e-3

FAMILIES: dict[str, Callable[[], dict]] = {"prng": prng_vector, "facing": facing_vector, "e2e": e2e_vector}


def render(doc: dict) -> str:
    return json.dumps(doc, separators=(",", ":")) + "\n"


def write_all() -> list[str]:
    VECTORS_DIR.mkdir(parents=True, exist_ok=True)
    written = []
    for name, make in FAMILIES.items():
        (VECTORS_DIR / f"{name}.json").write_text(render(make()))
        written.append(name)
    return written
