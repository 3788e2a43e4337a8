"""The fused GRU rollout: written as ONNX GRU nodes, it computes what torch's GRUCell loop computes."""
import collections

import onnx
import pytest
import torch
from torch import nn

from export.methods.base import GraphDef, TensorSpec
from export.models.gru_rollout import GruRollout, RolloutGraph
from export.onnx.export import check_parity, to_onnx

K, H, C, T = 6, 5, 4, 7


class CellLoop(RolloutGraph):
    """A decoder written with torch's own GRUCell (its gate order is what the writer must convert)."""

    def __init__(self, context: bool, residual: bool, extra_context: bool = False):
        super().__init__()
        torch.manual_seed(1)
        self.has_context, self.residual, self.extra_context = context, residual, extra_context
        self.cell = nn.GRUCell((C if context else 0) + K, H)
        self.out = nn.Linear(H, K)
        self.init = nn.Linear(K, H)

    def setup(self, seed, ctx=None):
        start = (seed.flatten(1) * 2.0, torch.tanh(self.init(seed.flatten(1))))
        return start + ((ctx * 1.0,) if self.has_context or self.extra_context else ())

    def forward(self, seed, ctx=None):
        x, h, *rest = self.setup(seed, ctx)
        x0, frames = x, []
        for _ in range(T):
            h = self.cell(x if not self.has_context else torch.cat([rest[0], x], -1), h)
            x = (x if self.residual else x0) + self.out(h)
            frames.append(x)
        return torch.stack(frames, 1).reshape(-1, T, K // 3, 3)

    def rollout(self) -> GruRollout:
        return GruRollout(self.cell.weight_ih, self.cell.bias_ih, self.cell.weight_hh, self.cell.bias_hh,
                          self.out.weight, self.out.bias, steps=T, frame_shape=(K // 3, 3), residual=self.residual)


def graph(module: CellLoop) -> GraphDef:
    inputs = [TensorSpec("seed", ["batch", K // 3, 3])]
    examples = (torch.randn(2, K // 3, 3),)
    if module.has_context or module.extra_context:
        inputs.append(TensorSpec("ctx", ["batch", C]))
        examples += (torch.randn(2, C),)
    return GraphDef(module, examples, inputs, [TensorSpec("future", ["batch", T, K // 3, 3])])


@pytest.mark.parametrize("context,residual", [(True, True), (False, True), (False, False), (True, False)])
def test_the_fused_rollout_matches_torchs_gru_cell_loop(context, residual):
    module = CellLoop(context, residual).eval()
    g = graph(module)
    blob = to_onnx(g)
    assert check_parity(g, blob, batch=9, seed=2) < 1e-5
    seed, ctx = torch.randn(3, K // 3, 3), torch.randn(3, C)
    x, h, *rest = module.setup(seed, ctx)
    with torch.no_grad():   # the rollout's own torch form agrees too
        assert torch.allclose(module.rollout().run(x, h, rest[0] if rest else None), module(seed, ctx), atol=1e-5)
    ops = collections.Counter(n.op_type for n in onnx.load_from_string(blob).graph.node)
    assert ops["GRU"] == T
    assert sum(ops.values()) <= T * (5 if context else 4) + 12   # a handful of nodes per step


def test_a_setup_that_does_not_match_the_rollouts_context_is_refused():
    module = CellLoop(context=False, residual=True, extra_context=True).eval()
    with pytest.raises(ValueError, match="context"):
        to_onnx(graph(module))
