"""What every method provides to the shared pipeline: data -> model -> loss -> ONNX graphs -> manifest.

The training loop, the exporter, the manifest writer and the predictors only talk to this
interface, so adding a method means adding one subclass (plus its model and predictor).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import torch
from torch import nn

from ..data.clip import Clip


@dataclass
class TensorSpec:
    name: str
    shape: list            # ints, or "batch" for the dynamic axis
    dtype: str = "float32"

    def to_contract(self) -> dict:
        return {"name": self.name, "shape": list(self.shape), "dtype": self.dtype}


@dataclass
class GraphDef:
    """One ONNX graph: a module, example inputs (batch 2) and the contract's names and shapes."""
    module: nn.Module
    example_inputs: tuple[torch.Tensor, ...]
    inputs: list[TensorSpec]
    outputs: list[TensorSpec]


@dataclass
class TrainingData:
    tensors: dict[str, torch.Tensor]          # equal first dimension: one row per training example
    stats: dict[str, torch.Tensor] = field(default_factory=dict)
    notes: dict = field(default_factory=dict)
    weights: np.ndarray | None = None          # per-example sampling weights (data/balance.py); None: uniform

    def __len__(self) -> int:
        return len(next(iter(self.tensors.values())))


class Method:
    name = "method"
    trainable = True

    def __init__(self, cfg: dict):
        self.cfg = cfg
        self.history_frames = int(cfg["history_frames"])
        self.future_frames = int(cfg["future_frames"])
        self.envelope: dict | None = None      # the training histories' envelope (pipeline.train)

    def prepare(self, clips: list[Clip]) -> TrainingData:
        raise NotImplementedError

    def build(self, data: TrainingData) -> nn.Module:
        raise NotImplementedError

    def loss(self, model: nn.Module, batch: dict[str, torch.Tensor], step: int) -> tuple[torch.Tensor, dict]:
        raise NotImplementedError

    def graphs(self, model: nn.Module) -> dict[str, GraphDef]:
        raise NotImplementedError

    def params(self, model: nn.Module) -> dict:
        out = {"history_frames": self.history_frames, "future_frames": self.future_frames}
        if self.envelope is not None:
            out["envelope"] = self.envelope
        return out

    def controls(self, actions: list[str]) -> list[dict]:
        return []

    def files(self, model: nn.Module) -> dict[str, dict]:
        """Extra JSON artefacts (name -> document), e.g. keypose centres."""
        return {}
