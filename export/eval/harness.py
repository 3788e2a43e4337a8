"""The evaluation runner: every row of rows.py through every table of configs/eval.json.

Windows are cut from the clips' world-frame positions (heldout.cut_windows), the frames the predictors
take and give: every row of a table sees the same windows, each model the last frames of its own history
length, and the ground truth is the captured world frames after the history. Models predict through the
Python predictor (export/sample/predictor.py), the code path the end-to-end vectors tie to the browser.

Each (row, table) is run for every training seed x sampling seed. A run gives one value per item (a window,
or a window and a requested action) and metric; a row's value is the mean over runs of the run's mean, its
uncertainty the seed std over runs combined with a cluster bootstrap over takes (stats.py).
"""
from __future__ import annotations

import importlib
import json
import math
import time
import warnings
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import torch

from ..config import load_config, model_hash, override
from ..data.clip import Clip
from ..data.skeleton import SKELETON
from ..data.sources import FPS
from ..data.split import short_horizons
from ..data.vocabulary import GROUPS, group as group_of
from ..data.windows import windows as train_windows
from ..manifest import read_manifest
from ..methods import METHODS, method_for
from ..ops.bones import bone_lengths
from ..ops.facing import Placement, canonicalise, place, rotate_about_y
from ..paths import CONFIGS_DIR, MODELS_DIR, RUNS_DIR
from ..sample.predictor import PREDICTORS, predictor_for
from ..sample.request import PredictError, Request
from . import baselines as B
from . import metrics as M
from . import realism_columns as R
from . import stats as S
from .classifiers import (Classifier, action_accuracy, select_classifier, snippet_accuracy, snippets,
                          split_snippets, train_classifier)
from .fid import FeatureSpace, frechet
from .heldout import HeldOutWindow, cut_windows
from .rows import ROWS, Row
from .variants import project_onto_history, with_rule

SEEDS_DIR = RUNS_DIR / "seeds"


@dataclass(frozen=True)
class Column:
    label: str
    unit: str
    better: str            # "lower", "higher" or ""
    truth: bool = False    # needs frame-wise ground truth
    balanced: bool = False  # mean over actions of each action's mean (recognition)
    section: str = ""      # where the report shows it ("" = only in the JSON and the detail tables)


# MPJPE in mm as Keyposes reports it; ADE/FDE/APD and WAT's pose-vector distances in metres.
COLUMNS: dict[str, Column] = {
    "ade": Column("ADE best of K (root-relative)", "m", "lower", True, section="accuracy"),
    "fde": Column("FDE best of K (root-relative)", "m", "lower", True, section="accuracy"),
    "ade_full": Column("ADE best of K (full positions)", "m", "lower", True, section="accuracy"),
    "fde_full": Column("FDE best of K (full positions)", "m", "lower", True, section="accuracy"),
    "mmade": Column("MMADE", "m", "lower", True, section="accuracy"),
    "mmfde": Column("MMFDE", "m", "lower", True, section="accuracy"),
    "mpjpe_h_best": Column("MPJPE at horizon, best", "mm", "lower", True, section="accuracy"),
    "mpjpe_h_ave": Column("MPJPE at horizon, ave", "mm", "lower", True),
    "mmade_half": Column("MMADE at half the threshold", "m", "lower", True),
    "mmade_double": Column("MMADE at double the threshold", "m", "lower", True),
    "mmfde_half": Column("MMFDE at half the threshold", "m", "lower", True),
    "mmfde_double": Column("MMFDE at double the threshold", "m", "lower", True),
    "apd": Column("APD (root-relative)", "m", "higher", section="diversity"),
    "div": Column("Diversity (WAT Eq. 10)", "m", "higher", section="diversity"),
    "div_w": Column("Diversity after DTW (Eq. 11)", "m", "higher", section="diversity"),
    "acc_pose": Column("Accuracy (pose GRU)", "%", "higher", balanced=True, section="recognition"),
    "acc_moac": Column("Accuracy (MOAC)", "%", "higher", balanced=True, section="recognition"),
    "fid": Column("FID vs the captured futures", "", "lower", True, section="recognition"),
    "smooth": Column("Eq. 4 as printed (squared)", "mm²", "lower", section="plausibility"),
    "smooth_unsq": Column("Eq. 4 as the authors' code (unsquared)", "mm", "lower", section="plausibility"),
    "bone": Column("Bone-length error", "%", "lower", section="plausibility"),
    "foot": Column("Frames with a foot below the floor", "%", "lower", section="plausibility"),
    "jump": Column("Smooth first frame", "%", "higher", section="plausibility"),
    "cut": Column("Samples cut by the guard", "%", "lower", section="plausibility"),
    "speed": Column("Joint speed, last second", "m/s", "", section="plausibility"),
    "length": Column("Mean length", "frames", "", section="plausibility"),
    "stopped": Column("Segments stopped (Eq. 8)", "%", "", section="plausibility"),
    # Evaluation v3: does the motion look like people's (export/eval/realism_columns.py)?
    "mpjpe_cm": Column("Per-joint error, best of K (root-relative)", "cm", "lower", True, section="realism"),
    "mpjpe_f_cm": Column("Per-joint error at the horizon, best of K (root-relative)", "cm", "lower", True,
                         section="realism"),
    **{f"speed_ratio_s{s}": Column(f"Joint speed / truth's, second {s}", "×", "", True, section="realism")
       for s in range(1, R.SECONDS + 1)},
    **{f"root_ratio_s{s}": Column(f"Root speed / truth's, second {s}", "×", "", True, section="realism")
       for s in range(1, R.SECONDS + 1)},
    "follow": Column("Speed follows the history (Spearman ρ, first second)", "", "higher", section="realism"),
    "skate": Column("Foot skating (median contact speed)", "m/s", "lower", section="realism"),
    "hip_range": Column("Hip vertical range", "m", "", section="realism"),
    "outside": Column("Truth outside every sample", "%", "lower", True, section="realism"),
    "outside_naive": Column("Truth outside every sample (the audit's rule)", "%", "", True),
    "spread_cm": Column("Pose spread at the last frame", "cm", "higher", section="realism"),
    "spread_all_cm": Column("Pose spread over the future", "cm", "higher"),
    "full": Column("Samples lasting the whole horizon", "%", "", section="realism"),
    "pskl_gp": Column("PSKL (truth ‖ prediction)", "", "lower", True, section="realism"),
    "pskl_pg": Column("PSKL (prediction ‖ truth)", "", "lower", True, section="realism"),
    "cmd": Column("CMD (BeLFusion)", "m/frame", "lower", True, section="realism"),
    **{c: Column(c, "m/s", "") for s in range(1, R.SECONDS + 1)
       for c in (f"speed_s{s}", f"root_s{s}", f"truth_speed_s{s}", f"truth_root_s{s}")},
    "history_speed": Column("History's joint speed", "m/s", ""),
}
SET_LEVEL = ("fid", *R.SET_COLUMNS)  # one value per run, not per item
RATIO = R.RATIOS                     # a ratio of two columns' means over the items both have
RECOGNITION = ("acc_pose", "acc_moac")

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
                "length_bin_frames", "bootstrap", "mmade", "nearest", "tables"):
        if key not in cfg:
            raise ValueError(f"{path}: evaluation config is missing '{key}'")
    for i, table in enumerate(cfg["tables"]):
        missing = [k for k in TABLE_KEYS if k not in table]
        if missing:
            raise ValueError(f"{path}: table {table.get('id', i)} is missing {missing}")
        if table["source"] not in ("test", "train"):
            raise ValueError(f"{path}: table {table['id']}: source must be test (held-out people) or train, "
                             f"got {table['source']!r}")
        if not (isinstance(table["history_frames"], int) and table["history_frames"] > 0):
            raise ValueError(f"{path}: table {table['id']}: history_frames must be a positive integer")
        if table.get("context_frames", table["history_frames"]) < table["history_frames"]:
            raise ValueError(f"{path}: table {table['id']}: context_frames must be at least history_frames")
    return cfg


