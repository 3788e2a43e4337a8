"""The evaluation runner: every row of rows.py through every table of configs/eval.json.

Models predict through the Python predictor (export/sample/predictor.py), the same code path
the end-to-end vectors tie to the browser. Each (row, table) is run for every training seed
× sampling seed; each run gives one value per metric, and a table cell is mean ± std over runs.
"""
from __future__ import annotations

import importlib
import json
import math
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import torch

from ..config import load_config
from ..data.clip import Clip
from ..data.sources import FPS
from ..data.windows import windows
from ..manifest import read_manifest
from ..methods import METHODS, method_for
from ..paths import CONFIGS_DIR, MODELS_DIR, RUNS_DIR
from ..sample.predictor import PREDICTORS, predictor_for
from ..sample.request import PredictError, Request
from . import metrics as M
from .classifiers import Classifier, snippet_accuracy, snippets, split_snippets, train_classifier
from .fid import FeatureSpace
from .rows import ROWS, Row
from .stats import summarise

SEEDS_DIR = RUNS_DIR / "seeds"

# Columns: id -> (label, unit, better, needs ground truth). MPJPE in mm as Keyposes reports it;
# WAT's pose-vector distances in metres.
COLUMNS: dict[str, tuple[str, str, str, bool]] = {
    "ade": ("ADE (best of K)", "m", "lower", True),
    "ade_w": ("ADE after DTW", "m", "lower", True),
    "mpjpe_1s_ave": ("MPJPE 1 s ave", "mm", "lower", True),
    "mpjpe_1s_best": ("MPJPE 1 s best", "mm", "lower", True),
    "mpjpe_h_ave": ("MPJPE horizon ave", "mm", "lower", True),
    "mpjpe_h_best": ("MPJPE horizon best", "mm", "lower", True),
    "div": ("Diversity", "m", "higher", False),
    "div_w": ("Diversity after DTW", "m", "higher", False),
    "acc_pose": ("Accuracy (pose GRU)", "%", "higher", False),     # mean over actions (balanced)
    "acc_moac": ("Accuracy (MOAC)", "%", "higher", False),
    "fid_tr": ("FID vs train", "", "lower", False),
    "fid_te": ("FID vs test", "", "lower", False),
    "pskl_gt_pred": ("PSKL gt→pred", "", "lower", False),
    "pskl_pred_gt": ("PSKL pred→gt", "", "lower", False),
    "smooth": ("Transition smoothness (Eq. 4)", "mm²", "lower", False),
    "speed": ("Joint speed, last second", "m/s", "", False),
    "length": ("Mean length", "frames", "", False),
    "stopped": ("Segments stopped (Eq. 8)", "%", "", False),   # variable-length methods only
}


@dataclass
class EvalWindow:
    clip: str
    action: str
    history: np.ndarray            # [H, J, 3]
    truth: np.ndarray | None       # [T, J, 3] when the table has frame-wise ground truth


@dataclass
class Sample:
    """One prediction: K futures for one window and one requested action."""
    window: EvalWindow
    action: str
    futures: np.ndarray            # [K, T, J, 3]
    lengths: np.ndarray            # [K]
    segments: list[list[dict]] = field(default_factory=list)


@dataclass
class ModelRun:
    """A row's trained model at one training seed."""
    seed: int
    predictor: object
    entry: dict
    served: bool


TABLE_KEYS = ("id", "title", "about", "source", "history_frames", "horizon_frames", "stride", "truth")


