"""Evaluation v3 on the presentation side, on a results document made by the real harness
(tests/fixtures/results_v3_tiny.json; tests/fixtures/make_results_v3.py writes it): every verdict in
docs/RESULTS.md and docs/MODEL_CARD.md sits beside its own paired numbers (both rows on the same windows,
with their count), rows that do not predict are marked and never counted, the tallies count only the served
learned models, and the realism tables state their windows, people and takes."""
import copy
import json
import re
from pathlib import Path

import pytest

from export.eval.card import card_problems, copying_tally, model_card, summary
from export.eval.report import VERDICT_WORDS, fmt, label_for, markdown

FIXTURE = Path(__file__).resolve().parents[1] / "fixtures" / "results_v3_tiny.json"
# a verdict as the writers print it: "<word> (<status>): <a> m against <b> m on the same <n> windows, ..."
VERDICT = re.compile(r"^(?P<word>" + "|".join(re.escape(w) for w in sorted(set(VERDICT_WORDS.values()), key=len,
                                                                             reverse=True))
                     + r") \((?P<status>[a-z ]+)\): (?P<a>\S+) m against (?P<b>\S+) m on the same (?P<n>\d+) windows")


@pytest.fixture(scope="module")
def tiny():
    return json.loads(FIXTURE.read_text())


@pytest.fixture
def doc(tiny):
    """The fixture with every row's own mean moved away from its paired value, so that a writer printing a
    row's own mean beside another's (different windows) cannot pass for one printing the paired values."""
    d = copy.deepcopy(tiny)
    for c in [*d["copying"], *(p for cl in d["claims"] for p in cl["parts"])]:
        for side in ("a", "b"):
            if c.get(f"{side}_value") and c.get(f"{side}_paired") is not None:
                c[f"{side}_value"]["mean"] = c[f"{side}_paired"] * 1.5 + 0.25
    d["summary"] = summary(d)
    return d


def table_rows(text: str):
    """Every markdown table of `text` as (header cells, [row cells])."""
    lines, out, i = text.splitlines(), [], 0
    while i < len(lines):
        if lines[i].startswith("| ") and i + 1 < len(lines) and lines[i + 1].startswith("|---"):
            head = [c.strip() for c in lines[i].strip("|").split(" | ")]
            body, i = [], i + 2
            while i < len(lines) and lines[i].startswith("| "):
                body.append([c.strip() for c in lines[i].strip().strip("|").split(" | ")])
                i += 1
            out.append((head, body))
        else:
            i += 1
    return out


def printed_verdicts(text: str, doc: dict) -> list[tuple[dict, str]]:
    """Each verdict cell of the text's verdict tables, with the verdict of results.json it stands for."""
    out = []
    for head, body in table_rows(text):
        if head[:2] != ["served model", "ahead"]:
            continue
        for cells in body:
            table = re.search(r"\(`(\w+)`\)", cells[1]).group(1)
            for name, text_ in zip(head[2:], cells[2:]):
                v = next((v for v in doc["verdicts"] if label_for(doc, v["row"]) == cells[0] and v["table"] == table
                          and name == f"vs {_name(doc, v['baseline'])}"), None)
                out.append((v, text_))
    return out


def _name(doc, base):
    from export.eval.report import _baseline_name
    return _baseline_name(doc, base)


@pytest.mark.parametrize("writer", [markdown, model_card], ids=["RESULTS.md", "MODEL_CARD.md"])
def test_every_verdict_sits_beside_its_paired_numbers_and_their_count(doc, writer):
    cells = printed_verdicts(writer(doc), doc)
    assert len([v for v, _ in cells if v]) == len(doc["verdicts"])        # each verdict printed once
    for v, text in cells:
        if v is None:
            assert text == "— (itself)"
            continue
        m = VERDICT.match(text)
        if v["status"] == "not evaluated":
            assert text.endswith("no windows both predict")
            continue
        assert m, text
        assert m["status"] == v["status"] and m["word"] == VERDICT_WORDS[v["status"]]
        assert (m["a"], m["b"], int(m["n"])) == (fmt(v["a_paired"], "m"), fmt(v["b_paired"], "m"), v["items"])