def table_windows(clips: list[Clip], table: dict) -> list[HeldOutWindow]:
    """The table's windows, world frame: history (with up to context_frames of earlier frames) and, when the
    table has ground truth, the horizon's captured frames after it; from the held-out people ("test") or the
    training people ("train")."""
    t = int(table["horizon_frames"]) if table["truth"] else 0
    wins = cut_windows(clips, table["source"], int(table["history_frames"]), t, int(table["stride"]),
                       table.get("context_frames"))
    return capped_windows(wins, table.get("cap_per_person_action"))


def capped_windows(wins: list[HeldOutWindow], cap: int | None) -> list[HeldOutWindow]:
    """At most `cap` windows per (person, action), spread evenly over that person's windows of it in clip
    order: salsa partner 61 alone holds 458 of the 748 held-out seconds, and without a cap an all-action
    mean would be a salsa mean. None keeps every window."""
    if not cap:
        return wins
    groups: dict[tuple[str, str], list[int]] = {}
    for i, w in enumerate(wins):
        groups.setdefault((str(w.subject), w.action), []).append(i)
    keep = set()
    for idx in groups.values():
        keep |= {idx[j] for j in np.unique(np.linspace(0, len(idx) - 1, min(cap, len(idx))).round().astype(int))}
    return [w for i, w in enumerate(wins) if i in keep]


def requested_actions(table: dict, actions: list[str], window: int, own: str) -> list[str]:
    """The window's own action, or (tables with "actions") a rotating subset of `actions_per_window` of
    `actions`, so that every action is requested equally often over the windows."""
    if not table.get("actions"):
        return [own]
    n = int(table.get("actions_per_window", len(actions)))
    return [actions[(window * n + j) % len(actions)] for j in range(min(n, len(actions)))]


# --- rows -----------------------------------------------------------------------------------

@dataclass
class ModelRun:
    """A row's trained model at one training seed."""
    seed: int
    predictor: object
    entry: dict
    served: bool


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
    runs, missing, broken = [], [], []
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
        # A model trained by other code or config is still evaluated, but said so: `make results` (or
        # `make models` for a served one) retrains it.
        if entry["hash"] != model_hash(override(cfg, **{"train.seed": seed}), manifest["data_hash"]) and \
                entry["hash"] != model_hash(cfg, manifest["data_hash"]):
            broken.append(f"training seed {seed} is stale: its hash is not what this code and config give")
        try:
            predictor = with_rule(predictor_for(entry, manifest, directory), row.extract)
        except Exception as e:   # a stale export (other graph signature, missing file) must not stop the rest
            broken.append(f"training seed {seed} does not load ({type(e).__name__}: {e})")
            continue
        runs.append(ModelRun(seed, predictor, entry, served))
    if missing:
        notes.append(f"training seeds {missing} not found (served seed 0 comes from `make models`, "
                     "the others from `make results`)")
    return runs, notes + broken


def max_horizon(entry: dict) -> int:
    spec = next((c for c in entry["controls"] if c["id"] == "horizon"), None)
    return round(spec["max"] * FPS) if spec else int(entry["params"]["future_frames"])


def controls_of(entry: dict) -> dict[str, dict]:
    return {c["id"]: c for c in entry["controls"]}


def request_seed(sampling_seed: int, window: int, action: int) -> int:
    # Distinct, reproducible draws for every window and requested action of a sampling seed.
    return (sampling_seed * 1_000_003 + window * 97 + action) % 2 ** 32


# --- predictions ------------------------------------------------------------------------------

@dataclass
class Sample:
    """One item's prediction: K world-frame futures for one window and one requested action."""
    futures: np.ndarray            # [K, T, J, 3]
    lengths: np.ndarray            # [K]
    samples: list[dict] = field(default_factory=list)
    history: np.ndarray | None = None   # what the row read (for the bone projection)


@dataclass
class Table:
    """A table's windows and what every row's metrics compare with."""
    cfg: dict
    wins: list[HeldOutWindow]
    items: list[tuple[int, str]]   # (window, requested action)
    units: S.Units
    weights: np.ndarray            # bootstrap resamples of its takes
    placements: list[Placement]
    truth_rr: np.ndarray | None    # [W, T, J*3] truths in each window's canonical frame, root-relative
    sets: dict[str, list[np.ndarray]] = field(default_factory=dict)   # MMADE sets at each threshold
    threshold: float | None = None
    truth_feats: list[np.ndarray] | None = None   # pose-GRU features of each window's captured future


def predict_model(run: ModelRun, row: Row, tab: Table, k: int, sampling_seed: int,
                  actions: list[str]) -> tuple[list[Sample | None], list[str]]:
    """K futures per item through the Python predictor; None where the predictor refuses the history."""
    n = int(run.entry["params"]["history_frames"])
    t = int(tab.cfg["horizon_frames"])
    ctl = controls_of(run.entry)
    out, refused = [], []
    for w, a in tab.items:
        win = tab.wins[w]
        req = Request(k=k if "k" in ctl else 1, seed=request_seed(sampling_seed, w, actions.index(a)),
                      actions=[a] if "actions" in ctl else [], horizon_frames=t, controls=dict(row.controls), plant_feet=row.plant_feet)
        try:
            pred = run.predictor.predict(win.history[-n:], req)
        except PredictError as e:
            refused.append(str(e))
            out.append(None)
            continue
        if pred.futures.shape[1] < t:   # the contract pads stopped samples to the horizon
            refused.append(f"returned {pred.futures.shape[1]} frames for a horizon of {t}")
            out.append(None)
            continue
        out.append(Sample(np.asarray(pred.futures, dtype=np.float64)[:, :t], np.minimum(np.asarray(pred.lengths), t),
                          pred.samples, win.history[-n:]))
    notes = [f"{len(refused)} of {len(out)} predictions refused, e.g. {refused[0]!r}"] if refused else []
    return out, notes