def load_eval_config(path: str | Path | None = None) -> dict:
    """configs/eval.json (or `path`), checked: a missing or wrong field is named in a ValueError."""
    path = Path(path or CONFIGS_DIR / "eval.json")
    try:
        cfg = json.loads(path.read_text())
    except OSError as e:
        raise FileNotFoundError(f"{path}: evaluation config not found") from e
    except json.JSONDecodeError as e:
        raise ValueError(f"{path}: not valid JSON ({e})") from e
    for key in ("k", "training_seeds", "sampling_seeds", "noise_sigma", "classifier", "snippet_stride", "fid",
                "length_bin_frames", "tables"):
        if key not in cfg:
            raise ValueError(f"{path}: evaluation config is missing '{key}'")
    for i, table in enumerate(cfg["tables"]):
        missing = [k for k in TABLE_KEYS if k not in table]
        if missing:
            raise ValueError(f"{path}: table {table.get('id', i)} is missing {missing}")
        if table["source"] not in ("test", "walker", "train"):
            raise ValueError(f"{path}: table {table['id']}: source must be test, walker or train, got {table['source']!r}")
        if table["history_frames"] != "model" and not (isinstance(table["history_frames"], int) and table["history_frames"] > 0):
            raise ValueError(f"{path}: table {table['id']}: history_frames must be a positive integer or \"model\"")
        if table["history_frames"] == "model" and table["truth"]:
            raise ValueError(f"{path}: table {table['id']}: a table with ground truth needs one history length")
    return cfg


def per_row_history(table: dict) -> bool:
    """A table without frame-wise ground truth may cut each row's windows with that model's own
    history length ("history_frames": "model"), so models with long histories are not left out."""
    return table["history_frames"] == "model"


def table_windows(clips: list[Clip], table: dict, history: int | None = None) -> list[EvalWindow]:
    """The table's windows: history + horizon inside the test parts (or one frame past the history
    when the table has no frame-wise ground truth), from the source the table names."""
    h, t = int(history or table["history_frames"]), int(table["horizon_frames"])
    part = "train" if table["source"] == "train" else "test"
    chosen = [c for c in clips if table["source"] != "walker" or c.split.role == "test"]
    length = h + (t if table["truth"] else 1)
    out = []
    for w in windows(chosen, part, length, h, stride=int(table["stride"])):
        out.append(EvalWindow(w.clip, w.action, w.positions[:h],
                              w.positions[h:h + t] if table["truth"] else None))
    return out


# --- rows -----------------------------------------------------------------------------------

def served_configs() -> set[str]:
    return set(json.loads((CONFIGS_DIR / "site.json").read_text())["models"])


def row_config(row: Row) -> tuple[dict | None, str]:
    """The row's config when its method and its predictor both exist, else (None, why not)."""
    path = CONFIGS_DIR / row.config
    if not path.exists():
        return None, f"configs/{row.config} does not exist yet"
    cfg = load_config(path)
    for registry, what in ((METHODS, "method"), (PREDICTORS, "predictor")):
        target = registry.get(cfg["method"])
        if target is None:
            return None, f"no {what} registered for method {cfg['method']!r}"
        module = target.split(":")[0]
        try:
            importlib.import_module(module)
        except ModuleNotFoundError as e:
            return None, f"the {what} {module} is not written yet ({e.name} missing)"
        except Exception as e:   # a module mid-edit must not stop the other rows
            return None, f"the {what} {module} cannot be imported: {type(e).__name__}: {e}"
    return cfg, ""


def load_row_models(row: Row, seeds: list[int], models_dir: Path, seeds_root: Path = SEEDS_DIR
                    ) -> tuple[list[ModelRun], list[str]]:
    """The row's trained models per training seed, and notes on what is missing and why."""
    cfg, why = row_config(row)
    if cfg is None:
        return [], [why]
    notes = []
    if not method_for(cfg).trainable:
        seeds = seeds[:1]   # nothing is trained, so every training seed gives the same model
        notes.append("not trained: one model stands for every training seed")
    runs, missing = [], []
    for seed in seeds:
        served = seed == 0 and row.config in served_configs()
        directory = Path(models_dir) if served else seeds_root / cfg["id"] / f"seed{seed}"
        manifest_path = directory / "manifest.json"
        entry = None
        if manifest_path.exists():
            manifest = read_manifest(manifest_path)
            entry = next((m for m in manifest["models"] if m["id"] == cfg["id"]), None)
        if entry is None:
            missing.append(seed)
            continue
        runs.append(ModelRun(seed, predictor_for(entry, manifest, directory), entry, served))
    if missing:
        notes.append(f"training seeds {missing} not found (served seed 0 comes from `make models`, "
                     "the others from `make results`)")
    return runs, notes


