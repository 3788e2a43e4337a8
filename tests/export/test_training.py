"""The shared training loop and export path: determinism, resumption, DDP, ONNX parity."""
import json
import os
import subprocess
import sys

import numpy as np
import onnx
import pytest
import torch

from export.config import load_config, override
from export.onnx.export import check_parity, to_onnx
from export.paths import ROOT
from export.pipeline import train

TINY = {"train.steps": 12, "train.batch_size": 8, "train.checkpoint_every": 6, "model.hidden": 16, "train.stride": 4}


def tiny_cfg():
    return override(load_config("regression.json"), **TINY)


def test_a_tiny_config_trained_twice_gives_byte_identical_onnx(clips):
    blobs = []
    for _ in range(2):
        method, model = train(tiny_cfg(), list(clips.values()), progress=False)
        blobs.append(to_onnx(method.graphs(model)["predict"]))
    assert blobs[0] == blobs[1]
    assert len(blobs[0]) > 10_000


def test_resuming_from_a_checkpoint_equals_an_uninterrupted_run(clips, tmp_path):
    cl = list(clips.values())
    _, full = train(tiny_cfg(), cl, tmp_path / "full", progress=False)
    train(tiny_cfg(), cl, tmp_path / "paused", progress=False, stop_at=6)
    assert torch.load(tmp_path / "paused" / "checkpoint.pt", weights_only=False)["step"] == 6
    _, resumed = train(tiny_cfg(), cl, tmp_path / "paused", resume=True, progress=False)
    for (k, a), b in zip(full.state_dict().items(), resumed.state_dict().values()):
        assert torch.equal(a, b), k


def test_a_finished_checkpoint_resumes_to_the_same_model_and_another_config_is_refused(clips, tmp_path):
    cl = list(clips.values())
    _, full = train(tiny_cfg(), cl, tmp_path / "run", progress=False)
    # `models --resume` exports what `train` left: a finished run is not trained again
    _, again = train(tiny_cfg(), cl, tmp_path / "run", resume=True, progress=False)
    for (k, a), b in zip(full.state_dict().items(), again.state_dict().values()):
        assert torch.equal(a, b), k
    with pytest.raises(ValueError, match="another config"):
        train(override(tiny_cfg(), **{"train.lr": 0.5}), cl, tmp_path / "run", resume=True, progress=False)
    # what training never reads (the sampling defaults, the words) resumes: the same weights, not retrained
    cfg = override(tiny_cfg(), description="served at another temperature")
    cfg["sampling"] = {"temperature": 1.75}
    _, resampled = train(cfg, cl, tmp_path / "run", resume=True, progress=False)
    for (k, a), b in zip(full.state_dict().items(), resampled.state_dict().values()):
        assert torch.equal(a, b), k


def test_onnx_matches_torch_and_the_check_can_fail(clips):
    method, model = train(tiny_cfg(), list(clips.values()), progress=False)
    graph = method.graphs(model)["predict"]
    blob = to_onnx(graph)
    assert check_parity(graph, blob) < 1e-4
    m = onnx.load_from_string(blob)
    assert m.opset_import[0].version >= 18 and not m.graph.value_info and not m.doc_string
    dims = m.graph.input[0].type.tensor_type.shape.dim
    assert dims[0].dim_param and [d.dim_value for d in dims[1:]] == [10, 18, 3]  # dynamic batch
    # a perturbed weight must be caught
    with torch.no_grad():
        model.head[-1].bias.add_(0.05)
    with pytest.raises(AssertionError, match="differs from torch"):
        check_parity(graph, blob)


def _ddp_and_one_process(tmp_path, cfg):
    """Train `cfg` 4 steps on 2 gloo ranks and on one process; (the one-process weights, each rank's)."""
    cfg_path = tmp_path / "tiny.json"
    cfg_path.write_text(json.dumps(cfg))
    env = {**os.environ, "PYTHONPATH": str(ROOT), "OMP_NUM_THREADS": "1"}
    common = ["-m", "export", "train", "--config", str(cfg_path), "--steps", "4", "--batch-size", "8"]
    bindir = os.path.dirname(sys.executable)
    subprocess.run([os.path.join(bindir, "torchrun"), "--standalone", "--nproc_per_node", "2", *common,
                    "--run-dir", str(tmp_path / "ddp")], check=True, env=env, cwd=ROOT, timeout=300,
                   capture_output=True)
    subprocess.run([sys.executable, *common, "--run-dir", str(tmp_path / "one")], check=True, env=env,
                   cwd=ROOT, timeout=300, capture_output=True)
    single = torch.load(tmp_path / "one" / "weights.pt")
    return single, [torch.load(tmp_path / "ddp" / f"weights-rank{rank}.pt") for rank in (0, 1)]


def test_ddp_with_two_gloo_ranks_matches_one_process(tmp_path, clips):
    # Bit-for-bit equality holds for a loss that draws no random numbers: the regression GRU without its
    # slowed windows (ops/time_scale.py draws them per process; see the next test).
    assert tiny_cfg()["augment"]["slow_fraction"] > 0   # the served regression config does slow windows
    cfg = override(tiny_cfg(), **{"augment.slow_fraction": 0.0})
    single, ranks = _ddp_and_one_process(tmp_path, cfg)
    for rank, ranked in enumerate(ranks):
        for k, v in single.items():
            np.testing.assert_allclose(ranked[k].numpy(), v.numpy(), atol=1e-5, err_msg=f"rank {rank} {k}")
    # and the four steps did move the weights
    _, init = train(override(cfg, **{"train.steps": 0}), list(clips.values()), progress=False)
    moved = max(float((single[k] - v).abs().max()) for k, v in init.state_dict().items())
    assert moved > 1e-4


@pytest.mark.xfail(strict=True, raises=AssertionError, reason="known gap: random training draws (slowed windows, WAT's and LCP-VAE's "
                   "samples) come from each process's generator, so N processes match one only in distribution; "
                   "drawing them per example of the global batch in train/loop.py would retrain every served model")
def test_ddp_with_random_slowed_windows_matches_one_process(tmp_path, clips):
    single, ranks = _ddp_and_one_process(tmp_path, tiny_cfg())
    for ranked in ranks:
        for k, v in single.items():
            np.testing.assert_allclose(ranked[k].numpy(), v.numpy(), atol=1e-5)
