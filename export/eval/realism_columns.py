"""The realism columns of a table (Evaluation v3): what each item and each run gives to the harness.

Per item (one window and its K futures): the per-joint error in cm beside the field's whole-pose ADE,
the mean joint speed and root speed in each second of the future beside the truth's (for the ratios),
foot skating, hip vertical range, whether the truth lies outside the samples, the pose spread in cm,
and the share of samples that last the whole horizon. Per run (a set of items): how the first second's
speed follows the history's (Spearman), PSKL both ways (Keyposes sec. 4.3) and CMD (BeLFusion), each
also per action group. The measures themselves are export/eval/realism/ and metrics.py.
"""
from __future__ import annotations

import numpy as np

from ..data.vocabulary import GROUPS, group as group_of
from . import metrics as M
from .realism import (cmd_by_class, contact_speeds, displacement_per_frame, follow, full_length_share,
                      hip_vertical_range, history_speed, joint_speed_per_second, median_contact_speed, mpjpe_cm,
                      outside, pose_spread_cm, root_speed_per_second)

SECONDS = 5                         # per-second columns exist for the first five seconds (the 5 s table)
SET_COLUMNS = ("follow", "pskl_gp", "pskl_pg", "cmd")
# ratio column -> (numerator, denominator): a ratio of means over the items both have (realism.speed)
RATIOS = {**{f"speed_ratio_s{s}": (f"speed_s{s}", f"truth_speed_s{s}") for s in range(1, SECONDS + 1)},
          **{f"root_ratio_s{s}": (f"root_s{s}", f"truth_root_s{s}") for s in range(1, SECONDS + 1)}}


def outside_naive(futures: np.ndarray, truth: np.ndarray) -> bool:
    """The audit's rule: the truth farther from the samples' mean than every sample is. Even a calibrated
    sampler puts the truth outside far more often than 1/(K+1) under it (each sample helped place the
    mean), so it is reported beside coverage.outside, never instead of it."""
    t = len(truth)
    pts = M.root_relative(np.asarray(futures, dtype=np.float64)[:, :t]).reshape(len(futures), -1)
    mean = pts.mean(0)
    d_truth = np.linalg.norm(M.root_relative(np.asarray(truth, dtype=np.float64)).reshape(-1) - mean)
    return bool(d_truth > np.linalg.norm(pts - mean, axis=1).max())


def item_realism(futures: np.ndarray, lengths: np.ndarray, truth: np.ndarray | None, history: np.ndarray,
                 horizon: int) -> dict[str, float]:
    """One item's realism values (see the module docstring); `truth` None: only what needs no truth."""
    f = np.asarray(futures, dtype=np.float64)[:, :horizon]
    k = len(f)
    out: dict[str, float] = {"history_speed": float(history_speed(history))}
    speeds = joint_speed_per_second(f, history).mean(0)
    roots = root_speed_per_second(f, history).mean(0)
    for s in range(min(len(speeds), SECONDS)):
        out[f"speed_s{s + 1}"], out[f"root_s{s + 1}"] = float(speeds[s]), float(roots[s])
    out["hip_range"] = float(np.mean(hip_vertical_range(f)))
    out["skate"] = median_contact_speed(np.concatenate([contact_speeds(x) for x in f]))
    if k > 1:
        last, over = pose_spread_cm(f)
        out["spread_cm"], out["spread_all_cm"] = float(last), float(over)
    out["full"] = 100.0 * full_length_share(np.minimum(lengths, horizon), horizon)
    if truth is not None:
        out["mpjpe_cm"], out["mpjpe_f_cm"] = mpjpe_cm(f, truth, root_relative=True)
        ts, tr = joint_speed_per_second(truth, history), root_speed_per_second(truth, history)
        for s in range(min(len(ts), SECONDS)):
            out[f"truth_speed_s{s + 1}"], out[f"truth_root_s{s + 1}"] = float(ts[s]), float(tr[s])
        if k > 1:
            out["outside"] = 100.0 * outside(f, truth)
            out["outside_naive"] = 100.0 * outside_naive(f, truth)
    return out


def set_realism(futures: list[np.ndarray | None], truths: list[np.ndarray] | None, actions: list[str],
                values: dict[str, np.ndarray]) -> dict[str, float]:
    """A run's set-level values, overall and per action group (keys "col" and "col@group"): Spearman of
    the history's speed against the first predicted second's, and, with truths, PSKL both ways on
    root-relative poses (every sample of every item against the captured futures) and CMD by group."""
    out: dict[str, float] = {}
    groups = np.array([group_of(a) for a in actions])
    done = np.array([f is not None for f in futures])
    for g in (None, *GROUPS):
        mask = done & (groups == g) if g else done
        tag = f"@{g}" if g else ""
        if not mask.any():
            continue
        if "speed_s1" in values:
            out[f"follow{tag}"] = follow(values["history_speed"][mask], values["speed_s1"][mask])
        if truths is None:
            continue
        idx = np.flatnonzero(mask)
        pred = np.concatenate([M.root_relative(futures[i]) for i in idx])
        real = np.stack([M.root_relative(truths[i]) for i in idx])
        if len(idx) >= 2:
            out[f"pskl_gp{tag}"], out[f"pskl_pg{tag}"] = M.pskl(real, pred)
        per_window = np.stack([displacement_per_frame(futures[i]) for i in idx])
        reference = {c: float(displacement_per_frame(real[groups[idx] == c]).mean()) for c in set(groups[idx])}
        out[f"cmd{tag}"] = cmd_by_class(per_window, groups[idx], reference)
    return out
