"""The `readout` family of shared test vectors: the stage's read-out for real predictions.

For the served WAT RNN model (the model the site opens on), a few histories from the test split whose
clip holds ground truth after the history: the Python predictor's K futures (export/sample) and the
evaluation's best-of-K and per-sample ADE and FDE of them (export/eval/metrics.py ade_fde and
ade_fde_per_sample), root-relative and in the world frame. The browser's read-out
(web/src/ui/readout.ts, on web/src/metrics/readout.ts) must give the same numbers for the same
history, request and seed (tests/web/readout-vector.test.ts).

Data-driven: the windows come from the clip index (its `default` history first when it has one, then
the test ranges with the most frames after the history), never from clip names, so the family can be
regenerated unchanged after the data or the models change. The horizon is the model's T_max, or the
longest ground truth a test range holds when none holds that much (then the file says so). Each case keeps
every stop decision 1.5 x the tolerance of its own Eq. 8 curve (export/tolerance.py keeps_its_stop_margin), as
the end-to-end vector does, so a last-bit difference between machines cannot change a length.
"""
from __future__ import annotations

import json

import numpy as np

MODEL_METHOD = "wat"          # the served model: the first manifest entry of this method (WAT RNN)
CASES = 3                     # windows, at most
KS = (3, 2, 2)               # K per case, in turn: every sample's stops must keep the margin
FIRST_SEED = 1
SEEDS = 3000
MIN_HORIZON = 15              # frames: a window with less ground truth after its history is not used


def _windows(index: dict, n: int, horizon: int) -> list[tuple[dict, int, int]]:
    """(clip entry, history start, ground-truth frames) for test windows: the index's default first
    (when it lies in a test range), then each other clip's longest test range, most ground truth first."""
    default: list[tuple[dict, int, int]] = []
    wanted = index.get("default")
    for c in index["clips"]:
        if wanted and c["name"] == wanted["clip"]:
            s = int(wanted["start"])
            default += [(c, s, min(horizon, b - s - n)) for a, b in c["test"] if a <= s and s + n + MIN_HORIZON <= b][:1]
    others = []
    for c in index["clips"]:
        if any(d[0]["name"] == c["name"] for d in default):
            continue
        ranges = [(b - a - n, a) for a, b in c["test"] if b - a - n >= MIN_HORIZON]
        if ranges:
            frames, a = max(ranges)
            others.append((c, a, min(horizon, frames)))
    others.sort(key=lambda w: (-w[2], w[0]["name"]))
    return default + others


def _errors(futures: np.ndarray, truth: np.ndarray, root_relative: bool) -> dict:
    from .eval import metrics as M
    ade_k, fde_k = M.ade_fde_per_sample(futures, truth, root_relative=root_relative)
    ade, fde = M.ade_fde(futures, truth, root_relative=root_relative)
    return {"ade": ade, "fde": fde, "ade_per_sample": ade_k.tolist(), "fde_per_sample": fde_k.tolist()}


def readout_vector(models_dir=None, clips_dir=None) -> dict:
    from .data.clip_json import read_clip
    from .manifest import read_manifest
    from .paths import CLIPS_DIR, MODELS_DIR
    from .sample.predictor import load_predictor
    from .sample.request import Request
    from .tolerance import about, float32_floor, float_gap, keeps_its_stop_margin

    models_dir, clips_dir = models_dir or MODELS_DIR, clips_dir or CLIPS_DIR
    manifest = read_manifest(models_dir / "manifest.json")
    entry = next((m for m in manifest["models"] if m["method"] == MODEL_METHOD), None)
    if entry is None:
        raise ValueError(f"the manifest serves no model of method {MODEL_METHOD}")
    index = json.loads((clips_dir / "index.json").read_text())
    n, t_max = entry["params"]["history_frames"], entry["params"]["future_frames"]
    windows = _windows(index, n, t_max)[:CASES]
    if not windows:
        raise ValueError(f"no test range holds {n} history frames and {MIN_HORIZON} frames of ground truth")
    predictor = load_predictor(entry["id"], models_dir)
    wide = load_predictor(entry["id"], models_dir, precision="float64")
    actions = manifest["actions"]

    def keeps(pred, history, req) -> bool:
        # as export/vectors.py's e2e cases: each case keeps the stop margin its own Eq. 8 curve asks for
        if pred.margins and min(pred.margins) < 1e-6:
            return False
        return keeps_its_stop_margin(pred, wide.predict(history, req))

    cases = []
    for i, (clip, start, horizon) in enumerate(windows):
        positions = read_clip(clips_dir / clip["file"]).positions
        history = positions[start:start + n].astype(np.float32)
        truth = positions[start + n:start + n + horizon].astype(np.float32)
        action = clip["action"] if clip["action"] in actions else actions[0]
        for seed in range(FIRST_SEED, FIRST_SEED + SEEDS):
            req = Request(k=KS[i % len(KS)], seed=seed, actions=[action], horizon_frames=horizon)
            pred = predictor.predict(history, req)
            if keeps(pred, history, req):
                break
        else:
            raise ValueError(f"no seed gives {clip['name']}@{start} stops that keep the margin their curves ask for")
        cases.append(readout_record(entry, clip["name"], start, horizon, horizon == t_max, history, truth, req, pred))

    def measured(cases: list[dict]) -> float:
        return max(max(float_gap(c, replay(c, wide, entry)), float32_floor(c)) for c in cases)

    gap = measured(cases)
    short = [c for c in cases if not c["covers_t_max"]]
    return {"about": about(
        f"the stage's read-out for {entry['label']} ({entry['id']}): test-split histories (the clip index's default "
        "first), the Python predictor's K futures with horizon_frames fixed to the ground truth used, and "
        "export/eval/metrics.py's best-of-K and per-sample ADE and FDE (whole-pose L2; root-relative and world frame, "
        "futures cut to the truth). Lengths exactly; the ADE/FDE floats within this file's tolerance plus the e2e "
        "vector's tolerance for the model (the futures come from native onnxruntime here, from wasm in the browser). "
        + (f"{len(short)} of {len(cases)} windows hold less than T_max = {t_max} frames of ground truth "
           "(horizon_frames says how many they hold)." if short else f"Every window holds T_max = {t_max} frames."),
        {entry["id"]: gap}), "margin": "per case: 1.5 x the tolerance of its own Eq. 8 curve", "cases": cases}


def readout_record(entry: dict, clip: str, start: int, horizon: int, covers: bool, history: np.ndarray,
                   truth: np.ndarray, req, pred) -> dict:
    """What a read-out case stores (also what a replay of it is compared on)."""
    from .vectors_record import float32_list
    futures = np.asarray(pred.futures, dtype=np.float32)
    return {"model": entry["id"], "model_hash": entry["hash"], "clip": clip, "start": start,
            "horizon_frames": horizon, "covers_t_max": covers,
            "history": float32_list(history), "truth": float32_list(truth), "request": req.to_json(),
            "lengths": [int(x) for x in pred.lengths], "min_margin": min(pred.margins) if pred.margins else None,
            "root_relative": _errors(futures, truth, root_relative=True),
            "world": _errors(futures, truth, root_relative=False)}


def replay(case: dict, predictor, entry: dict) -> dict:
    """The committed case's history and request through this predictor (never re-selected)."""
    from .sample.request import Request
    history = np.asarray(case["history"], dtype=np.float32)
    truth = np.asarray(case["truth"], dtype=np.float32)
    req = Request.from_json(case["request"])
    return readout_record(entry, case["clip"], case["start"], case["horizon_frames"], case["covers_t_max"], history,
                          truth, req, predictor.predict(history, req))
