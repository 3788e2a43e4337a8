"""docs/MODEL_CARD.md is generated from public/results.json, and the check that keeps it honest can fail:
a number the results do not hold, or a claim worded under another status than its own, is caught."""
import copy
import json

import pytest

from export.eval.card import MODEL_CARD_MD, SECTIONS, card_problems, model_card, summary
from export.eval.report import RESULTS_JSON


@pytest.fixture(scope="module")
def results():
    return json.loads(RESULTS_JSON.read_text())


def test_the_committed_card_is_written_from_the_committed_results(results):
    assert MODEL_CARD_MD.read_text() == model_card(results), \
        "docs/MODEL_CARD.md differs from what public/results.json gives: run `python -m export evaluate`"


def test_every_number_and_claim_of_the_card_agrees_with_the_results(results):
    assert card_problems(MODEL_CARD_MD.read_text(), results) == []


def test_the_summary_is_the_results_own_and_at_most_five_lines(results):
    assert results["summary"] == summary(results)
    assert 1 <= len(results["summary"]) <= 5


def test_a_number_the_results_do_not_hold_is_caught(results):
    card = model_card(results)
    line = next(ln for ln in card.splitlines() if ln.startswith("- ") and " m " in ln and "ADE" in ln)
    import re
    number = re.search(r"\d+\.\d{3}", line).group(0)
    wrong = card.replace(line, line.replace(number, "9" + number, 1))
    assert any("is not in the results" in p for p in card_problems(wrong, results))


def test_a_claim_worded_against_its_status_is_caught(results):
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
