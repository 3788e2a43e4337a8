"""Strips of frames: look at the motion, not only at a table of ADEs.

For each served model (through the same Python predictor the evaluation uses), held-out walk, run, jump
and dance histories of people the models never saw, and the futures' poses at 0, 1, 2 and 3 s drawn from
the side of the history's travel (grey: the truth, colours: K = 5 samples), with a panel of each future's
horizontal root speed over time; for models that take an action sequence, a walk history asked for
walk -> jump -> kick as well. Beside each case, numbers read from the same futures: root speed per second
(ops in eval/realism/speed.py), the hip's vertical range (eval/realism/jump_height.py) and the median foot
skating speed (eval/realism/skating.py), the truth's beside the samples'.

`python -m export strips` writes docs/strips/<model>.png and docs/strips/strips.json.
"""
from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .data.skeleton import SKELETON
from .eval.harness import controls_of
from .eval.realism.jump_height import hip_vertical_range
from .eval.realism.skating import contact_speeds, median_contact_speed
from .eval.realism.speed import root_speed_per_second
from .manifest import read_manifest
from .paths import MODELS_DIR, ROOT
from .sample.request import PredictError, Request

OUT_DIR = ROOT / "docs" / "strips"
FPS = 30
SECONDS = (0, 1, 2, 3)
K = 5


@dataclass(frozen=True)
class Case:
    name: str          # what the strip shows
    take: str          # a held-out take of the default data
    action: str        # the action asked for (WAT) and the take's own
    present: float     # where the history ends, as a share of the take's held-out frames
    sequence: tuple[str, ...] = ()


# One take per action group from the held-out people (export/data/split.TEST_PEOPLE): the walk the issue
# measured (cmu_08_03), the longest held-out run, a jump take, salsa and ballet. The present sits where
# the person is already moving (a third or a fifth in), so a frozen future is the model's, not the take's.
CASES = (
    Case("walk", "cmu_08_03", "walk", 0.2),
    Case("run", "cmu_49_04", "run", 0.25),
    Case("jump", "cmu_13_13", "jump", 0.2),
    Case("dance (salsa)", "cmu_61_13", "dance", 0.3),
    Case("dance (ballet)", "cmu_49_09", "dance", 0.3),
    Case("walk -> jump -> kick", "cmu_08_03", "walk", 0.2, ("walk", "jump", "kick")),
)


def _heldout_takes(names: set[str]) -> dict[str, np.ndarray]:
    """World positions of the held-out part of each named take (its first held-out range)."""
    from .data.sources import default_source
    out = {}
    for c in default_source().clips():
        if c.name in names and c.split.test:
            a, b = c.split.test[0]
            out[c.name] = c.positions[a:b]
    missing = names - set(out)
    if missing:
        raise ValueError(f"no held-out part in the default data for {sorted(missing)}")
    return out


def _measures(future: np.ndarray, history: np.ndarray) -> dict:
    """Per-second root speed (m/s), hip vertical range (m) and median skating (m/s) of one motion."""
    speeds = root_speed_per_second(future, history)
    contact = contact_speeds(future)   # a future whose feet never touch the floor has no skating to read
    return {"root_speed": [round(float(s), 3) for s in speeds],
            "hip_range": round(float(hip_vertical_range(future)), 3),
            "skate": round(float(median_contact_speed(contact)), 3) if len(contact) else None}


def predict_case(predictor, entry: dict, case: Case, motion: np.ndarray) -> dict:
    n = int(entry["params"]["history_frames"])
    ids = controls_of(entry)
    present = max(n, int(case.present * len(motion)))
    history, truth = motion[present - n:present], motion[present:present + FPS * SECONDS[-1]]
    horizon = FPS * SECONDS[-1] if not case.sequence else None
    if case.sequence and "actions" not in ids:
        return {"skipped": "takes no action sequence"}
    actions = list(case.sequence) if case.sequence else ([case.action] if "actions" in ids else [])
    req = Request(k=K if "k" in ids else 1, seed=0, actions=actions, horizon_frames=horizon)
    try:
        pred = predictor.predict(history, req)
    except PredictError as e:
        return {"refused": str(e)}
    futures = np.asarray(pred.futures, np.float64)
    out = {"history": history, "truth": truth if not case.sequence else None, "futures": futures,
           "lengths": [int(x) for x in pred.lengths],
           "samples": [_measures(f, history) for f in futures],
           "truth_measures": _measures(truth, history) if not case.sequence and len(truth) > 1 else None}
    if case.sequence:   # the hip's range inside each sample's jump segment
        out["jump_segment_hip_range"] = [
            round(float(hip_vertical_range(f, sg["start"], sg["start"] + max(sg["length"], 1))), 3)
            for f, s in zip(futures, pred.samples) for sg in s["segments"] if sg["action"] == "jump"]
    return out