def nearest_futures(queries: list[np.ndarray], clips: list[Clip], history: int, horizon: int, stride: int
                    ) -> np.ndarray:
    """baselines.nearest_window for many world histories [history, J, 3] at once, over every training window
    of the training people (mirrors included, as the models train): the bank is streamed clip by clip
    (baselines.nearest_indices within a clip, the running best across clips; ties go to the first), so
    only one clip's windows are ever in memory. -> [Q, horizon, J, 3] world futures."""
    canon, placements = zip(*(canonicalise(np.asarray(q, dtype=np.float64)[-history:], history - 1, SKELETON)
                              for q in queries))
    canon = np.stack(canon)
    query = B.facing_root_relative(canon).reshape(len(canon), -1)
    best_d = np.full(len(canon), np.inf)
    best = np.zeros((len(canon), horizon, *canon.shape[2:]))
    for clip in clips:
        bank = train_windows([clip], "train", history + horizon, history, stride=stride, mirror=True)
        if not bank:
            continue
        pos = np.stack([w.positions for w in bank])
        idx = B.nearest_indices(canon, pos[:, :history])
        d = np.linalg.norm(B.facing_root_relative(pos[idx, :history]).reshape(len(idx), -1) - query, axis=1)
        better = d < best_d
        best_d[better], best[better] = d[better], pos[idx[better], history:]
    return np.stack([place(f, p) for f, p in zip(best, placements)])


def predict_baseline(row: Row, tab: Table, train_clips: list[Clip], cfg: dict) -> tuple[list[Sample], list[str]]:
    """The row's pure baseline function on each window's world history (deterministic: one future)."""
    t = int(tab.cfg["horizon_frames"])
    notes = []
    if row.baseline == "nearest_window":
        h = int(row.history)
        futs = nearest_futures([tab.wins[w].history[-h:] for w, _ in tab.items], train_clips, h, t,
                               int(cfg["nearest"]["stride"]))
        return [Sample(f[None], np.array([t]), history=tab.wins[w].history[-h:])
                for f, (w, _) in zip(futs, tab.items)], notes
    out = []
    short = 0
    for w, _ in tab.items:
        hist = tab.wins[w].history[-int(row.history):]
        short += len(hist) < int(row.history)
        if row.baseline == "constant_velocity":
            fut = B.constant_velocity(hist, t)
        elif row.baseline == "repeat_cycle":
            fut = B.repeat_last_cycle(hist, t)
        else:
            raise ValueError(f"unknown baseline {row.baseline!r}")
        out.append(Sample(fut[None], np.array([t]), history=hist))
    if short:
        notes.append(f"{short} of {len(out)} windows hold fewer than {row.history} frames before the present "
                     f"(their take starts later): the baseline reads what there is, at least "
                     f"{tab.cfg['history_frames']} frames")
    return out, notes


def predict_truth(row: Row, tab: Table, k: int, sigma: float, sampling_seed: int) -> list[Sample]:
    """The oracle (the ground truth itself) and the noise sanity row (K noisy copies of it)."""
    out = []
    for i, (w, _) in enumerate(tab.items):
        truth = tab.wins[w].truth
        if row.kind == "oracle":
            fut = truth[None]
        else:
            rng = np.random.default_rng([sampling_seed, i])
            fut = truth[None] + rng.normal(0.0, sigma, (k, *truth.shape))
        out.append(Sample(fut, np.full(len(fut), len(truth)), history=tab.wins[w].history))
    return out


# --- metrics over a run -----------------------------------------------------------------------

def to_window_frame(world: np.ndarray, p: Placement) -> np.ndarray:
    """World positions into a window's canonical frame (facing +z at its last history frame, its root's
    ground point at the origin): facing.place undone."""
    shifted = np.asarray(world, dtype=np.float64) - np.array([p.x, 0.0, p.z])
    return rotate_about_y(shifted, -p.angle)


def item_metrics(s: Sample, win: HeldOutWindow, t: int, truth: bool, dtw: bool, history: int) -> dict[str, float]:
    """One item's values: accuracy against the ground truth, spread, and plausibility of the raw futures."""
    f, k = s.futures, len(s.futures)
    v: dict[str, float] = {}
    if truth:
        v["ade"], v["fde"] = M.ade_fde(f, win.truth, root_relative=True)
        v["ade_full"], v["fde_full"] = M.ade_fde(f, win.truth, root_relative=False)
        ave, best = M.mpjpe_at(M.root_relative(f), M.root_relative(win.truth), t - 1)
        v["mpjpe_h_ave"], v["mpjpe_h_best"] = ave * 1000, best * 1000
    v["apd"] = M.apd(M.root_relative(f))
    v["div"] = M.diversity(f)
    if dtw:
        trimmed = [x[:max(int(n), 2)] for x, n in zip(f, s.lengths)]
        v["div_w"] = M.diversity_dtw(trimmed) if k > 1 else 0.0
    hist_rr = M.root_relative(win.history)
    if len(win.history) >= M.L_FRAMES and t >= M.L_FRAMES:
        rr = M.root_relative(f)
        v["smooth"] = float(np.mean([M.transition_smoothness(hist_rr, x) for x in rr])) * 1e6
        v["smooth_unsq"] = float(np.mean([M.transition_smoothness_unsquared(hist_rr, x) for x in rr])) * 1e3
    ref = bone_lengths(win.history).mean(0)
    v["bone"] = 100 * float(np.mean([M.bone_length_error(x, ref) for x in f]))
    v["foot"] = 100 * float(np.mean([M.foot_below_floor(x) for x in f]))
    v["jump"] = 100 * float(np.mean([M.jump_ok(*M.first_frame_jump(win.history, x)) for x in f]))
    v["cut"] = 100 * float(np.mean([bool(x.get("cut")) for x in s.samples])) if s.samples else 0.0
    if t >= 2:
        v["speed"] = float(np.mean([M.joint_speed(x, FPS, min(int(FPS), t - 1)) for x in f]))
    v["length"] = float(np.mean(s.lengths))
    stops = [seg["stopped"] for x in s.samples for seg in x.get("segments", []) if "stopped" in seg]
    if stops and any("action" in seg for x in s.samples for seg in x.get("segments", [])):
        v["stopped"] = 100 * float(np.mean(stops))
    v.update(R.item_realism(f, s.lengths, win.truth if truth else None, win.history[-history:], t))
    return v


