"""`python -m export vectors`: the shared test vectors in contract/vectors/.

Python writes them; tests/export checks the committed files still match this code, and
tests/web checks that TypeScript reproduces them. Each later method adds its own family.
"""
from __future__ import annotations

import json
from typing import Callable

import numpy as np

from .data.skeleton import SKELETON
from .ops.facing import canonicalise, place
from .paths import VECTORS_DIR
from .rng import Prng
from .tolerance import about, float32_floor, float_gap, keeps_its_stop_margin, rounding_gap
from .vectors_keyposes import keyposes_e2e_cases, keyposes_record, keyposes_vector
from .vectors_lcp import lcp_e2e_cases, lcp_record, lcp_vector
from .vectors_asf import asf_vector
from .vectors_guard import bones_vector, envelope_vector, guard_vector
from .vectors_metrics import metrics_vector
from .vectors_foot_plant import foot_plant_vector
from .vectors_readout import readout_vector
from .vectors_record import record
from .vectors_retarget import retarget_vector
from .vectors_wat import dct_smoothness_vector, variance_stop_vector, wat_e2e_cases, wat_record
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
                     "generator, the first 1000 normals (two uniforms each)",
            "cases": cases}


def facing_vector() -> dict:
    from .data.clip_json import read_clip
    from .paths import CLIPS_DIR
    cases = []
    # a travelling, turning walk; a spin; a held-out salsa take (the root channel's round trip on all)
    for name, start in [("deepmimic_walker_turn_left1", 3), ("deepmimic_spin", 40), ("cmu_61_13", 20)]:
        window = read_clip(CLIPS_DIR / f"{name}.json").positions[start:start + 12].round(7)
        out, placement = canonicalise(window, at_frame=9, skeleton=SKELETON)
        cases.append({"clip": name, "start": start, "at_frame": 9, "window": window.tolist(),
                      "placement": {"angle": placement.angle, "x": placement.x, "z": placement.z},
                      "canonical": out.tolist(), "placed_back": place(out, placement).tolist()})
    return {"about": "a world window -> canonical (root-relative poses, the root channel in the root joint's x and z, "
                     "turned so at_frame faces +z with the root above the origin there), its placement, and the "
                     "canonical window placed back in the world (the round trip)", "cases": cases}


def direct_e2e_cases(entry: dict, predictor, margin: float) -> list[dict]:
    """The deterministic baselines: no thresholded decisions, so no margins to keep."""
    from .data.clip_json import read_clip
    from .paths import CLIPS_DIR
    from .sample.request import Request
    cases = []
    n = entry["params"]["history_frames"]
    for clip_name, start in [(HELD_OUT_WALK, 3), (HELD_OUT_DANCE, 90)]:
        history = read_clip(CLIPS_DIR / f"{clip_name}.json").positions[start:start + n]
        req = Request(k=1, seed=7, horizon_frames=entry["params"]["future_frames"] + 15)
        cases.append(record(entry, clip_name, start, history, req, predictor.predict(history, req)))
    return cases


# Each method's cases (its own module picks histories and requests; stochastic ones keep margins)
# and what a case stores of a prediction (the replay compares on the same fields).
E2E_CASES: dict[str, Callable[[dict, object, float], list[dict]]] = {
    "zero_velocity": direct_e2e_cases,
    "regression": direct_e2e_cases,
    "wat": wat_e2e_cases,
    "wat_transformer": wat_transformer_e2e_cases,
    "lcp_vae": lambda entry, predictor, margin: lcp_e2e_cases(entry, predictor),
    "keyposes": keyposes_e2e_cases,
}
E2E_RECORD = {"zero_velocity": record, "regression": record, "wat": wat_record, "wat_transformer": wat_record,
              "lcp_vae": lcp_record, "keyposes": keyposes_record}
