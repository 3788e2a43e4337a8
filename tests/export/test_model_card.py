"""docs/MODEL_CARD.md is generated from public/results.json, and the check that keeps it honest can fail:
a number the results do not hold, a claim worded under another status than its own, or a section that finds
no data in the results, is caught. The checks on the checker run on a results document in the current format
(tests/fixtures/results_v3_tiny.json), since the committed one is only as new as the last full evaluation."""
import copy
import json
from pathlib import Path

import pytest

from export.eval.card import MODEL_CARD_MD, SECTIONS, card_gaps, card_problems, model_card, summary
from export.eval.report import RESULTS_JSON

FIXTURE = Path(__file__).resolve().parents[1] / "fixtures" / "results_v3_tiny.json"


@pytest.fixture(scope="module")
def results():
    return json.loads(RESULTS_JSON.read_text())


@pytest.fixture(scope="module")
def tiny():
    return json.loads(FIXTURE.read_text())


def test_the_committed_card_is_written_from_the_committed_results(results):
    assert MODEL_CARD_MD.read_text() == model_card(results), \
        "docs/MODEL_CARD.md differs from what public/results.json gives: run `python -m export evaluate`"


def test_every_number_and_claim_of_the_card_agrees_with_the_results(results):
    assert card_problems(MODEL_CARD_MD.read_text(), results) == []


def test_the_summary_is_the_results_own_and_at_most_five_lines(results):
    assert results["summary"] == summary(results)
    assert 1 <= len(results["summary"]) <= 5


def test_a_card_from_current_results_agrees_with_them_and_finds_data_for_every_section(tiny):
    assert tiny["summary"] == summary(tiny) and 1 <= len(tiny["summary"]) <= 5
    assert card_gaps(tiny) == []
    assert card_problems(model_card(tiny), tiny) == []


def test_a_section_without_data_is_caught(tiny):
    card = model_card(tiny)
    for key, gap in (("per_action", "per-action"),):
        d = copy.deepcopy(tiny)
        d["data"].pop(key)
        assert any(gap in p for p in card_problems(card, d))
    for key in ("verdicts", "served_learned", "summary", "claims"):
        assert card_problems(card, dict(tiny, **{key: []})), key
    used = {v["table"] for v in tiny["verdicts"]}
    for tid in used:
        d = dict(tiny, tables=[t for t in tiny["tables"] if t["id"] != tid])
        assert any(f"table {tid}" in p for p in card_gaps(d))


def test_a_number_the_results_do_not_hold_is_caught(tiny):
    results = tiny
    card = model_card(results)
    line = next(ln for ln in card.splitlines() if ln.startswith("| ") and " m against " in ln)
    import re
    number = re.search(r"(\d+\.\d{3}) m against", line).group(1)
    wrong = card.replace(line, line.replace(number, "9" + number, 1))
    assert any("is not in the results" in p for p in card_problems(wrong, results))


def test_a_claim_worded_against_its_status_is_caught(tiny):
    results = tiny
    claim = results["claims"][0]
    card = model_card(results)
    other = next(s for s in SECTIONS if s != claim["status"])
    worded = card.replace(f"- **{claim['status']}** ({claim['paper']}): {claim['text']}",
                          f"- **{other}** ({claim['paper']}): {claim['text']}")
    assert worded != card
    assert any(claim["id"] in p for p in card_problems(worded, results))
    # The same card against results where the claim changed status: the stale wording is caught.
    changed = copy.deepcopy(results)
    changed["claims"][0]["status"] = other
    assert any(claim["id"] in p for p in card_problems(card, changed))
    dropped = card.replace(claim["text"], "a claim reworded by hand")
    assert any(f"claim {claim['id']} appears 0 times" in p for p in card_problems(dropped, results))
