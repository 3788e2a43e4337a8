"""`make results` trains extra training seeds into their own directory with their own manifest,
and the harness loads them exactly like the served models."""
import json

import numpy as np
import pytest

from export.config import load_config, override
from export.eval.harness import load_row_models
from export.eval.rows import Row
from export.eval.seeds import train_seeds
from export.paths import MODELS_DIR
from export.sample.request import Request


@pytest.fixture(scope="module")
def clips(deepmimic):
    """Tiny models train on the DeepMimic clips (small, named, with their own test tails)."""
    return deepmimic


def test_an_extra_seed_is_trained_exported_and_loaded_once(clips, tmp_path, monkeypatch):
    cfg = override(load_config("regression.json"), **{"id": "tiny-regression", "train.steps": 2,
                                                        "train.batch_size": 8, "model.hidden": 8, "train.stride": 8})
    path = tmp_path / "tiny.json"
    path.write_text(json.dumps(cfg))
    row = Row("tiny", "Tiny regression", config=str(path))
    said, checked = [], []
    # the extra seeds' graphs go through the rounding-derived parity check (export/onnx/parity.py)
    from export.onnx import parity
    real = parity.check_parity
    def spy(graph, blob, *args, **kwargs):
        checked.append(graph.outputs[0].name)
        return real(graph, blob, *args, **kwargs)
    monkeypatch.setattr("export.eval.seeds.check_parity", spy)
    notes = train_seeds(list(clips.values()), [1], rows=[row], seeds_root=tmp_path / "seeds", progress=said.append)
    assert notes == [] and len(said) == 1 and checked
    manifest = json.loads((tmp_path / "seeds" / "tiny-regression" / "seed1" / "manifest.json").read_text())
    assert [m["id"] for m in manifest["models"]] == ["tiny-regression"]
    assert train_seeds(list(clips.values()), [1], rows=[row], seeds_root=tmp_path / "seeds", progress=said.append) == []
    assert len(said) == 1   # same code, config and data: kept, not retrained

    runs, notes = load_row_models(row, [0, 1], MODELS_DIR, tmp_path / "seeds")
    assert [r.seed for r in runs] == [1] and "training seeds [0] not found" in notes[0]
    history = clips["walker_walk_forward"].positions[:10]
    pred = runs[0].predictor.predict(history, Request(k=1, seed=0, horizon_frames=30))
    assert pred.futures.shape == (1, 30, 18, 3) and np.isfinite(pred.futures).all()


def test_a_model_from_other_code_or_config_is_evaluated_but_called_stale(clips, tmp_path):
    cfg = override(load_config("regression.json"), **{"id": "tiny-regression", "train.steps": 2,
                                                        "train.batch_size": 8, "model.hidden": 8, "train.stride": 8})
    path = tmp_path / "tiny.json"
    path.write_text(json.dumps(cfg))
    row = Row("tiny", "Tiny regression", config=str(path))
    train_seeds(list(clips.values()), [1], rows=[row], seeds_root=tmp_path / "seeds", progress=lambda s: None)
    runs, notes = load_row_models(row, [1], MODELS_DIR, tmp_path / "seeds")
    assert len(runs) == 1 and not any("stale" in n for n in notes)
    path.write_text(json.dumps(override(cfg, **{"loss.floor": 1.0})))   # the config changed since
    runs, notes = load_row_models(row, [1], MODELS_DIR, tmp_path / "seeds")
    assert len(runs) == 1 and any("training seed 1 is stale" in n for n in notes)