E2E_MARGIN = 1e-3            # sampled labels (Keyposes): distance of a uniform to its CDF bounds
# Held-out takes (people no model trained on) for the end-to-end cases: a walk and a ballet dance.
HELD_OUT_WALK, HELD_OUT_DANCE, HELD_OUT_SALSA = "cmu_10_04", "cmu_49_09", "cmu_61_13"
E2E_TEXT = ("TypeScript predictors must reproduce these: lengths, segments, labels and marks exactly, every float "
            "within the model's tolerance. Cases keep margins to any decision threshold (`margin`, per model), "
            "so a difference within the tolerance cannot flip a decision: each WAT case's stops keep 1.5 x the "
            "tolerance of its own Eq. 8 curve v (derived from that curve's float32-vs-float64 gap, "
            "export/tolerance.py keeps_its_stop_margin); Keyposes' draws keep a distance of each uniform to its CDF "
            "bounds. Checks replay the cases (history, "
            "request, seed) and never select them again.")
STOPPING = ("wat", "wat_transformer")


def replay(case: dict, predictor, entry: dict) -> dict:
    """The committed case's history and request through this predictor, stored as the case was."""
    from .sample.request import Request
    history = np.asarray(case["history"], dtype=np.float32)
    req = Request.from_json(case["request"])
    return E2E_RECORD[entry["method"]](entry, case["clip"], case["start"], history, req,
                                       predictor.predict(history, req))


def e2e_vector(models_dir=None) -> dict:
    """For every served model: manifest + history + request + seed -> futures and lengths.

    Stochastic methods keep only cases whose decisions keep a margin (WAT: 1.5 x the tolerance of
    each case's own Eq. 8 curve; Keyposes: E2E_MARGIN to the sampling CDF bounds), because a last-bit
    runtime difference could flip such a decision. Each model's float32-vs-float64 gap comes from replaying its cases on the same graphs
    widened to float64.
    """
    from .manifest import read_manifest
    from .paths import MODELS_DIR
    from .sample.predictor import load_predictor
    models_dir = models_dir or MODELS_DIR
    manifest = read_manifest(models_dir / "manifest.json")
    cases, gap, margins = [], {}, {}
    for entry in manifest["models"]:
        predictor = load_predictor(entry["id"], models_dir)
        wide = load_predictor(entry["id"], models_dir, precision="float64")

        def measured(cs: list[dict]) -> float:
            return max(max(float_gap(c, replay(c, wide, entry), f"e2e/{entry['id']}"), float32_floor(c)) for c in cs)
        if entry["method"] in STOPPING:
            # each case keeps the stop margin its own Eq. 8 curves ask for (export/tolerance.py)
            def keeps(pred, history, req, wide=wide):
                return bool(pred.margins) and min(pred.margins) >= 1e-6 and keeps_its_stop_margin(pred, wide.predict(history, req))
            mine = E2E_CASES[entry["method"]](entry, predictor, keeps)
            margins[entry["id"]] = "per case: 1.5 x the tolerance of its own Eq. 8 curve"
        else:
            mine = E2E_CASES[entry["method"]](entry, predictor, E2E_MARGIN)
            margins[entry["id"]] = E2E_MARGIN
        gap[entry["id"]] = measured(mine)
        cases += mine
    return {"about": about(E2E_TEXT, gap), "margin": margins, "cases": cases}


def _op_family(make: Callable[[], dict]) -> Callable[[], dict]:
    """A family computed in float64 from committed inputs: its gap is the float32 rounding of its results."""
    def family() -> dict:
        doc = make()
        return {**doc, "about": about(doc["about"], rounding_gap(doc))}
    family.__name__ = make.__name__
    return family


FAMILIES: dict[str, Callable[[], dict]] = {
    "prng": _op_family(prng_vector),
    "facing": _op_family(facing_vector),
    "dct_smoothness": _op_family(dct_smoothness_vector),
    "variance_stop": _op_family(variance_stop_vector),
    "lcp": _op_family(lcp_vector),
    "keyposes": _op_family(keyposes_vector),
    "retarget": _op_family(retarget_vector),
    "asf": _op_family(asf_vector),
    "metrics": _op_family(metrics_vector),
    "bones": _op_family(bones_vector),
    "envelope": _op_family(envelope_vector),
    "guard": _op_family(guard_vector),
    "foot_plant": _op_family(foot_plant_vector),
    "readout": readout_vector,
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