def max_horizon(entry: dict) -> int:
    spec = next((c for c in entry["controls"] if c["id"] == "horizon"), None)
    return round(spec["max"] * FPS) if spec else int(entry["params"]["future_frames"])


def controls_of(entry: dict) -> dict[str, dict]:
    return {c["id"]: c for c in entry["controls"]}


def request_seed(sampling_seed: int, window: int, action: int) -> int:
    # Distinct, reproducible draws for every window and requested action of a sampling seed.
    return (sampling_seed * 1_000_003 + window * 97 + action) % 2 ** 32


def requested_actions(table: dict, actions: list[str], window: int, own: str) -> list[str]:
    """The window's own action, or (tables with "actions": "all") every action, or a rotating subset of
    `actions_per_window` of them, so that every action is requested equally often over the windows."""
    if table.get("actions") != "all":
        return [own]
    n = int(table.get("actions_per_window", len(actions)))
    return [actions[(window * n + j) % len(actions)] for j in range(min(n, len(actions)))]


def predict_model(run: ModelRun, row: Row, table: dict, wins: list[EvalWindow], actions: list[str],
                  k: int, sampling_seed: int) -> tuple[list[Sample], list[str]]:
    """K futures per window (and per requested action) through the Python predictor."""
    n = int(run.entry["params"]["history_frames"])
    t = int(table["horizon_frames"])
    ctl = controls_of(run.entry)
    conditioned = "actions" in ctl
    out, refused = [], []
    for i, w in enumerate(wins):
        requested = requested_actions(table, actions, i, w.action)
        for a in requested:
            req = Request(k=k if "k" in ctl else 1, seed=request_seed(sampling_seed, i, actions.index(a)),
                          actions=[a] if conditioned else [], horizon_frames=t, controls=dict(row.controls))
            try:
                pred = run.predictor.predict(w.history[-n:], req)
            except PredictError as e:
                refused.append(str(e))
                continue
            if pred.futures.shape[1] < t:   # the contract pads stopped samples to the horizon
                refused.append(f"returned {pred.futures.shape[1]} frames for a horizon of {t}")
                continue
            lengths = np.minimum(np.asarray(pred.lengths), t)
            out.append(Sample(w, a, np.asarray(pred.futures, dtype=np.float64)[:, :t], lengths,
                              [s.get("segments", []) for s in pred.samples]))
    notes = [f"{len(refused)} of {len(refused) + len(out)} predictions refused, e.g. {refused[0]!r}"] if refused else []
    return out, notes


def predict_truth(row: Row, wins: list[EvalWindow], k: int, sigma: float, sampling_seed: int) -> list[Sample]:
    """The oracle (the ground truth itself) and the noise sanity row (K noisy copies of it)."""
    out = []
    for i, w in enumerate(wins):
        t = len(w.truth)
        if row.kind == "oracle":
            fut = w.truth[None]
        else:
            rng = np.random.default_rng([sampling_seed, i])
            fut = w.truth[None] + rng.normal(0.0, sigma, (k, *w.truth.shape))
        out.append(Sample(w, w.action, fut, np.full(len(fut), t)))
    return out


# --- metrics over a run -----------------------------------------------------------------------

@dataclass
class References:
    """Snippets of real motion the set-level metrics compare with, per action."""
    train: dict[str, np.ndarray]
    test: dict[str, np.ndarray]


def references(clips: list[Clip], frames: int) -> References:
    def by_action(part: str, stride: int) -> dict[str, np.ndarray]:
        x, acts, _ = split_snippets(clips, part, frames, stride)
        return {a: x[[i for i, b in enumerate(acts) if b == a]] for a in sorted(set(acts))}
    return References(by_action("train", 2), by_action("test", 1))


