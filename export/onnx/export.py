"""Writing one graph to a single small ONNX file, and checking it against torch.

torch's dynamo exporter (opset 18; 17 gives an invalid file here) with the weights inside the
file. It records a lot of metadata (doc strings, value_info, node metadata); that is stripped
before the file is written, and `check_parity` runs the stripped file.
"""
from __future__ import annotations

import hashlib
import inspect
import logging
import warnings
from pathlib import Path

import numpy as np
import onnx
import onnx.compose
import onnxruntime as ort
import torch

from ..methods.base import GraphDef
from ..models.gru_rollout import RolloutGraph, RolloutSetup
from .rollout import append_rollout

OPSET = 18
logging.getLogger("torch.onnx").setLevel(logging.ERROR)  # e.g. "torchvision is not installed"


def _strip(model: onnx.ModelProto) -> onnx.ModelProto:
    model.doc_string = ""
    model.producer_version = ""
    del model.metadata_props[:]
    del model.graph.value_info[:]
    model.graph.doc_string = ""
    for node in _all_nodes(model):
        node.doc_string = ""
        del node.metadata_props[:]
    for f in model.functions:
        f.doc_string = ""
        del f.metadata_props[:]
    for init in model.graph.initializer:
        init.doc_string = ""
    return model


def _all_nodes(model: onnx.ModelProto):
    stack = [model.graph] + [f for f in model.functions]
    while stack:
        g = stack.pop()
        for node in g.node:
            yield node
            for attr in node.attribute:
                if attr.type == onnx.AttributeProto.GRAPH:
                    stack.append(attr.g)
                elif attr.type == onnx.AttributeProto.GRAPHS:
                    stack.extend(attr.graphs)


def _torch_export(module: torch.nn.Module, example_inputs: tuple, input_names: list[str],
                  output_names: list[str]) -> onnx.ModelProto:
    batch = torch.export.Dim("batch", min=1, max=1024)
    with warnings.catch_warnings(), torch.no_grad():
        warnings.simplefilter("ignore")
        program = torch.onnx.export(
            module, example_inputs, input_names=input_names, output_names=output_names,
            dynamic_shapes=_batch_axes(module, batch, len(input_names)),
            opset_version=OPSET, dynamo=True, external_data=False, verbose=False, optimize=True)
    return program.model_proto


def _batch_axes(module: torch.nn.Module, batch, count: int) -> tuple:
    """Axis 0 of every input is the batch; a forward(*inputs) takes them as one nested tuple."""
    axes = tuple({0: batch} for _ in range(count))
    params = inspect.signature(module.forward).parameters.values()
    return (axes,) if any(p.kind is p.VAR_POSITIONAL for p in params) else axes


def to_onnx(graph: GraphDef) -> bytes:
    """Export, strip and serialise one graph with a dynamic batch axis on every tensor. A
    RolloutGraph is exported as its setup, then its GRU recurrence is written as fused nodes."""
    module = graph.module.eval()
    inputs = [s.name for s in graph.inputs]
    if isinstance(module, RolloutGraph):
        rollout = module.rollout()
        finish = module.finish()
        setup_outputs = ["setup_seed", "setup_h0"] + (["setup_context"] if rollout.context_size else [])
        setup_outputs += ["setup_anchor"] if finish is not None else []
        model = _torch_export(RolloutSetup(module), graph.example_inputs, inputs, setup_outputs)
        out = graph.outputs[0].name
        model = append_rollout(model, rollout, out if finish is None else "rollout_raw", keep=int(finish is not None))
        if finish is not None:
            # The finishing layer (models/finish.py) is exported by torch on its own and joined to the
            # rollout's frames and the setup's anchor (the history's last two frames).
            frames = torch.zeros(2, rollout.steps, *rollout.frame_shape)
            anchor = torch.zeros(2, 2, *rollout.frame_shape)
            tail = _torch_export(finish.eval(), (frames, anchor), ["frames", "anchor"], [out])
            model = onnx.compose.merge_models(model, tail, io_map=[("rollout_raw", "frames"), ("setup_anchor", "anchor")],
                                              prefix2="finish_", outputs=["finish_" + out])
            for o in model.graph.output:
                o.name = out if o.name == "finish_" + out else o.name
            for node in model.graph.node:
                node.output[:] = [out if n == "finish_" + out else n for n in node.output]
    else:
        model = _torch_export(module, graph.example_inputs, inputs, [s.name for s in graph.outputs])
    model = _strip(model)
    onnx.checker.check_model(model, full_check=True)
    return model.SerializeToString()


def write(graph: GraphDef, path: Path) -> dict:
    """Export, check against torch, write; returns the manifest's description of the graph."""
    data = to_onnx(graph)
    check_parity(graph, data)
    Path(path).write_bytes(data)
    return {"file": Path(path).name, "bytes": len(data), "sha256": hashlib.sha256(data).hexdigest(),
            "inputs": [s.to_contract() for s in graph.inputs],
            "outputs": [s.to_contract() for s in graph.outputs]}


def session(path_or_bytes, threads: int = 1) -> ort.InferenceSession:
    opts = ort.SessionOptions()
    opts.intra_op_num_threads = threads
    opts.inter_op_num_threads = 1
    opts.log_severity_level = 3
    src = str(path_or_bytes) if isinstance(path_or_bytes, Path) else path_or_bytes
    return ort.InferenceSession(src, opts, providers=["CPUExecutionProvider"])


def check_parity(graph: GraphDef, onnx_bytes: bytes, batch: int = 5, seed: int = 0, rtol: float = 1e-4) -> float:
    """Largest |onnx - torch| over the outputs, relative to each output's RMS size; raises past rtol."""
    gen = torch.Generator().manual_seed(seed)
    inputs = tuple(_like(x, batch, gen) for x in graph.example_inputs)
    with torch.no_grad():
        want = graph.module.eval()(*inputs)
    want = want if isinstance(want, (tuple, list)) else (want,)
    sess = session(onnx_bytes)
    got = sess.run(None, {s.name: x.numpy() for s, x in zip(graph.inputs, inputs)})
    worst = 0.0
    for spec, w, g in zip(graph.outputs, want, got):
        w = w.numpy()
        scale = max(float(np.sqrt(np.mean(w.astype(np.float64) ** 2))), 1e-6)
        err = float(np.abs(w - g).max()) / scale
        if err > rtol:
            raise AssertionError(f"{spec.name}: ONNX differs from torch by {err:.2e} of its RMS size")
        worst = max(worst, err)
    return worst


def _like(x: torch.Tensor, batch: int, gen: torch.Generator) -> torch.Tensor:
    shape = (batch,) + tuple(x.shape[1:])
    if x.dtype.is_floating_point:
        return torch.randn(shape, generator=gen) * x.std().clamp_min(0.1) + x.mean()
    return torch.randint(0, int(x.max()) + 1, shape, generator=gen, dtype=x.dtype)
