"""The odd histories of issue 30 through every served model, as a markdown table for the issue's note:
for each odd history (reflected, frozen, 0.5x, 2x, 3x, scaled 0.8 and 1.25, raised 0.5 m) and model,
whether it was warned or refused, with what words, and the first-frame jump ratio (the first predicted
step over the history's last step, metrics.first_frame_jump; "-" when the history does not move).
Held-out walks of the served clips, 40 frames each; the tests (tests/export/test_odd_histories.py)
build the same histories from here. Run: python -m export.eval.odd_table [--models DIR]
"""
from __future__ import annotations

import json

import numpy as np

from ..data.clip_json import read_clip
from ..manifest import read_manifest
from ..paths import CLIPS_DIR, MODELS_DIR
from .metrics import first_frame_jump

FRAMES = 40
KINDS = ("reflected", "frozen", "speed 0.5x", "speed 2x", "speed 3x", "scale 0.8", "scale 1.25", "raised 0.5 m")
# the warning each kind must give (issue 30, items 1-4); raised: the root height (item 5's refusal order)
EXPECTED = {"reflected": "handedness", "frozen": "motion", "speed 0.5x": "tempo", "speed 2x": "tempo",
            "speed 3x": "tempo", "scale 0.8": "body_scale", "scale 1.25": "body_scale", "raised 0.5 m": "root_height"}


def held_out_walks(count: int = 3) -> list[np.ndarray]:
    """World positions of the served held-out walks (whole takes), the first `count`."""
    index = json.loads((CLIPS_DIR / "index.json").read_text())
    names = [c["name"] for c in index["clips"] if c["role"] == "test" and c["action"] == "walk"]
    return [read_clip(CLIPS_DIR / f"{n}.json").positions for n in names[:count]]


def retime(p: np.ndarray, factor: float) -> np.ndarray:
    """A motion played `factor` times as fast (Catmull-Rom between its frames)."""
    out = []
    for t in np.arange(0, len(p) - 1, factor):
        i, u = int(t), t - int(t)
        p0, p1, p2, p3 = p[max(i - 1, 0)], p[i], p[min(i + 1, len(p) - 1)], p[min(i + 2, len(p) - 1)]
        out.append(0.5 * (2 * p1 + (p2 - p0) * u + (2 * p0 - 5 * p1 + 4 * p2 - p3) * u * u
                          + (3 * p1 - p0 - 3 * p2 + p3) * u ** 3))
    return np.asarray(out)


def odd_history(walk: np.ndarray, kind: str, start: int = 0) -> np.ndarray:
    """FRAMES frames of a held-out walk, changed as `kind` says (world positions)."""
    w = np.asarray(walk, dtype=np.float64)
    base = w[start:start + FRAMES]
    if kind == "reflected":           # through the x = 0 plane, the left and right labels kept
        return base * np.array([-1.0, 1.0, 1.0])
    if kind == "frozen":
        return np.repeat(base[-1:], FRAMES, axis=0)
    if kind.startswith("speed"):
        factor = float(kind.split()[1].rstrip("x"))
        played = retime(w[start:], factor)
        if len(played) < FRAMES:
            played = np.concatenate([played, retime(w, factor)])   # a short take: play it again
        return played[:FRAMES]
    if kind.startswith("scale"):
        return base * float(kind.split()[1])
    if kind == "raised 0.5 m":
        return base + np.array([0.0, 0.5, 0.0])
    raise ValueError(f"unknown odd history {kind!r}; known: {', '.join(KINDS)}")


def request_for(entry: dict, manifest: dict):
    from ..sample.request import Request
    ids = {c["id"] for c in entry["controls"]}
    return Request(k=3 if "k" in ids else 1, seed=0, actions=["walk"] if "actions" in ids else [],
                   horizon_frames=30 if "horizon" in ids or "actions" in ids else None)


def run(kind: str, walk: np.ndarray, predictor, entry: dict, manifest: dict) -> dict:
    """One odd history through one predictor: refused or not, the warnings' quantities, the jump ratio."""
    from ..sample.request import PredictError
    history = odd_history(walk, kind)
    try:
        pred = predictor.predict(history, request_for(entry, manifest))
    except PredictError as e:
        return {"refused": True, "message": str(e), "quantities": [], "ratio": None}
    ratios = []
    for i in range(len(pred.futures)):
        jump, step = first_frame_jump(history, pred.futures[i])
        ratios.append(jump / step if step > 1e-6 else np.nan)
    return {"refused": False, "message": "", "quantities": [w["quantity"] for w in pred.warnings],
            "ratio": float(np.nanmax(ratios)) if np.isfinite(ratios).any() else None,
            "jump": float(max(first_frame_jump(history, f)[0] for f in pred.futures))}


SHORT = {"handedness": "left/right swapped", "motion": "does not move", "tempo": "tempo", "body_scale": "body size",
         "root_height": "root height", "root_speed": "root speed", "joint_speed": "joint speed",
         "scale": "size", "bone_error": "bones"}


def words(r: dict) -> str:
    if r["refused"]:
        m = r["message"]
        return "refused: " + (m[:70] + "..." if len(m) > 70 else m)
    return ("warned: " + ", ".join(SHORT.get(q, q) for q in r["quantities"])) if r["quantities"] else "silent"


def main(argv: list[str] | None = None) -> None:
    import argparse
    from pathlib import Path
    from ..sample.predictor import load_predictor
    ap = argparse.ArgumentParser(prog="python -m export.eval.odd_table", description=__doc__.split("\n")[0])
    ap.add_argument("--models", type=Path, default=MODELS_DIR, help="a models directory (default: public/models)")
    models_dir = ap.parse_args(argv).models
    manifest = read_manifest(models_dir / "manifest.json")
    walk = held_out_walks(1)[0]
    models = manifest["models"]
    predictors = {e["id"]: load_predictor(e["id"], models_dir) for e in models}
    print("| odd history | " + " | ".join(e["id"] for e in models) + " |")
    print("|---|" + "---|" * len(models))
    for kind in KINDS:
        cells = []
        for e in models:
            r = run(kind, walk, predictors[e["id"]], e, manifest)
            ratio = "-" if r.get("ratio") is None else f"{r['ratio']:.2f}x"
            cells.append(f"{words(r)} ({ratio})" if not r["refused"] else words(r))
        print(f"| {kind} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