def mm_metrics(s: Sample, w: int, tab: Table) -> dict[str, float]:
    """MMADE and MMFDE of one window (DLow): its futures' best-of-K ADE and FDE against the truth of every
    window in its similar set, averaged over the set; at the chosen threshold, half and double it."""
    f = to_window_frame(s.futures, tab.placements[w])
    f = M.root_relative(f).reshape(len(f), f.shape[1], -1)
    members = tab.sets["double"][w]             # every smaller set is inside it
    ade, fde = M.ade_fde_many(f, tab.truth_rr[members], root_relative=False)
    at = {m: i for i, m in enumerate(members)}
    out = {}
    for name, suffix in (("chosen", ""), ("half", "_half"), ("double", "_double")):
        idx = [at[m] for m in tab.sets[name][w]]
        out[f"mmade{suffix}"], out[f"mmfde{suffix}"] = float(ade[idx].mean()), float(fde[idx].mean())
    return out


@dataclass
class Context:
    """What every run's metrics need: classifiers, the FID feature space, the evaluation config."""
    classifiers: dict[str, Classifier]
    space: FeatureSpace
    cfg: dict


@dataclass
class RunResult:
    values: dict[str, np.ndarray]        # per item (NaN where the item has no value)
    sets: dict[str, float]               # set-level metrics (FID)
    boot: dict[str, float]               # their take-bootstrap std (first run only)
    lengths: dict[str, list[int]]
    items: int


def run_metrics(samples: list[Sample | None], tab: Table, ctx: Context, first: bool) -> RunResult:
    """One run's per-item values for every column, and its set-level FID."""
    t = int(tab.cfg["horizon_frames"])
    n = len(tab.items)
    vals: dict[str, np.ndarray] = {c: np.full(n, np.nan) for c in COLUMNS}
    lengths: dict[str, list[int]] = {}
    for i, s in enumerate(samples):
        if s is None:
            continue
        w, a = tab.items[i]
        got = item_metrics(s, tab.wins[w], t, bool(tab.cfg["truth"]), bool(tab.cfg.get("dtw")),
                           int(tab.cfg["history_frames"]))
        if tab.truth_rr is not None:
            got.update(mm_metrics(s, w, tab))
        for c, x in got.items():
            vals[c][i] = x
        for j, length in enumerate(s.lengths):
            segs = s.samples[j].get("segments") if j < len(s.samples) else None
            for seg in segs or [{"length": int(length)}]:
                lengths.setdefault(seg.get("action") or a, []).append(int(seg["length"]))
    done = [i for i, s in enumerate(samples) if s is not None]
    sets, boot = {}, {}
    sets.update(R.set_realism([None if s is None else s.futures for s in samples],
                              [tab.wins[w].truth for w, _ in tab.items] if tab.cfg["truth"] else None,
                              [a for _, a in tab.items], vals))
    stride = int(ctx.cfg["snippet_stride"])
    clf0 = ctx.classifiers["pose_gru"]
    if t >= clf0.frames and done:
        cut = [snippets(f, clf0.frames, stride) for i in done for f in samples[i].futures]
        owner = np.array([i for i in done for _ in samples[i].futures])
        feats_by_item: dict[int, list[np.ndarray]] = {}
        for kind, clf in ctx.classifiers.items():
            labels, feats = clf.classify_snippets(cut)
            target = np.array([clf.actions.index(tab.items[i][1]) for i in owner])
            hit = (labels == target).astype(np.float64)
            col = "acc_pose" if kind == "pose_gru" else "acc_moac"
            for i in done:
                vals[col][i] = 100 * hit[owner == i].mean()
            if kind == "pose_gru":
                for i, f in zip(owner, feats):
                    feats_by_item.setdefault(int(i), []).append(f)
        if tab.truth_feats is not None:
            gen = [np.concatenate(feats_by_item[i]) for i in done]
            ref = [tab.truth_feats[tab.items[i][0]] for i in done]
            if sum(map(len, gen)) > 2 and sum(map(len, ref)) > 2:
                sets["fid"] = ctx.space.fid(np.concatenate(gen), np.concatenate(ref))
                if first:
                    boot["fid"] = fid_boot_std(gen, ref, [int(tab.units.take[i]) for i in done], tab, ctx)
    return RunResult(vals, sets, boot, lengths, len(done))


def fid_boot_std(gen: list[np.ndarray], ref: list[np.ndarray], takes: list[int], tab: Table, ctx: Context) -> float:
    """FID's std over take resamples (generated and captured features of the drawn takes together)."""
    rounds = int(ctx.cfg["fid"]["bootstrap"])
    g = [ctx.space.project(x) for x in gen]
    r = [ctx.space.project(x) for x in ref]
    takes = np.asarray(takes)
    draws = []
    for wts in tab.weights[:rounds]:
        pick = np.repeat(np.arange(len(takes)), wts[takes].astype(int))
        if len(pick) < 2:
            continue
        ga, ra = np.concatenate([g[i] for i in pick]), np.concatenate([r[i] for i in pick])
        if len(ga) > 2 and len(ra) > 2:
            draws.append(frechet(ga, ra))
    return float(np.std(draws, ddof=1)) if len(draws) > 1 else 0.0


# --- a row through a table ----------------------------------------------------------------------

@dataclass
class RowStats:
    """A finished row: per-item values averaged over runs, and each column's seed std (for the claims)."""
    items: dict[str, np.ndarray]
    seed_std: dict[str, float]


def summarise_runs(results: list[RunResult], tab: Table, mask: np.ndarray | None = None, suffix: str = "",
                   cols=None) -> tuple[dict, RowStats]:
    """values[col] = {"mean", "std" (bootstrap and seeds combined), "seed_std", "boot_std", "n"}, over the
    items in `mask` (all by default; set-level columns read their "col{suffix}" value of each run)."""
    values, items, seed_std = {}, {}, {}
    keep = np.ones(len(tab.items), dtype=bool) if mask is None else mask
    for col, spec in COLUMNS.items():
        if cols is not None and col not in cols:
            continue
        if col in SET_LEVEL:
            per_run = [r.sets[col + suffix] for r in results if col + suffix in r.sets]
            s = S.summarise(per_run) if per_run else None
            if s is None:
                continue
            boot = next((r.boot[col] for r in results if col in r.boot), 0.0) if not suffix else 0.0
            values[col] = {**s, "seed_std": s["std"], "boot_std": boot, "std": math.hypot(s["std"], boot)}
            continue
        if col in RATIO:
            got = _ratio(results, tab, keep, *RATIO[col])
            if got is not None:
                values[col] = got
            continue
        stack = np.stack([np.where(keep, r.values[col], np.nan) for r in results])
        if not np.isfinite(stack).any():
            continue
        per_run = [S.aggregate(v, tab.units, spec.balanced) for v in stack]
        s = S.summarise(per_run)
        if s is None:
            continue
        with warnings.catch_warnings():   # an item no run predicted stays NaN
            warnings.simplefilter("ignore", RuntimeWarning)
            mean_items = np.nanmean(stack, axis=0)
        boot = S.cluster_std(mean_items, tab.units, tab.weights, spec.balanced)
        values[col] = {**s, "seed_std": s["std"], "boot_std": boot, "std": math.hypot(s["std"], boot), "n": int(np.isfinite(mean_items).sum())}
        items[col], seed_std[col] = mean_items, s["std"]
    return values, RowStats(items, seed_std)