def _side_view(history: np.ndarray):
    """Project onto the vertical plane along the history's travel (x: metres along it from the present)."""
    travel = history[-1, 0, [0, 2]] - history[0, 0, [0, 2]]
    u = travel / np.linalg.norm(travel) if np.linalg.norm(travel) > 0.05 else np.array([1.0, 0.0])
    origin = history[-1, 0, [0, 2]]
    return lambda p: np.stack([(p[..., [0, 2]] - origin) @ u, p[..., 1]], -1)


def _draw_pose(ax, pose2d: np.ndarray, color, lw: float) -> None:
    for j, pj in enumerate(SKELETON.parents):
        if pj >= 0:
            ax.plot(*zip(pose2d[j], pose2d[pj]), color=color, lw=lw)


def draw(model_title: str, results: list[tuple[Case, dict]], path: Path) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    cols = len(SECONDS) + 1
    fig, axes = plt.subplots(len(results), cols, figsize=(2.6 * cols, 2.5 * len(results)), squeeze=False)
    for r, (case, res) in enumerate(results):
        if "futures" not in res:
            for ax in axes[r]:
                ax.axis("off")
            axes[r, 0].set_title(f"{case.name}: {res.get('refused') or res.get('skipped')}"[:70], fontsize=7, loc="left")
            continue
        fut, truth, hist = res["futures"], res["truth"], res["history"]
        proj = _side_view(hist)
        times = SECONDS if not case.sequence else tuple(np.linspace(0, (fut.shape[1] - 1) / FPS, len(SECONDS)).round(1))
        for c, sec in enumerate(times):
            ax, t = axes[r, c], min(int(round(sec * FPS)), fut.shape[1] - 1)
            if truth is not None and t < len(truth):
                _draw_pose(ax, proj(truth[t]), "0.65", 2.2)
            for s in range(len(fut)):
                _draw_pose(ax, proj(fut[s, t]), f"C{s}", 1.0)
            ax.axhline(0, color="k", lw=0.5)
            centre = float(proj(fut[:, t, 0])[:, 0].mean())
            ax.set_xlim(centre - 1.2, centre + 1.2)
            ax.set_ylim(-0.1, 2.1)
            ax.set_aspect("equal")
            ax.tick_params(labelsize=5)
            label = case.name if c == 0 else ""
            ax.set_title(f"{label} {case.take} t={sec:g} s".strip(), fontsize=7)
        ax = axes[r, -1]   # horizontal root speed per frame: a freezing future falls to 0
        speed = lambda m: np.linalg.norm(np.diff(np.concatenate([hist[-1:], m])[:, 0, [0, 2]], axis=0), axis=-1) * FPS
        if truth is not None:
            ax.plot(np.arange(len(truth)) / FPS, speed(truth), color="0.5", lw=2)
        for s in range(len(fut)):
            ax.plot(np.arange(fut.shape[1]) / FPS, speed(fut[s]), color=f"C{s}", lw=0.8)
        ax.set_title("root speed (m/s)", fontsize=7)
        ax.tick_params(labelsize=5)
    fig.suptitle(f"{model_title}: held-out people (grey: truth, colours: {K} samples)", fontsize=9)
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=70)
    plt.close(fig)


def run(models: list[str] | None = None, out_dir: Path = OUT_DIR) -> dict:
    from .sample.predictor import load_predictor
    manifest = read_manifest(MODELS_DIR / "manifest.json")
    entries = [e for e in manifest["models"] if (models is None and e["method"] != "zero_velocity") or
               (models is not None and e["id"] in models)]
    takes = _heldout_takes({c.take for c in CASES})
    summary = {}
    for entry in entries:
        p = load_predictor(entry["id"])
        results = [(c, predict_case(p, entry, c, takes[c.take])) for c in CASES]
        draw(entry.get("label", entry["id"]), results, out_dir / f"{entry['id']}.png")
        summary[entry["id"]] = {c.name: {k: v for k, v in res.items() if k not in ("history", "truth", "futures")}
                                for c, res in results}
        print(f"wrote {out_dir / (entry['id'] + '.png')}")
    # `--model` redraws some models: the others' entries stay, as their pictures do.
    path = out_dir / "strips.json"
    kept = json.loads(path.read_text()) if models is not None and path.exists() else {}
    path.write_text(json.dumps({**kept, **summary}, indent=1) + "\n")
    return summary
