"""The same graph evaluated in float64: the reference that measures a graph's float32 error.

Every float32 initializer, constant, cast target and graph input/output becomes float64, and the
graph runs on onnx's reference evaluator (numpy, so float64 throughout: onnxruntime has no double
kernel for some ops, e.g. Erf). The weights are the float32 ones, exactly widened, so the only
difference to the served graph is the precision of the arithmetic. `python -m export vectors` uses
it to derive each vector family's tolerance (export/tolerance.py).
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
import onnx
from onnx import TensorProto, numpy_helper
from onnx.reference import ReferenceEvaluator


def widen(model: onnx.ModelProto) -> onnx.ModelProto:
    """A float64 copy of a float32 graph, with the same weights."""
    out = onnx.ModelProto()
    out.CopyFrom(model)
    g = out.graph
    for init in g.initializer:
        if init.data_type == TensorProto.FLOAT:
            init.CopyFrom(numpy_helper.from_array(numpy_helper.to_array(init).astype(np.float64), init.name))
    for vi in list(g.input) + list(g.output) + list(g.value_info):
        if vi.type.tensor_type.elem_type == TensorProto.FLOAT:
            vi.type.tensor_type.elem_type = TensorProto.DOUBLE
    for node in g.node:
        for a in node.attribute:
            if node.op_type == "Cast" and a.name == "to" and a.i == TensorProto.FLOAT:
                a.i = TensorProto.DOUBLE
            elif a.type == onnx.AttributeProto.TENSOR and a.t.data_type == TensorProto.FLOAT:
                a.t.CopyFrom(numpy_helper.from_array(numpy_helper.to_array(a.t).astype(np.float64), a.t.name))
            elif a.type == onnx.AttributeProto.GRAPH:
                raise ValueError(f"{node.op_type}: graphs with sub-graphs are not widened (none is exported)")
    return out


class Float64Session:
    """Runs a float32 ONNX file in float64 with the interface of an onnxruntime session's run()."""

    def __init__(self, path: Path):
        self._eval = ReferenceEvaluator(widen(onnx.load(str(path))))

    def run(self, names: list[str], feeds: dict[str, np.ndarray]) -> list[np.ndarray]:
        wide = {k: (v.astype(np.float64) if v.dtype == np.float32 else v) for k, v in feeds.items()}
        with np.errstate(over="ignore"):      # the reference sigmoid's exp(-x) overflows to 1/inf = 0, correctly
            return self._eval.run(names, wide)
