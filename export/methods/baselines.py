"""The two baselines: zero-velocity and the deterministic regression GRU."""
from __future__ import annotations

import numpy as np
import torch
from torch import nn

from ..data.clip import Clip
from ..data.skeleton import SKELETON
from ..data.windows import window_weights, windows
from ..models.regression_gru import RegressionGRU
from ..models.zero_velocity import ZeroVelocity
from ..ops.floor import floor_penalty
from ..ops.time_scale import slow_settings, slow_share
from .base import GraphDef, Method, TensorSpec, TrainingData

J = SKELETON.num_joints


class _DirectMethod(Method):
    """history [batch, N, J, 3] -> future [batch, T, J, 3], one deterministic future per history."""

    def controls(self, actions: list[str]) -> list[dict]:
        # Longer horizons repeat the graph on its own output (export/sample/direct.py).
        return [{"id": "horizon", "type": "number", "label": "Horizon (s)", "min": 1, "max": 5, "step": 0.5,
                 "default": 2, "help": "How far to predict; past 1 s the model is applied to its own output."}]

    def graphs(self, model: nn.Module) -> dict[str, GraphDef]:
        example = torch.randn(2, self.history_frames, J, 3)
        return {"predict": GraphDef(
            module=model, example_inputs=(example,),
            inputs=[TensorSpec("history", ["batch", self.history_frames, J, 3])],
            outputs=[TensorSpec("future", ["batch", self.future_frames, J, 3])])}


class ZeroVelocityMethod(_DirectMethod):
    name = "zero_velocity"
    trainable = False

    def prepare(self, clips: list[Clip]) -> TrainingData:
        return TrainingData({"none": torch.zeros(1)})

    def build(self, data: TrainingData) -> nn.Module:
        return ZeroVelocity(self.future_frames)


class RegressionMethod(_DirectMethod):
    name = "regression"

    def prepare(self, clips: list[Clip]) -> TrainingData:
        t = self.cfg.get("train", {})
        ws = windows(clips, "train", self.history_frames + self.future_frames, self.history_frames,
                     stride=int(t.get("stride", 1)), mirror=bool(t.get("mirror", True)))
        if not ws:
            raise ValueError("no training windows: every clip's training part is shorter than "
                             f"{self.history_frames + self.future_frames} frames")
        motion = torch.from_numpy(np.stack([w.positions for w in ws])).float()   # [W, N+T, J, 3]
        hist, fut = motion[:, :self.history_frames], motion[:, self.history_frames:]
        offsets = fut - hist[:, -1:]
        stats = {
            "pose_mean": hist.reshape(-1, J * 3).mean(0),
            "pose_std": hist.reshape(-1, J * 3).std(0).clamp_min(1e-3),
            "offset_std": offsets.reshape(-1, J * 3).std(0).clamp_min(1e-3),
            "step_std": hist.reshape(len(hist), self.history_frames, J * 3).diff(dim=1).reshape(-1, J * 3).std(0).clamp_min(1e-4),
        }
        return TrainingData({"history": hist, "future": fut}, stats, {"windows": len(ws)}, window_weights(ws))

    def build(self, data: TrainingData) -> nn.Module:
        m = self.cfg.get("model", {})
        s = data.stats
        return RegressionGRU(J, self.future_frames, int(m.get("hidden", 64)), int(m.get("dct_bases", 10)),
                             s["pose_mean"], s["pose_std"], s["offset_std"], bool(m.get("keep_bones", True)),
                             bool(m.get("seam", True)), s.get("step_std"), bool(m.get("history_steps", False)))

    def loss(self, model, batch, step):
        # a share of the windows replayed slowly (ops/time_scale.py; a labelled variant, as the sampling methods';
        # configs/regression.json also reads the history's steps, models/inputs.py). Not measured on its own
        # before serving: the evaluation's rows before and after this pass are in the session's note.
        s = slow_settings(self.cfg)
        history, future = slow_share(batch["history"], batch["future"], s["fraction"], s["min"], s["log"])
        pred = model(history)
        err = torch.linalg.vector_norm(pred - future, dim=-1).mean()  # mean per-joint error, metres
        floor = floor_penalty(pred)                                            # feet may not sink (ops/floor.py)
        w = float(self.cfg.get("loss", {}).get("floor", 100.0))
        return err + w * floor, {"mpjpe": float(err.detach()), "floor": float(floor.detach())}
