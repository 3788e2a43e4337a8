"""The one training loop every method uses: seeded, checkpointed, resumable, with a progress bar.

On one process it is deterministic (one thread, deterministic kernels), so a config trained
twice gives identical weights. Under `torchrun --nproc_per_node N` it runs DistributedDataParallel
with gloo on the CPU: every step draws one global batch from a seeded permutation and each rank
takes its own contiguous shard of it, so N ranks see the same examples as one process would.
"""
from __future__ import annotations

import json
import os
import random
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import torch
import torch.distributed as dist
from torch import nn
from tqdm import tqdm

from ..methods.base import Method, TrainingData


@dataclass
class TrainConfig:
    steps: int = 1000
    batch_size: int = 64
    lr: float = 1e-3
    seed: int = 0
    checkpoint_every: int = 500
    grad_clip: float = 1.0

    @classmethod
    def from_cfg(cls, cfg: dict, **overrides) -> "TrainConfig":
        t = {k: v for k, v in cfg.get("train", {}).items() if k in cls.__dataclass_fields__}
        t.update({k: v for k, v in overrides.items() if v is not None})
        return cls(**t)


def seed_everything(seed: int) -> None:
    random.seed(seed)
    np.random.seed(seed % 2**32)
    torch.manual_seed(seed)


def deterministic() -> None:
    torch.set_num_threads(1)
    torch.use_deterministic_algorithms(True)


def world() -> tuple[int, int]:
    """(rank, size) when launched by torchrun, else (0, 1)."""
    size = int(os.environ.get("WORLD_SIZE", "1"))
    if size > 1 and not dist.is_initialized():
        dist.init_process_group("gloo")
    return (dist.get_rank(), dist.get_world_size()) if size > 1 else (0, 1)


def batch_indices(n: int, batch_size: int, steps: int, seed: int, weights: np.ndarray | None = None) -> np.ndarray:
    """[steps, batch_size] example indices: seeded epochs of permutations, concatenated; with `weights`,
    seeded draws with replacement in proportion to them (the balance rule, data/balance.py)."""
    rng = np.random.default_rng(seed)
    if weights is not None:
        p = np.asarray(weights, dtype=np.float64)
        if p.shape != (n,) or (p < 0).any() or not p.sum() > 0:
            raise ValueError(f"sampling weights must be {n} non-negative numbers with a positive sum")
        return rng.choice(n, size=(steps, batch_size), replace=True, p=p / p.sum())
    needed = steps * batch_size
    order = [rng.permutation(n) for _ in range(-(-needed // n))]
    return np.concatenate(order or [np.zeros(0, dtype=int)])[:needed].reshape(steps, batch_size)


def fit(method: Method, model: nn.Module, data: TrainingData, tc: TrainConfig,
        run_dir: Path | None = None, resume: bool = False, progress: bool = True,
        stop_at: int | None = None) -> nn.Module:
    """Train to tc.steps (or pause at `stop_at`, checkpointed, to resume later with resume=True)."""
    rank, size = world()
    if tc.batch_size % size:
        raise ValueError(f"batch size {tc.batch_size} does not split over {size} processes")
    deterministic()
    seed_everything(tc.seed)
    net = nn.parallel.DistributedDataParallel(model) if size > 1 else model
    optim = torch.optim.Adam(model.parameters(), lr=tc.lr)
    sched = torch.optim.lr_scheduler.CosineAnnealingLR(optim, T_max=max(1, tc.steps), eta_min=tc.lr * 0.05)
    plan = batch_indices(len(data), tc.batch_size, tc.steps, tc.seed, data.weights)
    shard = tc.batch_size // size
    start = 0
    ckpt = run_dir / "checkpoint.pt" if run_dir else None
    if resume and ckpt and ckpt.exists():
        state = torch.load(ckpt, weights_only=False)
        # A checkpoint continues only the run it was saved from: another config would be a different model.
        if "config" in state and _trained_part(json.loads(state["config"])) != _trained_part(method.cfg):
            raise ValueError(f"{ckpt} was saved by another config than {method.cfg['id']}'s: delete it or train "
                             "without resuming")
        model.load_state_dict(state["model"])
        optim.load_state_dict(state["optim"])
        sched.load_state_dict(state["sched"])
        torch.set_rng_state(state["torch_rng"])
        start = state["step"]

    end = min(tc.steps, stop_at) if stop_at else tc.steps
    bar = tqdm(range(start, end), initial=start, total=tc.steps, desc=method.cfg["id"],
               disable=not progress or rank != 0, dynamic_ncols=True, mininterval=1.0)
    model.train()
    for step in bar:
        idx = torch.from_numpy(plan[step, rank * shard:(rank + 1) * shard])
        batch = {k: v[idx] for k, v in data.tensors.items()}
        loss, logs = method.loss(net, batch, step)
        optim.zero_grad(set_to_none=True)
        loss.backward()
        if tc.grad_clip:
            nn.utils.clip_grad_norm_(model.parameters(), tc.grad_clip)
        optim.step()
        sched.step()
        if rank == 0 and step % 10 == 0:
            bar.set_postfix(loss=f"{loss.item():.4f}", **{k: f"{v:.4f}" for k, v in logs.items()}, refresh=False)
        if ckpt and rank == 0 and ((step + 1) % tc.checkpoint_every == 0 or step + 1 == end):
            _save(ckpt, model, optim, sched, step + 1, _config_key(method.cfg))
    model.eval()
    return model


def _config_key(cfg: dict) -> str:
    return json.dumps(cfg, sort_keys=True)


# What training never reads: the sampling defaults (a temperature, a sigma scale) and the words. A model
# re-served at another temperature is exported from its checkpoint, not trained again for 30-50 minutes.
_NOT_TRAINED = ("sampling", "label", "description")


def _trained_part(cfg: dict) -> dict:
    return {k: v for k, v in cfg.items() if k not in _NOT_TRAINED}


def _save(path: Path, model, optim, sched, step: int, config: str) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_suffix(".tmp")
    torch.save({"model": model.state_dict(), "optim": optim.state_dict(), "sched": sched.state_dict(),
                "torch_rng": torch.get_rng_state(), "step": step, "config": config}, tmp)
    os.replace(tmp, path)  # a crash mid-write never leaves a broken checkpoint