def run_metrics(samples: list[Sample], table: dict, classifiers: dict[str, Classifier],
                space: FeatureSpace, pose_refs: dict[str, dict[str, np.ndarray]], refs: References,
                cfg: dict, interval: bool) -> tuple[dict[str, float], dict, dict[str, list[int]]]:
    """One run's value per column, FID intervals (when asked) and predicted lengths per action."""
    t = int(table["horizon_frames"])
    stride = int(cfg["snippet_stride"])
    frames = classifiers["pose_gru"].frames
    vals: dict[str, list[float]] = {c: [] for c in COLUMNS}
    lengths: dict[str, list[int]] = {}
    for s in samples:
        k = len(s.futures)
        trimmed = [f[:max(int(n), 2)] for f, n in zip(s.futures, s.lengths)]
        dtw = bool(table.get("dtw", True))
        if s.window.truth is not None:
            truth = s.window.truth
            vals["ade"].append(M.ade(s.futures, truth))
            if dtw:
                vals["ade_w"].append(M.ade_dtw(trimmed, truth))
            if t >= FPS:
                ave, best = M.mpjpe_at(s.futures, truth, int(FPS) - 1)
                vals["mpjpe_1s_ave"].append(ave * 1000)
                vals["mpjpe_1s_best"].append(best * 1000)
            if t > FPS:
                ave, best = M.mpjpe_at(s.futures, truth, t - 1)
                vals["mpjpe_h_ave"].append(ave * 1000)
                vals["mpjpe_h_best"].append(best * 1000)
        vals["div"].append(M.diversity(s.futures))
        if dtw:
            vals["div_w"].append(M.diversity_dtw(trimmed) if k > 1 else 0.0)
        if len(s.window.history) >= M.L_FRAMES and t >= M.L_FRAMES:
            vals["smooth"] += [M.transition_smoothness(s.window.history, f) * 1e6 for f in s.futures]
        if t >= 2:
            vals["speed"] += [M.joint_speed(f, FPS, min(int(FPS), t - 1)) for f in s.futures]
        vals["length"] += [float(n) for n in s.lengths]
        for j, n in enumerate(s.lengths):
            segs = s.segments[j] if j < len(s.segments) and s.segments[j] else [{"length": int(n)}]
            for seg in segs:
                lengths.setdefault(seg.get("action") or s.action, []).append(int(seg["length"]))
                if "stopped" in seg:
                    vals["stopped"].append(100.0 * bool(seg["stopped"]))
    out = {c: float(np.mean(v)) for c, v in vals.items() if v}
    intervals = {}
    if t >= frames and samples:
        motions = [f for s in samples for f in s.futures]
        targets = [s.action for s in samples for _ in s.futures]
        for kind, clf in classifiers.items():
            labels, feats = clf.classify(motions, stride)
            truth_idx = np.array([clf.actions.index(a) for a in targets])
            out[f"acc_{'pose' if kind == 'pose_gru' else 'moac'}"] = 100.0 * M.balanced_accuracy(labels, truth_idx)
            if kind == "pose_gru":
                for part in ("train",) if table["source"] == "train" else ("train", "test"):
                    ref = pose_refs[part]
                    gen = [f for f, a in zip(feats, targets) if a in ref]
                    ref_rows = [ref[a] for a in sorted({a for a in targets if a in ref})]
                    if gen and ref_rows and sum(len(g) for g in gen) > 2:
                        g, r = np.concatenate(gen), np.concatenate(ref_rows)
                        col = "fid_tr" if part == "train" else "fid_te"
                        if interval:
                            value, lo, hi = space.fid_interval(g, r, int(cfg["fid"]["bootstrap"]), seed=0)
                            intervals[col] = [lo, hi]
                        else:
                            value = space.fid(g, r)
                        out[col] = value
        # PSKL per action against that action's real snippets, then averaged over actions.
        ref = refs.train if table["source"] == "train" else refs.test
        gp, pg = [], []
        for a in sorted(set(targets)):
            if a not in ref or len(ref[a]) == 0:
                continue
            gen = np.concatenate([snippets(f, frames, stride) for f, b in zip(motions, targets) if b == a])
            x, y = M.pskl(ref[a], gen)
            gp.append(x)
            pg.append(y)
        if gp:
            out["pskl_gt_pred"], out["pskl_pred_gt"] = float(np.mean(gp)), float(np.mean(pg))
    return out, intervals, lengths


