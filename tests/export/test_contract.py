import json
import math
import shutil

import pytest

from export.contract import ContractError, load_json
from export.data.clip_json import read_clip
from export.paths import CLIPS_DIR
from export.rng import Prng
from export.vectors import FAMILIES, render
from export.paths import VECTORS_DIR


def test_committed_files_validate():
    index = load_json(CLIPS_DIR / "index.json", "clip-index")
    for entry in index["clips"]:
        load_json(CLIPS_DIR / entry["file"], "clip")


def test_clip_with_nan_names_file_and_problem(tmp_path):
    text = (CLIPS_DIR / "walk.json").read_text()
    bad = tmp_path / "walk.json"
    bad.write_text(text.replace("[[0,0.847532,0]", "[[0,NaN,0]", 1))
    with pytest.raises(ContractError) as e:
        read_clip(bad)
    assert "walk.json" in str(e.value) and "NaN" in str(e.value)


def test_clip_with_null_position_names_the_field(tmp_path):
    doc = json.loads((CLIPS_DIR / "walk.json").read_text())
    doc["positions"][3][5][1] = None
    bad = tmp_path / "walk.json"
    bad.write_text(json.dumps(doc))
    with pytest.raises(ContractError, match=r"walk.json: field positions/3/5/1"):
        read_clip(bad)


def test_manifest_missing_a_field_names_file_and_field(tmp_path):
    manifest = {"format": "motion-futures/manifest", "version": 1, "fps": 30,
                "skeleton": {"joints": ["root", "chest"], "parents": [-1, 0]},
                "actions": ["walk"], "data_hash": "sha256:" + "0" * 64,
                "models": [{"id": "m", "method": "regression", "label": "M", "hash": "sha256:" + "0" * 64,
                            "graphs": {"decoder": {"file": "m.onnx", "inputs": [{"name": "history", "shape": ["batch", 10, 18, 3], "dtype": "float32"}],
                                                   "outputs": [{"name": "future", "shape": ["batch", 30, 18, 3], "dtype": "float32"}]}},
                            "params": {"history_frames": 10}, "controls": []}]}
    path = tmp_path / "manifest.json"
    path.write_text(json.dumps(manifest))
    with pytest.raises(ContractError, match=r"manifest.json: field models/0/params: 'future_frames' is a required property"):
        load_json(path, "manifest")


def test_unreadable_and_broken_json(tmp_path):
    with pytest.raises(ContractError, match="missing.json: cannot be read"):
        load_json(tmp_path / "missing.json", "clip")
    (tmp_path / "broken.json").write_text("{\"format\": ")
    with pytest.raises(ContractError, match="broken.json: not valid JSON"):
        load_json(tmp_path / "broken.json", "clip")


def _same(a, b, where: str) -> str | None:
    """Where two JSON documents differ, allowing last-bit float differences (BLAS and libm builds
    differ between machines, and a value rounded to 6 decimals can flip its last digit)."""
    if isinstance(a, dict) and isinstance(b, dict):
        if a.keys() != b.keys():
            return f"{where}: keys {sorted(a.keys() ^ b.keys())}"
        return next((d for k in a if (d := _same(a[k], b[k], f"{where}/{k}"))), None)
    if isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            return f"{where}: length {len(a)} != {len(b)}"
        return next((d for i, (x, y) in enumerate(zip(a, b)) if (d := _same(x, y, f"{where}/{i}"))), None)
    if isinstance(a, float) or isinstance(b, float):
        ok = isinstance(b, (int, float)) and math.isclose(a, b, rel_tol=1e-9, abs_tol=2e-6)
        return None if ok else f"{where}: {a!r} != {b!r}"
    return None if a == b else f"{where}: {a!r} != {b!r}"


@pytest.mark.parametrize("name", sorted(FAMILIES))
def test_committed_vectors_match_this_code(name):
    committed = json.loads((VECTORS_DIR / f"{name}.json").read_text())
    diff = _same(committed, json.loads(render(FAMILIES[name]())), name)
    assert diff is None, f"run `python -m export vectors`: {diff}"


def test_prng_known_values_and_seed_checks():
    r = Prng(42)
    assert [r.next_u32() for _ in range(2)] == [660444221, 3652823732]
    assert 0 <= Prng(7).uniform() < 1
    with pytest.raises(ValueError, match="seed"):
        Prng(-1)
    with pytest.raises(ValueError, match="seed"):
        Prng(2 ** 32)