def _ratio(results: list[RunResult], tab: Table, keep: np.ndarray, num: str, den: str) -> dict | None:
    """A ratio of means (realism.speed.ratio_to_truth) over the items with both values, per run; its
    bootstrap std from the same people-then-takes resamples."""
    both = [keep & np.isfinite(r.values[num]) & np.isfinite(r.values[den]) for r in results]
    per_run = [float(r.values[num][b].mean() / r.values[den][b].mean()) for r, b in zip(results, both)
               if b.any() and r.values[den][b].mean() > 0]
    s = S.summarise(per_run)
    if s is None:
        return None
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        n = np.nanmean(np.stack([np.where(b, r.values[num], np.nan) for r, b in zip(results, both)]), 0)
        d = np.nanmean(np.stack([np.where(b, r.values[den], np.nan) for r, b in zip(results, both)]), 0)
        boot = S.resampled(n, tab.units, tab.weights) / S.resampled(d, tab.units, tab.weights)
    boot = boot[np.isfinite(boot)]
    sd = float(boot.std(ddof=1)) if boot.size > 1 else 0.0
    return {**s, "seed_std": s["std"], "boot_std": sd, "std": math.hypot(s["std"], sd), "n": int(np.isfinite(n).sum())}


GROUP_COLUMNS = ("ade", "fde", "mpjpe_cm", "mpjpe_f_cm", "apd", "foot", "cut", "length", "mmade",
                 *[c for c, spec in COLUMNS.items() if spec.section == "realism"])


def by_group(results: list[RunResult], tab: Table) -> dict[str, dict]:
    """Every realism and accuracy column per action group (walk, run, jump, dance, other): no failure hides
    in a mean over all actions. Each group's values are over its own items, with their own bar."""
    groups = np.array([group_of(a) for _, a in tab.items])
    out = {}
    for g in GROUPS:
        mask = groups == g
        if mask.any():
            values, _ = summarise_runs(results, tab, mask, f"@{g}", GROUP_COLUMNS)
            out[g] = {"items": int(mask.sum()), "people": len(set(tab.units.person[mask])),
                      "takes": len(set(tab.units.take[mask])), "values": values}
    return out


FLAG_CUT = 5.0             # % of samples the output guard cuts
FLAG_LENGTH = 0.5          # of the horizon: samples shorter than that on average do not predict it


def does_not_predict(values: dict, horizon: int) -> str:
    """Why a row's futures are not predictions (Evaluation v3, item 4), or "": the output guard cuts more
    than 5% of its samples, or they last less than half the horizon on average. Such a row is flagged in
    every table and kept out of every tally and "within 10%"."""
    reasons = []
    cut = values.get("cut", {}).get("mean")
    if cut is not None and cut > FLAG_CUT:
        reasons.append(f"the output guard cuts {cut:.0f}% of its samples (more than {FLAG_CUT:.0f}%)")
    length = values.get("length", {}).get("mean")
    if length is not None and length < FLAG_LENGTH * horizon:
        reasons.append(f"its samples last {length:.1f} of {horizon} frames on average (less than half)")
    return "; ".join(reasons)


PAIRED_ROWS = ("oracle", "zero-velocity", "regression-gru")
PAIRED_COLUMNS = ("ade", "fde", "mpjpe_cm", "mpjpe_f_cm", "skate", "hip_range", "outside", "spread_cm", "smooth",
                  "acc_moac", *[f"speed_ratio_s{s}" for s in range(1, R.SECONDS + 1)],
                  *[f"root_ratio_s{s}" for s in range(1, R.SECONDS + 1)])


def on_accepted(stats: dict, row: str, tab: Table) -> dict:
    """A row that refuses windows is compared only on the windows it accepts: the ground truth's,
    zero-velocity's and the regression GRU's values on exactly those items, with their count."""
    mine = stats.get(row)
    if mine is None or "ade" not in mine.items and "length" not in mine.items:
        return {}
    key = "ade" if "ade" in mine.items else "length"
    mask = np.isfinite(mine.items[key])
    out = {"items": int(mask.sum()), "rows": {}}
    for other in PAIRED_ROWS:
        theirs = stats.get(other)
        if theirs is None or other == row:
            continue
        vals = {}
        for col in PAIRED_COLUMNS:
            if col in RATIO:
                num, den = (theirs.items.get(c) for c in RATIO[col])
                if num is not None and den is not None and np.isfinite(den[mask]).any():
                    ok = mask & np.isfinite(num) & np.isfinite(den)
                    vals[col] = float(num[ok].mean() / den[ok].mean())
            elif col in theirs.items:
                vals[col] = S.aggregate(np.where(mask, theirs.items[col], np.nan), tab.units)
        out["rows"][other] = vals
    mine_vals = {}
    for col in PAIRED_COLUMNS:
        if col in RATIO:
            num, den = (mine.items.get(c) for c in RATIO[col])
            if num is not None and den is not None:
                ok = mask & np.isfinite(num) & np.isfinite(den)
                mine_vals[col] = float(num[ok].mean() / den[ok].mean()) if ok.any() else None
        elif col in mine.items:
            mine_vals[col] = S.aggregate(mine.items[col], tab.units)
    out["rows"][row] = mine_vals
    return out


def by_action(stats: RowStats, tab: Table, cols=("ade", "apd", "acc_moac")) -> dict[str, dict[str, float]]:
    """The row's run-averaged value per action (requested action in the transitions table)."""
    out = {}
    acts = np.array([a for _, a in tab.items])
    for col in cols:
        if col not in stats.items:
            continue
        v = stats.items[col]
        out[col] = {a: float(np.nanmean(v[acts == a])) for a in sorted(set(acts)) if np.isfinite(v[acts == a]).any()}
    return out


# --- the whole evaluation ---------------------------------------------------------------------