@pytest.mark.parametrize("writer", [markdown, model_card], ids=["RESULTS.md", "MODEL_CARD.md"])
def test_every_claim_part_prints_the_paired_values_never_each_rows_own_mean(doc, writer):
    text = writer(doc)
    for c in doc["claims"]:
        line = next(ln for ln in text.splitlines() if c["text"] in ln)
        for p in c["parts"]:
            if p.get("kind") == "trend" or p.get("a_paired") is None:
                continue
            unit = doc["columns"][p["metric"]]["unit"]
            assert f"{p['a']} {fmt(p['a_paired'], unit)} vs {p['b']}" in line
            assert f"{fmt(p['b_paired'], unit)} (" in line and f"on the {p['items']} items both predict" in line
            assert f"{fmt(p['a_value']['mean'], unit)} ±" not in line and f"{p['a']} {fmt(p['a_value']['mean'], unit)} " \
                not in line


def test_the_copying_tables_state_the_windows_of_each_row(doc):
    text = markdown(doc)
    for head, body in table_rows(text):
        if head[:2] != ["model", "windows"]:
            continue
        for cells in body:
            mine = {c["items"] for c in doc["copying"] if c["label"] == cells[0]}
            assert set(int(x) for x in cells[1].split("/")) <= mine


def test_a_row_that_refuses_windows_shows_its_refusal_rate_and_its_paired_block(doc):
    text = markdown(doc)
    for t in doc["tables"]:
        for r in t["rows"]:
            if not (r.get("refused") or {}).get("items"):
                continue
            share = fmt(100.0 * r["refused"]["items"] / t["items"], "%")
            lines = [ln for ln in text.splitlines() if ln.startswith(f"| {r['label']} | {r['items']}/{t['items']}")]
            assert lines and all(f"({share}% refused)" in ln for ln in lines)
            if t["truth"] and not t.get("in_sample") and r.get("paired"):
                lead = f"{r['label']} predicts {r['paired']['items']} of the {t['items']} windows"
                assert lead in text
                block = text[text.index(lead):].split("\n\n")[1]
                zero = next(ln for ln in block.splitlines() if ln.startswith("| Zero-velocity |"))
                assert fmt(r["paired"]["rows"]["zero-velocity"]["ade"], "m") == zero.split(" | ")[1]


def test_rows_that_do_not_predict_are_marked_everywhere_and_never_counted(doc):
    d = copy.deepcopy(doc)
    table = next(t for t in d["tables"] if t["id"] == "heldout_2s")
    lcp = next(r for r in table["rows"] if r["id"] == "lcp-vae")
    lcp["flag"] = "the output guard cuts 66% of its samples (more than 5%)"
    for v in d["verdicts"]:
        if v["row"] == "lcp-vae" and v["table"] == "heldout_2s":
            v["status"] = "holds"                       # even a verdict the data would pass is not counted
    d["shape"] = [{"table": "heldout_2s", "with": "lcp-vae", "without": "lcp-vae-no-shape", "metric": "ade",
                   "with_value": lcp["values"]["ade"], "without_value": lcp["values"]["ade"], "ratio": 1.0,
                   "within": False, "flag": lcp["flag"], "tolerance": 0.1, "difference": 0.0, "bar": 0.1}]
    text = markdown(d)
    for head in ("\n### Held-out people, 2 s ahead (`heldout_2s`)", "\n## Held-out people, 2 s ahead (`heldout_2s`)"):
        section = text[text.index(head) + 1:]
        section = section[:section.index("\n## ")] if "\n## " in section else section
        section = section[:section.index("\n### ")] if "\n### " in section else section
        lines = [ln for ln in section.splitlines() if ln.startswith(f"| {lcp['label']}")]
        assert len(lines) >= 4 and all(f"**does not predict: {lcp['flag']}**" in ln for ln in lines)
    assert "| no (does not predict: the output guard cuts 66%" in text
    beat = copying_tally(d)["beat"]
    assert all("lcp-vae" not in rows for base in beat.values() for t, rows in base.items() if t == "heldout_2s")
    line = next(s for s in summary(d) if "zero-velocity" in s)
    assert "not scored, as they do not predict: LCP-VAE" in line and "LCP-VAE (row 4: h_t / reparam z_c) at" not in line
    card = model_card(dict(d, summary=summary(d)))
    assert f"does not predict: {lcp['flag']}" in card