# --- the whole evaluation ---------------------------------------------------------------------

def train_classifiers(clips: list[Clip], cfg: dict, cache_dir: Path | None) -> tuple[dict, dict]:
    """Pose GRU and MOAC (plus the shuffled-label pose GRU of the sanity rows) and their own accuracies."""
    ccfg = cfg["classifier"]
    seed = int(ccfg["seed"])
    frames = int(ccfg["snippet_frames"])
    report = {}
    trained = {}
    xtr, atr, _ = split_snippets(clips, "train", frames, int(ccfg["stride"]))
    xte, ate, cte = split_snippets(clips, "test", frames, 1)
    for kind, shuffled in (("pose_gru", False), ("moac", False), ("pose_gru", True)):
        start = time.time()
        clf = train_classifier(kind, clips, ccfg, seed, shuffled=shuffled, cache_dir=cache_dir)
        groups = {}
        predicted = clf.snippet_outputs(xte)[0].argmax(1) if len(xte) else np.zeros(0, dtype=int)
        for name in sorted({"walker" if c.startswith("walker") else c for c in cte}):
            idx = [i for i, c in enumerate(cte) if (c.startswith("walker") if name == "walker" else c == name)]
            labels, counts = np.unique(predicted[idx], return_counts=True)
            groups[name] = {"accuracy": 100 * snippet_accuracy(clf, xte[idx], [ate[i] for i in idx]),
                            "snippets": len(idx),
                            "predicted": {clf.classes[j]: int(n) for j, n in sorted(zip(labels, counts), key=lambda x: -x[1])}}
        key = kind + ("_shuffled" if shuffled else "")
        # What a motionless snippet is called (any pose held still: MOAC then sees zero velocity). A static
        # prediction inherits this class, so it explains how zero-velocity scores.
        still = np.repeat(xtr[:1, :1], frames, axis=1)
        report[key] = {
            "motionless_class": clf.classes[int(clf.snippet_outputs(still)[0].argmax())],
            "train_accuracy": 100 * snippet_accuracy(clf, xtr, atr),
            "test_accuracy": 100 * snippet_accuracy(clf, xte, ate),
            "test_balanced_accuracy": 100 * snippet_accuracy(clf, xte, ate, balanced=True),
            "test_groups": groups, "train_snippets": len(xtr), "test_snippets": len(xte),
            "classes": len(clf.classes), "chance": 100.0 / len(clf.classes),
            "seconds": round(time.time() - start, 1)}
        trained[key] = clf
    return trained, report