def train_classifiers(clips: list[Clip], cfg: dict, cache_dir: Path | None, progress=print) -> tuple[dict, dict]:
    """Pose GRU and MOAC, each in the configuration leave-one-person-out chose inside the training people,
    then trained on every training person (plus the shuffled-label pose GRU of the sanity check); their
    held-out accuracies overall and per action."""
    ccfg = cfg["classifier"]
    seed = int(ccfg["seed"])
    frames = int(ccfg["snippet_frames"])
    report, trained = {}, {}
    xtr, atr, _ = split_snippets(clips, "train", frames, int(ccfg["stride"]))
    xte, ate, cte = split_snippets(clips, "test", frames, int(ccfg.get("test_stride", 5)))
    # Non-overlapping held-out snippets for the shuffled-label check: its binomial band counts them as trials.
    xsh, ash, _ = split_snippets(clips, "test", frames, frames)
    chosen = {}
    for kind in ("pose_gru", "moac"):
        start = time.time()
        chosen[kind], selection = select_classifier(kind, clips, ccfg, cache_dir)
        progress(f"classifier {kind}: leave-one-person-out chose {selection['chosen']} ({time.time() - start:.0f} s)")
        report[kind] = {"selection": selection}
    for kind, shuffled in (("pose_gru", False), ("moac", False), ("pose_gru", True)):
        start = time.time()
        clf = train_classifier(kind, clips, chosen[kind], seed, shuffled=shuffled, cache_dir=cache_dir)
        key = kind + ("_shuffled" if shuffled else "")
        still = np.repeat(xtr[:1, :1], frames, axis=1)
        predicted = clf.snippet_outputs(xte)[0].argmax(1) if len(xte) else np.zeros(0, dtype=int)
        groups = {}
        for a in sorted(set(ate)):
            idx = [i for i, b in enumerate(ate) if b == a]
            labels, counts = np.unique(predicted[idx], return_counts=True)
            groups[a] = {"predicted": {clf.classes[j]: int(c) for j, c in sorted(zip(labels, counts), key=lambda x: -x[1])[:4]}}
        per_action = action_accuracy(clf, xte, ate)
        for a, g in groups.items():
            g.update(per_action[a])
        report[key] = {**report.get(key, {}),
                       "config": {k: v for k, v in chosen[kind].items() if k in ("hidden", "noise", "steps")},
                       "motionless_class": clf.classes[int(clf.snippet_outputs(still)[0].argmax())],
                       "train_accuracy": 100 * snippet_accuracy(clf, xtr, atr),
                       "test_accuracy": 100 * snippet_accuracy(clf, xte, ate),
                       "test_balanced_accuracy": 100 * snippet_accuracy(clf, xte, ate, balanced=True),
                       "test_groups": groups, "train_snippets": len(xtr), "test_snippets": len(xte),
                       "test_takes": len(set(cte)), "classes": len(clf.classes), "chance": 100.0 / len(clf.classes),
                       "seconds": round(time.time() - start, 1)}
        if shuffled:
            # Chance for this classifier: the accuracy its own prediction frequencies q would reach if they were
            # independent of the true actions (frequencies p), sum_c q_c p_c. A classifier trained on shuffled
            # labels can learn the label prior (and call everything by one class) but nothing more.
            pred = clf.snippet_outputs(xsh)[0].argmax(1)
            truth = np.array([clf.actions.index(a) for a in ash])
            q = np.bincount(pred, minlength=len(clf.classes)) / len(pred)
            p = np.bincount(truth, minlength=len(clf.classes)) / len(truth)
            report[key].update(check_snippets=len(xsh), check_accuracy=100 * float((pred == truth).mean()),
                               check_chance=100 * float(q @ p))
        trained[key] = clf
    return trained, report


def heldout_actions(clips: list[Clip]) -> list[str]:
    """CMU actions with held-out people: the only ones a claim may rest on."""
    return sorted({c.action for c in clips if c.split.role == "test"})


def build_table(table: dict, clips: list[Clip], actions: list[str], ctx: Context) -> Table:
    """Windows, items and bootstrap units of a table; for tables with ground truth also the MMADE sets and
    the captured futures' classifier features."""
    cfg = ctx.cfg
    wins = table_windows(clips, table)
    pool = heldout_actions(clips) if table.get("actions") == "heldout" else actions
    items = [(i, a) for i, w in enumerate(wins) for a in requested_actions(table, pool, i, w.action)]
    units = S.units([wins[i].clip for i, _ in items], [a for _, a in items], [wins[i].subject for i, _ in items])
    # people are the unit: resample them, then their takes (stats.bootstrap_weights)
    weights = S.bootstrap_weights(S.take_people(units), int(cfg["bootstrap"]["rounds"]), int(cfg["bootstrap"]["seed"]))
    h = int(table["history_frames"])
    placements = [canonicalise(w.history[-h:], h - 1, SKELETON)[1] for w in wins]
    tab = Table(table, wins, items, units, weights, placements, None)
    if table["truth"] and wins:
        tab.truth_rr = np.stack([M.root_relative(to_window_frame(w.truth, p)).reshape(len(w.truth), -1)
                                 for w, p in zip(wins, placements)])
        last = np.stack([to_window_frame(w.history[-1:], p) for w, p in zip(wins, placements)])
        if len(wins) >= int(cfg["mmade"]["min_median_size"]):
            thr = M.choose_threshold(last, int(cfg["mmade"]["min_median_size"]))
            tab.threshold = thr
            tab.sets = {"chosen": M.similar_sets(last, thr), "half": M.similar_sets(last, thr / 2),
                        "double": M.similar_sets(last, thr * 2)}
        else:
            tab.sets = {name: [np.array([i]) for i in range(len(wins))] for name in ("chosen", "half", "double")}
        clf = ctx.classifiers["pose_gru"]
        if int(table["horizon_frames"]) >= clf.frames:
            _, feats = clf.classify([w.truth for w in wins], int(cfg["snippet_stride"]))
            tab.truth_feats = feats
    return tab


def table_doc(tab: Table, clips: list[Clip], doc_k: int) -> dict:
    table = tab.cfg
    h, t = int(table["history_frames"]), int(table["horizon_frames"])
    doc = {key: table[key] for key in ("id", "title", "about", "source", "horizon_frames", "truth")}
    doc.update({"k": doc_k, "history_frames": h, "context_frames": int(table.get("context_frames", h)),
                "windows": len(tab.wins), "items": len(tab.items), "stride": int(table["stride"]),
                "clips": sorted({w.clip for w in tab.wins}), "actions": sorted({a for _, a in tab.items}),
                "people": sorted({str(w.subject) for w in tab.wins}, key=lambda p: (len(p), p)),
                "takes": len({w.clip for w in tab.wins}), "rows": [], "notes": [],
                "in_sample": table["source"] == "train"})
    if table["source"] == "test" and table["truth"]:
        doc["exceptions"] = [{"action": a, "horizon_frames": x}
                             for a, x in short_horizons([c for c in clips if c.split.role == "test"], h, [t])]
    if tab.threshold is not None:
        chosen = tab.sets["chosen"]
        doc["mmade"] = {"threshold": tab.threshold, "median_set": float(np.median([len(s) for s in chosen])),
                        "alone": int(sum(len(s) == 1 for s in chosen)),
                        "half": {"threshold": tab.threshold / 2,
                                 "median_set": float(np.median([len(s) for s in tab.sets["half"]])),
                                 "alone": int(sum(len(s) == 1 for s in tab.sets["half"]))},
                        "double": {"threshold": tab.threshold * 2,
                                   "median_set": float(np.median([len(s) for s in tab.sets["double"]])),
                                   "alone": int(sum(len(s) == 1 for s in tab.sets["double"]))}}
    return doc