def test_the_summary_says_plainly_when_no_served_learned_model_beats_zero_velocity(doc):
    assert not any(v["status"] == "holds" for v in doc["verdicts"] if v["baseline"] == "zero-velocity")
    lines = summary(doc)
    assert len(lines) <= 5
    assert any(s.startswith("No served learned model is shown to beat zero-velocity at 1 s or 2 s") for s in lines)
    d = copy.deepcopy(doc)
    v = next(v for v in d["verdicts"] if (v["row"], v["table"], v["baseline"]) ==
             ("keyposes", "heldout_2s", "zero-velocity"))
    v["status"] = "holds"
    line = next(s for s in summary(d) if "zero-velocity" in s)
    assert line.startswith("Shown to beat zero-velocity") and "Keyposes (T = 0.3, refined: served) at 2 s" in line
    # only served learned models are counted: not the baselines, ablations or zero-velocity itself
    named = {label_for(d, r) for r in d["served_learned"]}
    assert all(x.split(" at ")[0] in named for x in line.split(": ", 1)[1].split("; not shown")[0].split("; "))


def test_realism_tables_for_every_held_out_table_with_windows_people_and_takes_per_group(doc):
    text = markdown(doc)
    realism = text[text.index("## Motion realism"):text.index("\n## ", text.index("## Motion realism") + 1)]
    for t in doc["tables"]:
        if not t["truth"] or t.get("in_sample"):
            assert f"(`{t['id']}`)" not in realism
            continue
        part = realism[realism.index(f"### {t['title']} (`{t['id']}`)"):]
        part = part[:part.index("\n### ")] if "\n### " in part else part
        assert "√18 × the per-joint distance for 18 joints" in part and "100/(K+1)" in part
        oracle = next(r for r in t["rows"] if r["id"] == "oracle")
        for group, g in oracle["by_group"].items():
            people = f"{g['people']} {'person' if g['people'] == 1 else 'people'}"
            assert f"*{group}*: {g['items']} window" in part and people in part
        jump = part[part.index("*jump*"):].split("\n\n")[1]
        assert "hip range (m) | captures' hip range (m)" in jump.splitlines()[0]
        served = [r for r in t["rows"] if r["id"] in doc["models"] and r.get("values")]
        assert all(f"| {r['label']} |" in part for r in served)


def test_the_card_data_section_is_the_results_data_per_action(doc):
    card = model_card(doc)
    data = card[card.index("## The data"):card.index("## The models evaluated")]
    per = doc["data"]["per_action"]
    rows = [ln for ln in data.splitlines() if ln.startswith("| ") and not ln.startswith("| action")]
    assert [ln.split(" | ")[0][2:] for ln in rows] == list(per)
    assert f"{len(doc['data']['train_people_list'])} other performers" in data
    assert f"{doc['data']['train_takes']} takes" in data


def test_the_card_check_catches_a_verdict_printed_without_its_paired_numbers(doc):
    card = model_card(doc)
    assert card_problems(card, doc) == []
    v = next(v for v in doc["verdicts"] if v["status"] not in ("not evaluated",) and v["a_paired"] is not None)
    paired = f"{fmt(v['a_paired'], 'm')} m against {fmt(v['b_paired'], 'm')} m on the same {v['items']} windows"
    lines = card.splitlines()
    i = next(i for i, ln in enumerate(lines) if ln.startswith(f"| {label_for(doc, v['row'])} |")
             and f"(`{v['table']}`)" in ln and paired in ln)
    lines[i] = lines[i].replace(paired, f"{fmt(v['a_paired'], 'm')} m against 0.999 m on the same {v['items']} windows")
    problems = card_problems("\n".join(lines), doc)
    assert any("not printed beside its paired numbers" in p for p in problems)


def test_the_card_check_fails_when_a_section_finds_no_data(doc):
    card = model_card(doc)
    no_data = copy.deepcopy(doc)
    no_data["data"].pop("per_action")
    assert any("per-action" in p for p in card_problems(card, no_data))
    no_table = copy.deepcopy(doc)
    no_table["tables"] = [t for t in no_table["tables"] if t["id"] != "heldout_2s"]
    assert any("heldout_2s" in p for p in card_problems(card, no_table))
    no_verdicts = dict(doc, verdicts=[])
    assert any("no verdicts" in p for p in card_problems(card, no_verdicts))
