"""Slowed motion for training: a history and its own continuation replayed at a fraction of their speed.

A labelled variant beside both papers' data (neither slows its training motion). Why: on held-out people
every model here moved a held pose. A ballerina holding her arms above her head for two seconds (cmu_49_09,
a history at 0.03 m/s) got ten futures that all lowered the arms by 40-70 cm, because in the training
takes raised arms always come down: the models read the pose and ignored that the history did not move.
Their first predicted second ran at 0.2-0.4 m/s whatever the history's speed (0.01-1.4 m/s). Replayed
slowly, every training pose is also seen held or drifting, its future exactly as slow as its history, so
a model learns that the history's speed carries on into the future for every pose. Measured on WAT (RNN)
(methods/wat.py): 30% of the same pairs slowed, factors log-uniform in [0.02, 1] (near-held poses as
often as gently slowed ones), held-out follow rho 0.32 -> 0.53 and best-of-10 ADE / zero-velocity's
0.884 -> 0.833 (person 49's held poses 2.5-3.0x -> 1.8-2.2x), at the cost of speed in the 2nd second
(0.48 -> 0.35 of the truth's; the prior-speed term gives some back). Uniform in [0.1, 1] at 50%: 0.839, rho 0.50.

A slowed pair is the same motion, canonical at the same present (export/ops/facing.py): frame i of the
slowed sequence shows the original at time present + (i - present) * factor, positions linearly
interpolated (between frames 1/30 s apart the bones shorten by well under a millimetre). Training only;
no TypeScript twin.
"""
from __future__ import annotations

import torch


def slow_down(history: torch.Tensor, future: torch.Tensor, factor: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
    """history [B, N, J, 3] and its continuation future [B, T, J, 3], both canonical at the history's last
    frame, replayed at `factor` [B] (0 < factor <= 1) of their speed -> (history, future) of the same
    shapes. The present (the history's last frame) stays where it is."""
    if not bool(((factor > 0) & (factor <= 1)).all()):
        raise ValueError("slow-down factors must lie in (0, 1]")
    seq = torch.cat([history, future], 1)
    b, f = seq.shape[:2]
    present = history.shape[1] - 1
    times = present + (torch.arange(f, dtype=seq.dtype)[None] - present) * factor.to(seq.dtype)[:, None]
    lo = times.floor().clamp(0, f - 1)
    w = (times - lo)[:, :, None, None]
    lo = lo.long()
    hi = (lo + 1).clamp(max=f - 1)
    idx = lambda i: i[:, :, None, None].expand(-1, -1, *seq.shape[2:])
    out = seq.gather(1, idx(lo)) * (1 - w) + seq.gather(1, idx(hi)) * w
    return out[:, :present + 1], out[:, present + 1:]


def slowed_length(length: torch.Tensor, factor: torch.Tensor) -> torch.Tensor:
    """How many frames a continuation of `length` frames lasts when replayed at `factor` of its speed."""
    # a float32 factor of 0.1 is 0.100000001: without the margin 7 frames would last 69, not 70
    return torch.floor(length.to(torch.float64) / factor.to(torch.float64) + 1e-4).long()


def draw_factors(count: int, minimum: float, log: bool) -> torch.Tensor:
    """`count` slow-down factors from the global torch generator (training is seeded): uniform in
    [minimum, 1], or log-uniform there (as many within 0.02-0.1 as within 0.2-1: poses all but held)."""
    u = torch.rand(count)
    return minimum ** (1.0 - u) if log else minimum + (1.0 - minimum) * u


def slow_share(history: torch.Tensor, future: torch.Tensor, fraction: float, minimum: float, log: bool
               ) -> tuple[torch.Tensor, torch.Tensor]:
    """Training windows (history [B, N, J, 3] and future [B, T, J, 3], canonical at the history's last frame)
    with each replayed slowly with probability `fraction`, at draw_factors' factors."""
    if fraction <= 0:
        return history, future
    pick = torch.rand(len(history)) < fraction
    if not bool(pick.any()):
        return history, future
    factor = draw_factors(int(pick.sum()), minimum, log)
    history, future = history.clone(), future.clone()
    history[pick], future[pick] = slow_down(history[pick], future[pick], factor)
    return history, future


def slow_settings(cfg: dict) -> dict:
    """A config's `augment` block -> {fraction, min, log} (fraction 0, no slowing, is the papers' data)."""
    a = cfg.get("augment", {})
    return {"fraction": float(a.get("slow_fraction", 0.0)), "min": float(a.get("slow_min", 0.25)),
            "log": a.get("slow_spacing", "linear") == "log"}
