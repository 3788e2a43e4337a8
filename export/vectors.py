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
from .vectors_keyposes import keyposes_e2e_cases, keyposes_vector
from .vectors_lcp import lcp_e2e_cases, lcp_vector
from .vectors_retarget import retarget_vector
from .vectors_wat import dct_smoothness_vector, variance_stop_vector, wat_e2e_cases
from .vectors_wat_transformer import wat_transformer_e2e_cases

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


def direct_e2e_cases(entry: dict, predictor, margin: float) -> list[dict]:
    """The deterministic baselines: no thresholded decisions, so no margins to keep."""
    from .data.clip_json import read_clip
    from .paths import CLIPS_DIR
    from .sample.request import Request
    cases = []
    n = entry["params"]["history_frames"]
    for clip_name, start in [("walker_walk_forward", 3), ("spin", 90)]:
        history = read_clip(CLIPS_DIR / f"{clip_name}.json").positions[start:start + n]
        req = Request(k=1, seed=7, horizon_frames=entry["params"]["future_frames"] + 15)
        pred = predictor.predict(history, req)
        cases.append({"model": entry["id"], "model_hash": entry["hash"], "clip": clip_name, "start": start,
                      "history": history.astype(np.float32).tolist(), "request": req.to_json(),
                      "lengths": pred.lengths.tolist(), "futures": np.round(pred.futures.astype(np.float64), 6).tolist()})
    return cases


# Each method's cases (its own module picks histories and requests; stochastic ones keep margins).
E2E_CASES: dict[str, Callable[[dict, object, float], list[dict]]] = {
    "zero_velocity": direct_e2e_cases,
    "regression": direct_e2e_cases,
    "wat": wat_e2e_cases,
    "wat_transformer": wat_transformer_e2e_cases,
    "lcp_vae": lambda entry, predictor, margin: lcp_e2e_cases(entry, predictor),
    "keyposes": keyposes_e2e_cases,
}


def e2e_vector() -> dict:
    """For every served model: manifest + history + request + seed -> futures and lengths.

    Stochastic methods keep only cases whose stored margins (to the stop threshold, to sampling
    CDF bounds) are at least E2E_MARGIN, because a 1e-6 runtime difference could flip such a
    decision.
    """
    from .manifest import read_manifest
    from .paths import MODELS_DIR
    from .sample.predictor import load_predictor
    manifest = read_manifest(MODELS_DIR / "manifest.json")
    cases = []
    for entry in manifest["models"]:
        cases += E2E_CASES[entry["method"]](entry, load_predictor(entry["id"]), E2E_MARGIN)
    return {"about": "TypeScript predictors must reproduce these: lengths (and sampled labels) exactly, "
                     "positions to 1e-4. Cases keep margins of at least E2E_MARGIN to any decision threshold.",
            "margin": E2E_MARGIN, "cases": cases}


E2E_MARGIN = 1e-3

FAMILIES: dict[str, Callable[[], dict]] = {
    "prng": prng_vector,
    "facing": facing_vector,
    "dct_smoothness": dct_smoothness_vector,
    "variance_stop": variance_stop_vector,
    "lcp": lcp_vector,
    "keyposes": keyposes_vector,
    "retarget": retarget_vector,
    "e2e": e2e_vector,
}


def render(doc: dict) -> str:
    return json.dumps(doc, separators=(",", ":")) + "\n"


def write_all() -> list[str]:
    VECTORS_DIR.mkdir(parents=True, exist_ok=True)
    written = []
    for name, make in FAMILIES.items():
        (VECTORS_DIR / f"{name}.json").write_text(render(make()))
        written.append(name)
    return written
