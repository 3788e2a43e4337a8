"""The committed results belong to the committed models: same hashes, and RESULTS.md agrees with results.json
(docs/MODEL_CARD.md is checked in test_model_card.py)."""
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


def test_committed_results_are_on_held_out_people():
    results = json.loads(RESULTS_JSON.read_text())
    for t in results["tables"]:
        held_out = t["source"] == "test"
        assert held_out or t["in_sample"], f"table {t['id']} is neither held-out nor labelled in-sample"
        if held_out and t["truth"]:
            rows = {r["id"] for r in t["rows"] if r.get("values")}
            assert {"nearest-window", "repeat-cycle-60"} <= rows, f"table {t['id']} lacks the copying baselines"
    in_sample = {t["id"] for t in results["tables"] if t.get("in_sample")}
    assert not any(p["table"] in in_sample for c in results["claims"] for p in c["parts"])


def test_results_md_states_the_split_per_action_and_what_is_not_evaluated():
    from pathlib import Path
    doc = json.loads((Path(__file__).parents[1] / "fixtures" / "results_v3_tiny.json").read_text())
    text = markdown(doc)
    assert "## The data and the split" in text
    section = text.split("## The data and the split")[1].split("\n## ")[0]
    for action, v in doc["data"]["per_action"].items():
        row = next(line for line in section.splitlines() if line.startswith(f"| {action} |"))
        assert f"| {v['train']['takes']} |" in row and f"| {v['test']['takes']} |" in row, row
        if not v["test"]["takes"]:
            assert "trained on only" in row
    assert "Not evaluated:" in section and "Horizon exceptions" in section
    # the section is built from the document: without per-action data it says nothing rather than guess
    assert "## The data and the split" not in markdown({**doc, "data": {}})