def evaluate(clips: list[Clip], cfg: dict, rows: list[Row] = ROWS, models_dir: Path = MODELS_DIR,
             seeds_root: Path = SEEDS_DIR, cache_dir: Path | None = RUNS_DIR / "eval", progress=print) -> dict:
    """Run every row through every table; returns the results document (see report.py)."""
    started = time.time()
    torch.set_num_threads(1)   # the machine is shared, and small batches gain nothing from threads
    k = int(cfg["k"])
    actions = sorted({c.action for c in clips})
    classifiers, clf_report = train_classifiers(clips, cfg, cache_dir)
    main = {"pose_gru": classifiers["pose_gru"], "moac": classifiers["moac"]}
    frames = main["pose_gru"].frames
    refs = references(clips, frames)
    # FID features: PCA fitted on the training snippets' pose-GRU features (WAT supplement sec. 10).
    pose_refs = {part: {a: main["pose_gru"].snippet_outputs(x)[1] for a, x in getattr(refs, part).items()}
                 for part in ("train", "test")}
    space = FeatureSpace(np.concatenate(list(pose_refs["train"].values())), int(cfg["fid"]["dims"]))
    progress(f"classifiers ready ({time.time() - started:.0f} s)")

    tables = []
    served_hashes: dict[str, str] = {}
    skipped: list[dict] = []
    loaded: dict[str, tuple[list[ModelRun], list[str]]] = {}
    for r in rows:
        if r.kind == "model":
            loaded[r.id] = load_row_models(r, list(cfg["training_seeds"]), models_dir, seeds_root)
            if not loaded[r.id][0]:
                skipped.append({"row": r.id, "label": r.label, "reason": "; ".join(loaded[r.id][1])})
            for run in loaded[r.id][0]:
                if run.served:
                    served_hashes[run.entry["id"]] = run.entry["hash"]
    for table in cfg["tables"]:
        t0 = time.time()
        cache: dict[int, list[EvalWindow]] = {}

        def windows_for(h: int, table=table, cache=cache) -> list[EvalWindow]:
            if h not in cache:
                cache[h] = table_windows(clips, table, h)
            return cache[h]

        fixed = None if per_row_history(table) else int(table["history_frames"])
        wins = windows_for(fixed or M.L_FRAMES)
        doc = {key: table[key] for key in ("id", "title", "about", "source", "horizon_frames", "truth")}
        doc.update({"k": k, "history_frames": fixed, "windows": len(wins) if fixed else None,
                    "clips": sorted({w.clip for w in wins}),
                    "actions": sorted({w.action for w in wins}) if table.get("actions") != "all" else actions,
                    "rows": [], "notes": []})
        t = int(table["horizon_frames"])
        doc["columns"] = [c for c in COLUMNS if _column_applies(c, table)]
        edges = list(range(0, t + 1, int(cfg["length_bin_frames"])))
        if edges[-1] != t:
            edges.append(t)
        doc["length_edges"] = edges
        for r in rows:
            if r.tables is not None and table["id"] not in r.tables:
                continue
            r0 = time.time()
            row_doc = _run_row(r, table, windows_for, loaded.get(r.id), cfg, k, actions, main, space, pose_refs,
                               refs, edges)
            if row_doc is None:
                continue
            row_doc["seconds"] = round(time.time() - r0, 1)
            doc["rows"].append(row_doc)
        if not doc["rows"]:
            doc["notes"].append("no row can run here yet" + (" (no action-conditioned model)" if table.get(
                "conditioned_only") else ""))
        progress(f"table {table['id']}: {len(wins) if fixed else 'per-row'} windows, {len(doc['rows'])} rows "
                 f"({time.time() - t0:.0f} s)")
        tables.append(doc)

    from .checks import evaluate_claims, sanity_checks
    sanity = sanity_checks(tables, clf_report, cfg)
    claims = evaluate_claims(tables)
    return {"format": "motion-futures/results", "version": 1,
            "columns": {c: {"label": v[0], "unit": v[1], "better": v[2]} for c, v in COLUMNS.items()},
            "k": k, "fps": FPS, "training_seeds": cfg["training_seeds"], "sampling_seeds": cfg["sampling_seeds"],
            "models": served_hashes, "classifiers": clf_report, "classifier_config": cfg["classifier"],
            "sanity": sanity, "claims": claims, "tables": tables, "skipped": skipped,
            "context_plot": cfg.get("context_plot", []), "length_plot": cfg.get("length_plot"),
            "seconds": round(time.time() - started, 1)}


def _column_applies(col: str, table: dict) -> bool:
    label, unit, better, needs_truth = COLUMNS[col]
    t = int(table["horizon_frames"])
    if needs_truth and not table["truth"]:
        return False
    if col.startswith("mpjpe_1s") and t < FPS or col.startswith("mpjpe_h") and t <= FPS:
        return False
    if col in ("ade_w", "div_w") and not table.get("dtw", True):
        return False
    return not (col == "fid_te" and table["source"] == "train")


