"""WAT (Transformer): the RNN method's training strategy (weak supervision, padding, stopping, the
loss of Eq. 6, the delta fit) with the Transformer CVAE of Fig. 3b. Only the model differs, and the
exported graphs keep the RNN's signatures, so the browser runs it with the same WAT predictor."""
from __future__ import annotations

from torch import nn

from ..data.skeleton import SKELETON
from ..models.wat_transformer import WatTransformer
from .base import TrainingData
from .wat import WatMethod


class WatTransformerMethod(WatMethod):
    name = "wat_transformer"
    model_class = WatTransformer

    def build(self, data: TrainingData) -> nn.Module:
        # The decoder's padded sequence and positional encodings need N (the RNN does not).
        return self.model_class(SKELETON.num_joints, len(self.actions), self.future_frames,
                                history_frames=self.history_frames, **self.cfg.get("model", {}), **data.stats)