def rows_for(table: dict, rows: list[Row]) -> list[Row]:
    served = served_configs()
    out = []
    for r in rows:
        if r.tables is not None and table["id"] not in r.tables:
            continue
        if table.get("served_only") and not (r.kind == "oracle" or (r.kind == "model" and r.config in served)):
            continue
        out.append(r)
    return out


def evaluate(clips: list[Clip], cfg: dict, rows: list[Row] = ROWS, models_dir: Path = MODELS_DIR,
             seeds_root: Path = SEEDS_DIR, cache_dir: Path | None = RUNS_DIR / "eval", progress=print) -> dict:
    """Run every row through every table; returns the results document (see report.py)."""
    started = time.time()
    torch.set_num_threads(1)   # the machine is shared, and small batches gain nothing from threads
    k = int(cfg["k"])
    actions = sorted({c.action for c in clips})
    train_clips = [c for c in clips if c.split.role != "test"]
    classifiers, clf_report = train_classifiers(clips, cfg, cache_dir, progress)
    main = {"pose_gru": classifiers["pose_gru"], "moac": classifiers["moac"]}
    frames = main["pose_gru"].frames
    xtr, _, _ = split_snippets(clips, "train", frames, 2)
    space = FeatureSpace(main["pose_gru"].snippet_outputs(xtr)[1], int(cfg["fid"]["dims"]))
    ctx = Context(main, space, cfg)
    clf_seconds = time.time() - started
    progress(f"classifiers ready ({clf_seconds:.0f} s)")

    skipped: list[dict] = []
    served_hashes: dict[str, str] = {}
    loaded: dict[str, tuple[list[ModelRun], list[str]]] = {}
    for r in rows:
        if r.kind == "model":
            loaded[r.id] = load_row_models(r, list(cfg["training_seeds"]), models_dir, seeds_root)
            if not loaded[r.id][0]:
                skipped.append({"row": r.id, "label": r.label, "reason": "; ".join(loaded[r.id][1])})
            for run in loaded[r.id][0]:
                if run.served:
                    served_hashes[run.entry["id"]] = run.entry["hash"]

    tables, store, tabs = [], {}, {}
    for table in cfg["tables"]:
        t0 = time.time()
        tab = build_table(table, clips, actions, ctx)
        tabs[table["id"]] = tab
        doc = table_doc(tab, clips, k)
        store[table["id"]] = {}
        edges = list(range(0, int(table["horizon_frames"]) + 1, int(cfg["length_bin_frames"])))
        if edges[-1] != int(table["horizon_frames"]):
            edges.append(int(table["horizon_frames"]))
        doc["length_edges"] = edges
        derived: dict[str, list[tuple[RunResult, list[str]]]] = {}
        for r in rows_for(table, rows):
            r0 = time.time()
            row_doc, results = _run_row(r, tab, loaded.get(r.id), cfg, k, actions, ctx, train_clips, derived, rows)
            if row_doc is None:
                continue
            if results:
                values, stats_ = summarise_runs(results, tab)
                row_doc["values"] = values
                row_doc["by_action"] = by_action(stats_, tab)
                row_doc["by_group"] = by_group(results, tab)
                row_doc["lengths"] = {a: M.length_histogram(v, edges) for a, v in sorted(results[0].lengths.items())}
                row_doc["items"] = results[0].items
                row_doc["refused"] = {"items": len(tab.items) - results[0].items, "of": len(tab.items),
                                      "share": 100.0 * (1 - results[0].items / len(tab.items))}
                flag = does_not_predict(values, int(table["horizon_frames"]))
                if flag:
                    row_doc["flag"] = flag
                store[table["id"]][r.id] = stats_
            row_doc["seconds"] = round(time.time() - r0, 1)
            doc["rows"].append(row_doc)
        for row_doc in doc["rows"]:
            if row_doc.get("refused", {}).get("items"):
                row_doc["paired"] = on_accepted(store[table["id"]], row_doc["id"], tab)
        columns = [c for c, spec in COLUMNS.items() if spec.section and any(c in r.get("values", {}) for r in doc["rows"])]
        doc["columns"] = columns
        doc["extra_columns"] = [c for c in COLUMNS if not COLUMNS[c].section
                                and any(c in r.get("values", {}) for r in doc["rows"])]
        if not [r for r in doc["rows"] if r.get("values")]:
            doc["notes"].append("no row can run here yet")
        doc["seconds"] = round(time.time() - t0, 1)
        progress(f"table {table['id']}: {len(tab.wins)} windows, {len(doc['rows'])} rows ({doc['seconds']:.0f} s)")
        tables.append(doc)

    from .checks import (claims_tally, comparisons, copying_checks, evaluate_claims, recognition_checks,
                         sanity_checks, served_verdicts, shape_comparison, variant_report)
    sanity = sanity_checks(tables, clf_report, cfg)
    recognition = recognition_checks(tables, clf_report)
    sanity += recognition
    by_table = {t["id"]: t for t in tables}
    claims = evaluate_claims(by_table, store, tabs, recognition)
    copying = copying_checks(by_table, store, tabs)
    served = served_configs()
    ids = {c: load_config(CONFIGS_DIR / c).get("id") for c in served}
    first_of = {}      # the model as served: the served config's row named by its id (else its first row)
    for r in rows:
        if r.kind == "model" and r.config in served and (r.id == ids[r.config] or r.config not in first_of):
            first_of[r.config] = r.id
    learned = [rid for config, rid in first_of.items() if method_for(load_config(CONFIGS_DIR / config)).trainable]
    doc = {"format": "motion-futures/results", "version": 2,
           "columns": {c: {"label": v.label, "unit": v.unit, "better": v.better} for c, v in COLUMNS.items()},
           "k": k, "fps": FPS, "training_seeds": cfg["training_seeds"], "sampling_seeds": cfg["sampling_seeds"],
           "bootstrap": cfg["bootstrap"], "min_people": S.MIN_PEOPLE, "min_takes": S.MIN_TAKES,
           "comparisons": comparisons(claims, copying),
           "models": served_hashes, "classifiers": clf_report,
           "classifier_config": {k2: v for k2, v in cfg["classifier"].items() if k2 != "selection"},
           "sanity": sanity, "claims": claims,
           "copying": copying, "served_learned": learned, "verdicts": served_verdicts(copying, learned),
           "shape": shape_comparison(by_table, store, tabs),
           "variants": variant_report(by_table, tabs),
           "data": data_summary(clips),
           "tables": tables, "skipped": skipped,
           "context_plot": cfg.get("context_plot", []), "length_plot": cfg.get("length_plot"),
           "classifier_seconds": round(clf_seconds, 1), "seconds": round(time.time() - started, 1)}
    doc["tally"] = claims_tally(claims)
    from .card import copying_tally, recognition_tally, summary
    from .report import _round
    doc["copying_tally"] = copying_tally(doc)
    doc["recognition_tally"] = recognition_tally(doc)
    doc["summary"] = summary(_round(doc))   # from the numbers as results.json stores them
    return doc


