"""The committed results belong to the committed models: same hashes, and RESULTS.md agrees with results.json."""
import json

from export.eval.report import RESULTS_JSON, RESULTS_MD, markdown
from export.manifest import read_manifest
from export.paths import MODELS_DIR


def test_committed_results_name_the_committed_models():
    results = json.loads(RESULTS_JSON.read_text())
    manifest = read_manifest(MODELS_DIR / "manifest.json")
    assert results["models"] == {m["id"]: m["hash"] for m in manifest["models"]}, \
        "public/results.json was made with other models: run `python -m export evaluate` (or `make results`)"


def test_committed_markdown_is_written_from_the_committed_json():
    assert RESULTS_MD.read_text() == markdown(json.loads(RESULTS_JSON.read_text())), \
        "docs/RESULTS.md and public/results.json differ: run `python -m export evaluate`"