def _run_row(r: Row, table: dict, windows_for, loaded, cfg: dict, k: int, actions: list[str],
             classifiers, space, pose_refs, refs, edges) -> dict | None:
    t = int(table["horizon_frames"])
    fixed = None if per_row_history(table) else int(table["history_frames"])
    base = {"id": r.id, "label": r.label, "kind": r.kind, "group": r.group, "note": r.note,
            "controls": r.controls, "notes": []}
    runs_values: list[dict] = []
    intervals: dict = {}
    lengths: dict[str, list[int]] = {}
    if r.kind in ("oracle", "noise"):
        if not table["truth"]:
            return None
        seeds = list(cfg["sampling_seeds"]) if r.kind == "noise" else [cfg["sampling_seeds"][0]]
        wins = windows_for(fixed)
        for s in seeds:
            samples = predict_truth(r, wins, k, float(cfg["noise_sigma"]), s)
            vals, iv, lens = run_metrics(samples, table, classifiers, space, pose_refs, refs, cfg, not runs_values)
            runs_values.append(vals)
            intervals = intervals or iv
            lengths = lengths or lens
        base.update({"k": 1 if r.kind == "oracle" else k, "history_frames": None, "train_seeds": []})
        if r.kind == "noise":
            base["sigma"] = float(cfg["noise_sigma"])
    else:
        runs, notes = loaded
        if not runs:
            return None
        base["notes"] += notes
        first = runs[0].entry
        ctl = controls_of(first)
        if table.get("conditioned_only") and "actions" not in ctl:
            return None
        need = int(first["params"]["history_frames"])
        if fixed is not None and need > fixed:
            base["skipped"] = f"needs {need} history frames; this table's windows have {fixed}"
            return base
        # Per-row tables cut at least L frames of history, so Eq. 4 can be measured at the transition.
        wins = windows_for(fixed or max(need, M.L_FRAMES))
        if not wins:
            base["skipped"] = f"no window of {need} history frames fits in this table's clips"
            return base
        base["windows"] = len(wins)
        if fixed is None:
            base["notes"].append(f"history {need} frames, {len(wins)} windows")
        usable = [run for run in runs if max_horizon(run.entry) >= t]
        if not usable:
            base["skipped"] = f"predicts at most {max_horizon(first)} frames; this table needs {t}"
            return base
        if len(usable) < len(runs):
            base["notes"].append(f"training seeds {[x.seed for x in runs if x not in usable]} predict at most "
                                 f"{min(max_horizon(x.entry) for x in runs if x not in usable)} frames (stale export)")
        stochastic = "k" in ctl
        sampling = list(cfg["sampling_seeds"]) if stochastic else [cfg["sampling_seeds"][0]]
        for run in usable:
            for s in sampling:
                samples, refused = predict_model(run, r, table, wins, actions, k, s)
                base["notes"] += [n for n in refused if n not in base["notes"]]
                if not samples:
                    continue
                vals, iv, lens = run_metrics(samples, table, classifiers, space, pose_refs, refs, cfg,
                                             not runs_values)
                runs_values.append(vals)
                intervals = intervals or iv
                lengths = lengths or lens
        base.update({"k": k if stochastic else 1, "history_frames": need,
                     "train_seeds": [run.seed for run in usable], "sampling_seeds": sampling,
                     "hashes": {str(run.seed): run.entry["hash"] for run in usable}})
        if not stochastic:
            base["notes"].append("deterministic: one future per history; sampling seeds do not apply")
    base["runs"] = len(runs_values)
    base["values"] = {c: summarise([v.get(c, math.nan) for v in runs_values]) for c in COLUMNS}
    base["values"] = {c: v for c, v in base["values"].items() if v is not None}
    base["intervals"] = intervals
    base["lengths"] = {a: M.length_histogram(v, edges) for a, v in sorted(lengths.items())}
    return base
