"""The committed models in public/models: valid, complete, and not stale against config, data and code."""
import gzip
import hashlib

import numpy as np
import pytest

from export.bench.native import cap_mb
from export.config import load_config, model_hash
from export.contract import load_json
from export.data.clip_json import read_clip
from export.manifest import read_manifest
from export.paths import CLIPS_DIR, MODELS_DIR
from export.sample.predictor import load_predictor
from export.sample.request import PredictError, Request

MANIFEST = read_manifest(MODELS_DIR / "manifest.json")


def test_manifest_uses_the_committed_data():
    index = load_json(CLIPS_DIR / "index.json", "clip-index")
    assert MANIFEST["data_hash"] == index["data_hash"]
    assert MANIFEST["skeleton"]["joints"] == index["skeleton"]["joints"]


@pytest.mark.parametrize("entry", [m for m in MANIFEST["models"] if cap_mb(m)], ids=lambda e: e["id"])
def test_committed_model_fits_its_issues_size_cap(entry):
    """A model's graphs together, gzipped at level 9 (what a browser downloads with compression)."""
    gz = sum(len(gzip.compress((MODELS_DIR / g["file"]).read_bytes(), 9)) for g in entry["graphs"].values())
    assert gz <= cap_mb(entry) * 1e6, f"{entry['id']}: {gz} bytes of ONNX gzipped"


@pytest.mark.parametrize("entry", MANIFEST["models"], ids=lambda e: e["id"])
def test_committed_model_is_not_stale(entry):
    cfg = load_config(entry["config"])
    assert cfg["id"] == entry["id"]
    assert entry["hash"] == model_hash(cfg, MANIFEST["data_hash"]), (
        f"{entry['id']} is stale against its config, the data or export/ code: run `make models`")
    for graph in entry["graphs"].values():
        blob = (MODELS_DIR / graph["file"]).read_bytes()
        assert hashlib.sha256(blob).hexdigest() == graph["sha256"] and len(blob) == graph["bytes"]


def test_python_predictor_follows_the_contract():
    index = load_json(CLIPS_DIR / "index.json", "clip-index")
    clip = read_clip(CLIPS_DIR / f"{index['default']['clip']}.json")      # a held-out walk
    p = load_predictor("regression-gru")
    pred = p.predict(clip.positions[:10], Request(k=1, seed=3, horizon_frames=50))
    assert pred.futures.shape == (1, 50, 18, 3) and pred.lengths.tolist() == [50]
    assert np.all(np.isfinite(pred.futures))
    # the future joins the history: its first frame is near the last observed pose
    assert np.abs(pred.futures[0, 0] - clip.positions[9]).max() < 0.15
    zero = load_predictor("zero-velocity").predict(clip.positions[:10], Request(horizon_frames=40))
    np.testing.assert_allclose(zero.futures[0], np.repeat(clip.positions[9:10], 40, axis=0), atol=1e-6)


@pytest.mark.parametrize("history, req, message", [
    (np.zeros((5, 18, 3)), Request(), "history has 5 frames; this model needs at least 10"),
    (np.full((10, 18, 3), np.nan), Request(), "NaN"),
    (np.zeros((10, 17, 3)), Request(), r"history must be \[frames, 18, 3\]"),
    (np.zeros((10, 18, 3)), Request(k=3), "deterministic"),
    (np.zeros((10, 18, 3)), Request(seed=-2), "seed"),
    (np.zeros((10, 18, 3)), Request(actions=["moonwalk"]), "unknown action 'moonwalk'"),
])
def test_bad_requests_get_clear_messages(history, req, message):
    with pytest.raises(PredictError, match=message):
        load_predictor("regression-gru").predict(history, req)


def test_missing_model_file_is_named(tmp_path):
    import shutil
    shutil.copy(MODELS_DIR / "manifest.json", tmp_path / "manifest.json")
    p = load_predictor("regression-gru", tmp_path)
    index = load_json(CLIPS_DIR / "index.json", "clip-index")
    history = read_clip(CLIPS_DIR / f"{index['default']['clip']}.json").positions[:10]   # a body the checks accept
    with pytest.raises(FileNotFoundError, match="regression-gru.predict.onnx: model file missing"):
        p.predict(history, Request())


def test_model_hash_covers_the_method_import_closure_only():
    from export.config import EXPORT_DIR, code_files
    files = {str(p.relative_to(EXPORT_DIR)) for p in code_files("export.methods.baselines")}
    assert {"methods/baselines.py", "models/regression_gru.py", "train/loop.py", "onnx/export.py",
            "pipeline.py", "data/skeleton.py"} <= files
    # Evaluation, other methods and the CLI do not change what the baselines compute.
    assert not any(f.startswith("eval/") for f in files)
    assert not {"methods/wat.py", "models/wat.py", "cli.py", "methods/__init__.py"} & files


def test_the_model_hash_reads_what_the_code_runs_not_its_comments_or_layout():
    from export.config import normalised_code
    code = '''"""Module docstring."""
import math


def f(x):
    """What f does."""
    # a comment
    return math.sqrt(x) + 1
'''
    reformatted = '''import math
def f( x ):   # another comment
    return (math.sqrt(x)
            + 1)
'''
    assert normalised_code(code) == normalised_code(reformatted)
    # a change to a function body, a constant or a name is a change to what runs
    for changed in (code.replace("+ 1", "+ 2"), code.replace("math.sqrt", "math.exp"),
                    code.replace("def f(x)", "def f(y)").replace("sqrt(x)", "sqrt(y)")):
        assert normalised_code(changed) != normalised_code(code)
    # a docstring-only function keeps a body, so removing the docstring cannot make it invalid
    assert "Pass" in normalised_code('def g():\n    """only a docstring."""\n')


def test_reformatting_every_file_of_export_leaves_every_code_hash_as_it_is():
    """ast.unparse drops every comment and rewrites every line's layout: a formatter can do no more."""
    import ast
    from export.config import EXPORT_DIR, normalised_code
    files = sorted(EXPORT_DIR.rglob("*.py"))
    assert len(files) > 50
    for path in files:
        text = path.read_text()
        assert normalised_code(ast.unparse(ast.parse(text))) == normalised_code(text), path