def data_summary(clips: list[Clip]) -> dict:
    """What the tables are cut from and the models learn from: people, takes and seconds on each side of
    the split, overall and per action (the model card and the Results page read this, never the clips)."""
    from ..data.balance import RULE as BALANCE_RULE
    test = [c for c in clips if c.split.role == "test"]
    train = [c for c in clips if c.split.role != "test"]

    def side(cs: list[Clip]) -> dict:
        return {"people": sorted({str(c.subject) for c in cs}, key=lambda p: (len(p), p)), "takes": len(cs),
                "seconds": round(sum(len(c) for c in cs) / FPS, 1)}
    actions = {a: {"group": group_of(a), "train": side([c for c in train if c.action == a]),
                   "test": side([c for c in test if c.action == a])} for a in sorted({c.action for c in clips})}
    return {"fps": FPS, "joints": SKELETON.num_joints, "clips": len(clips), "actions": len(actions),
            "heldout_people": side(test)["people"], "heldout_takes": len(test), "heldout_actions": heldout_actions(clips),
            "heldout_seconds": side(test)["seconds"],
            "train_people": len(side(train)["people"]), "train_people_list": side(train)["people"],
            "train_takes": len(train), "train_seconds": side(train)["seconds"],
            "per_action": actions, "groups": list(GROUPS), "balance": BALANCE_RULE,
            "train_only_actions": [a for a, v in actions.items() if not v["test"]["takes"]]}


def _run_row(r: Row, tab: Table, loaded, cfg: dict, k: int, actions: list[str], ctx: Context,
             train_clips: list[Clip], derived: dict, rows: list[Row]) -> tuple[dict | None, list[RunResult]]:
    table = tab.cfg
    t = int(table["horizon_frames"])
    base = {"id": r.id, "label": r.label, "kind": r.kind, "group": r.group, "note": r.note,
            "controls": r.controls, "notes": []}
    results: list[RunResult] = []
    if not tab.items:
        return None, []
    if r.kind in ("oracle", "noise"):
        if not table["truth"]:
            return None, []
        seeds = list(cfg["sampling_seeds"]) if r.kind == "noise" else [cfg["sampling_seeds"][0]]
        for s in seeds:
            results.append(run_metrics(predict_truth(r, tab, k, float(cfg["noise_sigma"]), s), tab, ctx, not results))
        base.update({"k": 1 if r.kind == "oracle" else k, "history_frames": None, "train_seeds": [], "runs": len(results)})
        if r.kind == "noise":
            base["sigma"] = float(cfg["noise_sigma"])
        return base, results
    if r.kind == "baseline":
        if not table["truth"]:
            return None, []
        samples, notes = predict_baseline(r, tab, train_clips, cfg)
        base["notes"] += notes
        results.append(run_metrics(samples, tab, ctx, True))
        base.update({"k": 1, "history_frames": r.history, "train_seeds": [], "runs": 1})
        return base, results
    if r.kind == "projected":
        got = derived.get(r.id)
        if not got:
            return None, []
        base.update({"k": k, "train_seeds": None, "runs": len(got), "parent": r.parent})
        base["notes"] += got[0][1] if got else []
        return base, [x for x, _ in got]
    runs, notes = loaded
    if not runs:
        return None, []
    base["notes"] += notes
    first = runs[0].entry
    ctl = controls_of(first)
    if table.get("conditioned_only") and "actions" not in ctl:
        return None, []
    need = int(first["params"]["history_frames"])
    if need > int(table["history_frames"]):
        base["skipped"] = f"needs {need} history frames; this table's windows have {table['history_frames']}"
        return base, []
    usable = [run for run in runs if max_horizon(run.entry) >= t]
    if not usable:
        base["skipped"] = f"predicts at most {max_horizon(first)} frames; this table needs {t}"
        return base, []
    if len(usable) < len(runs):
        base["notes"].append(f"training seeds {[x.seed for x in runs if x not in usable]} predict at most "
                             f"{min(max_horizon(x.entry) for x in runs if x not in usable)} frames (stale export)")
    if table.get("seeds") == "first":
        usable = usable[:1]
    stochastic = "k" in ctl
    sampling = list(cfg["sampling_seeds"]) if stochastic else [cfg["sampling_seeds"][0]]
    projected = [x for x in rows if x.kind == "projected" and x.parent == r.id
                 and (x.tables is None or table["id"] in x.tables)]
    for run in usable:
        for s in sampling:
            samples, refused = predict_model(run, r, tab, k, s, actions)
            base["notes"] += [n for n in refused if n not in base["notes"]]
            if not any(x is not None for x in samples):
                continue
            results.append(run_metrics(samples, tab, ctx, not results))
            for p in projected:
                proj = [None if x is None else Sample(project_onto_history(x.futures, x.history), x.lengths,
                                                      x.samples, x.history) for x in samples]
                derived.setdefault(p.id, []).append((run_metrics(proj, tab, ctx, len(derived.get(p.id, [])) == 0),
                                                     [f"{r.label}: {len(usable)} training seeds x {len(sampling)} sampling seeds"]))
    base.update({"k": k if stochastic else 1, "history_frames": need, "runs": len(results),
                 "train_seeds": [run.seed for run in usable], "sampling_seeds": sampling,
                 "hashes": {str(run.seed): run.entry["hash"] for run in usable}})
    if stochastic and len(usable) < 2:
        base["notes"].append("one training seed: the bar holds the take bootstrap only, no seed variance")
    if not stochastic:
        base["notes"].append("deterministic: one future per history; sampling seeds do not apply")
    return base, results
