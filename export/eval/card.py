"""docs/MODEL_CARD.md and the card page's five-line summary, both written from the results document
(public/results.json), so the static card can never state a number or a claim the evaluation did not.

`card_problems` is the check tests/export/test_model_card.py runs: every number in the card (outside code)
must appear in the results, and every claim must be worded under its own status.
"""
from __future__ import annotations

import json
import math
import re
from pathlib import Path

from ..paths import CONTRACT_DIR, DOCS_DIR

MODEL_CARD_MD = DOCS_DIR / "MODEL_CARD.md"

# Where each claim status is written in the card: one section per kind of verdict.
SECTIONS = {"holds": "Holds on held-out people", "fails": "Fails on held-out people",
            "no difference": "No practical difference on held-out people",
            "inconclusive": "Not decided on held-out people", "insufficient data": "Not decided on held-out people",
            "unusable": "Not decided on held-out people", "not evaluated": "Not decided on held-out people",
            "by construction": "True by construction (not counted)"}


def _fmt(value, unit: str = "") -> str:
    from .report import fmt
    return fmt(value, unit)


def _seconds(x: float) -> str:
    """Seconds of capture as people read them: 1.7 s, 54.9 s, 1934 s."""
    return f"{x:.0f}" if x >= 100 else f"{x:.1f}"


def copying_tally(doc: dict) -> dict:
    """Which served learned models are shown to beat each baseline, per held-out table (after Holm): the only
    tally the card prints. Baselines, ablations and rows that do not predict are never counted."""
    from .report import _verdict_flag
    beat: dict[str, dict[str, list[str]]] = {}
    for v in doc.get("verdicts") or []:
        if _verdict_flag(doc, v):
            continue
        got = beat.setdefault(v["baseline"], {}).setdefault(v["table"], [])
        if v["status"] == "holds":
            got.append(v["row"])
    return {"models": list(doc.get("served_learned") or []), "beat": beat}


def recognition_tally(doc: dict) -> dict:
    """How many "ground truth scores best" checks pass on held-out people (the in-sample ones are reported,
    not counted)."""
    held = {t["id"] for t in doc["tables"] if not t.get("in_sample")}
    checks = [s for s in doc.get("sanity", []) if s["id"].startswith("oracle-best") and s["table"] in held]
    return {"checks": len(checks), "passed": sum(bool(s["passed"]) for s in checks)}


def data_line(doc: dict) -> str:
    """Who the numbers are on and who the models learned from (results.data)."""
    d = doc["data"]
    performers = len(d.get("train_people_list") or []) or d["train_people"]
    return (f"Tested on {len(d['heldout_people'])} held-out people (subjects {', '.join(d['heldout_people'])}) whose "
            f"{d['heldout_takes']} takes ({_fmt(d['heldout_seconds'])} s, {len(d['heldout_actions'])} actions) no model "
            f"saw; trained on {d['train_takes']} takes ({_fmt(d['train_seconds'])} s) of {performers} other performers.")


def claims_line(doc: dict) -> str:
    k = doc["tally"]
    return (f"Paper claims on held-out people: {k['holds']} hold, {k['fails']} fail, {k['inconclusive']} "
            f"inconclusive, {k.get('no difference', 0)} no difference, {k['insufficient data']} insufficient data, "
            f"{k['unusable']} unusable, {k['not evaluated']} not evaluated; {k['by_construction']} true by "
            "construction are not counted.")


def classifiers_line(doc: dict) -> str | None:
    clf, rec = doc["classifiers"], doc.get("recognition_tally") or recognition_tally(doc)
    if "pose_gru" not in clf or "moac" not in clf:
        return None
    return (f"The action classifiers reach {_fmt(clf['pose_gru']['test_balanced_accuracy'], '%')}% (pose GRU) and "
            f"{_fmt(clf['moac']['test_balanced_accuracy'], '%')}% (MOAC) mean per-action accuracy on held-out people; "
            f"the ground truth scores best in {rec['passed']} of {rec['checks']} recognition checks.")


def summary(doc: dict) -> list[str]:
    """The card's five lines, every number taken from `doc` as the card and the results page print it: the data,
    whether each served learned model is shown to beat zero-velocity, the regression GRU and the nearest
    training window (only they are counted), and the paper claims."""
    from .report import VERDICT_BASELINES, beaten_line
    lines = [data_line(doc)] + [x for x in (beaten_line(doc, b) for b in VERDICT_BASELINES) if x]
    lines.append(claims_line(doc))
    if len(lines) < 5 and classifiers_line(doc):
        lines.append(classifiers_line(doc))
    return lines[:5]


def _part(p: dict, doc: dict) -> str:
    """A claim part with the numbers it rests on: both rows on the items both predict, with the count."""
    unit = doc["columns"].get(p["metric"], {}).get("unit", "")
    label = doc["columns"].get(p["metric"], {}).get("label", p["metric"])
    from .report import _holm, status_text
    if p.get("kind") == "trend" and "values" in p:
        return (f"{label} over {p['setting']} {', '.join(_fmt(x) for x in p['settings'])} (`{p['table']}`, on the "
                f"{p['items']} items every row predicts): " + " → ".join(_fmt(v, unit) for v in p["values"])
                + f", change over the range {_fmt(p['difference'], unit)}, 2σ {_fmt(p['bar'], unit)}{_holm(p)}: "
                + status_text(p))
    if p.get("a_paired") is None or p.get("b_paired") is None:
        return f"{p['a']} vs {p['b']} ({label}, `{p['table']}`): {status_text(p)}"
    return (f"{p['a']} {_fmt(p['a_paired'], unit)} vs {p['b']} {_fmt(p['b_paired'], unit)} ({label}, `{p['table']}`, "
            f"on the {p['items']} items both predict, 2σ {_fmt(p['bar'], unit)}{_holm(p)}): {status_text(p)}")


def _data(doc: dict) -> list[str]:
    """Who the models learned from and are tested on, per action (results.data, never the served clips)."""
    d = doc["data"]
    train = d.get("train_people_list") or []
    lines = ["## The data", "",
             f"- {d['clips']} takes of {d['actions']} actions, {d['joints']} joints in metres at {_fmt(d['fps'])} "
             "frames per second, in the world frame (the root travels over the floor).",
             f"- Held out: {len(d['heldout_people'])} people (subjects {', '.join(d['heldout_people'])}) give "
             f"{d['heldout_takes']} takes ({_seconds(d['heldout_seconds'])} s) of {len(d['heldout_actions'])} actions "
             f"({', '.join(d['heldout_actions'])}); no model saw them, and every claim rests on them alone.",
             f"- Training: {len(train) or d['train_people']} other performers"
             + (f" ({', '.join(train)})" if train else "")
             + f" give {d['train_takes']} takes ({_seconds(d['train_seconds'])} s)."
             + (f" Balance: {d['balance']}." if d.get("balance") else "")]
    if d.get("train_only_actions"):
        lines.append(f"- Trained on but never tested (no held-out person performs them): "
                     f"{', '.join(d['train_only_actions'])}; no number here says how the models do on them.")
    lines.append("- The in-sample table (training people) backs no claim.")
    per = d.get("per_action") or {}
    if per:
        lines += ["", "| action | group | training people | training takes | training s | held-out people | "
                  "held-out takes | held-out s |", "|---|---|---|---|---|---|---|---|"]
        for a, x in per.items():
            tr, te = x["train"], x["test"]
            lines.append(f"| {a} | {x['group']} | {len(tr['people'])} | {tr['takes']} | {_seconds(tr['seconds'])} | "
                         f"{len(te['people'])} | {te['takes']} | {_seconds(te['seconds'])} |")
    return lines + [""]


def _served_against_baselines(doc: dict) -> list[str]:
    from .report import VERDICT_BASELINES, beaten_line, verdict_table
    table = verdict_table(doc)
    if not table:
        return []
    return (["## The served learned models against the baselines", "",
             "Best-of-K ADE (root-relative) on held-out people, each model and baseline on the same windows (the "
             "windows the model accepts), with their count; \"beats\" needs a difference beyond the 2σ bar that "
             "also passes Holm's correction over the copying comparisons.", ""]
            + [f"- {x}" for x in (beaten_line(doc, b) for b in VERDICT_BASELINES) if x] + [""] + table + [""])


def _not_predicting(doc: dict) -> list[str]:
    """Rows whose futures are not predictions: marked, and left out of every tally."""
    from .report import flag_text
    flagged = [(t["id"], r) for t in doc["tables"] for r in t["rows"] if r.get("flag")]
    if not flagged:
        return []
    return ["## Rows that do not predict", "",
            "Left out of every tally and comparison count, and never \"within 10%\" of a row that predicts:", ""] \
        + [f"- {r['label']} (`{tid}`): {flag_text(r['flag'])}." for tid, r in flagged] + [""]


def model_card(doc: dict) -> str:
    """The whole card, from the (rounded) results document."""
    clf = doc["classifiers"]
    learned = set(doc.get("served_learned") or [])
    lines = ["# Model card: motion futures", "",
             "Generated from `public/results.json` by `python -m export evaluate` (`export/eval/card.py`): do not edit "
             "by hand. The site's Model card page reads the same file, and `docs/RESULTS.md` has every table.", "",
             "## In short", ""] + [f"- {s}" for s in doc.get("summary", [])] + [""]
    lines += _data(doc)
    lines += ["## The models evaluated", ""]
    lines += [f"- `{mid}` (hash `{h}`)" + (": learns from data" if mid in learned else "")
              for mid, h in sorted(doc["models"].items())] + [""]
    lines += _served_against_baselines(doc)
    for title in dict.fromkeys(SECTIONS.values()):
        claims = [c for c in doc["claims"] if SECTIONS.get(c["status"]) == title]
        if not claims:
            continue
        lines += [f"## {title}", ""]
        for c in claims:
            why = f" Why: {c['reason']}." if c.get("reason") else ""
            lines.append(f"- **{c['status']}** ({c['paper']}): {c['text']}{why} Numbers: "
                         + "; ".join(_part(p, doc) for p in c["parts"]) + ".")
        lines.append("")
    lines += _not_predicting(doc)
    lines += ["## The classifiers behind the recognition numbers", ""]
    for kind in ("pose_gru", "moac"):
        if kind in clf:
            r = clf[kind]
            lines.append(f"- {kind}: {_fmt(r['test_balanced_accuracy'], '%')}% mean per-action accuracy on held-out "
                         f"people (chance {_fmt(r['chance'], '%')}%), {_fmt(r['train_accuracy'], '%')}% on its training "
                         f"snippets; a motionless snippet is called \"{r.get('motionless_class')}\".")
    for s in doc.get("sanity", []):
        if s["id"].startswith("oracle-best"):
            lines.append(f"- {'pass' if s['passed'] else 'FAIL'} (`{s['table']}`): {s['text']}: the ground truth "
                         f"{_fmt(s['measured'])}, the best other {_fmt(s['expected'])}.")
    lines += ["", "## Known limits", "",
              f"- Few people: every number rests on the held-out people above, and each action has few takes; a "
              f"comparison with fewer than {doc.get('min_people', '?')} held-out people or "
              f"{doc.get('min_takes', '?')} held-out takes is reported as insufficient data, and a difference below "
              "its practical minimum as no difference.",
              "- Keyposes refuses histories with too little motion (too few keyposes); its rows say how many windows "
              "it predicted, and its comparisons are made on exactly those windows.",
              "- The recognition numbers are only as good as the classifiers above.",
              "- How lifelike the motion is (speed against the truth's second by second, foot skating, coverage, per "
              "action group) is in `docs/RESULTS.md`, section \"Motion realism\".", "",
              "## How to cite", "", "Cite the method papers and this project (`CITATION.cff`).", "",
              "```bibtex", CITATIONS.strip(), "```", ""]
    return "\n".join(lines)


# The papers and the data, one copy shared with the model-card page (web/src/model-card/card.ts).
CITATIONS = "".join(line for line in (CONTRACT_DIR / "papers.bib").read_text().splitlines(keepends=True)
                    if not line.startswith("%"))


def write_card(doc: dict, path: Path = MODEL_CARD_MD) -> None:
    from .report import _round
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(model_card(_round(doc)))


# --- the consistency check ------------------------------------------------------------------------

NUMBER = re.compile(r"(?<![\w.])-?\d+(?:\.\d+)?(?:e-?\d+)?(?![\w])")


def _prose(text: str) -> str:
    """The card without fenced blocks and `code` spans (citations, hashes and ids are not measurements)."""
    text = re.sub(r"```.*?```", "", text, flags=re.S)
    return re.sub(r"`[^`]*`", "", text)


def _known(doc) -> list[float]:
    """Every number the results hold, as values and inside strings (the summary excepted: it is derived)."""
    out: list[float] = []

    def walk(x, key=""):
        if key == "summary":
            return
        if isinstance(x, bool):
            return
        if isinstance(x, (int, float)):
            if math.isfinite(x):
                out.append(float(x))
        elif isinstance(x, str):
            out.extend(float(m) for m in NUMBER.findall(x))
        elif isinstance(x, dict):
            for k, v in x.items():
                walk(v, k)
                walk(k)
        elif isinstance(x, list):
            out.append(float(len(x)))          # a count of listed things ("6 held-out people")
            for v in x:
                walk(v)
    walk(doc)
    return out


def _matches(token: str, known: list[float]) -> bool:
    x = float(token)
    if "e" in token.lower():
        return any(math.isclose(v, x, rel_tol=0.06) for v in known)
    decimals = len(token.split(".")[1]) if "." in token else 0
    tol = 0.5 * 10 ** -decimals + 1e-9 * abs(x)
    return any(abs(v - x) <= tol for v in known)


def card_problems(text: str, doc: dict) -> list[str]:
    """Why the card disagrees with the results (empty when it does not): a number outside code that no value in
    the results rounds to; a claim missing, repeated, or written under another status than its own; a served
    model's verdict not beside its own paired numbers; or a section that finds no data in the results."""
    problems = []
    known = _known(doc)
    for token in sorted(set(NUMBER.findall(_prose(text))), key=float):
        if not _matches(token, known):
            problems.append(f"the number {token} is not in the results")
    section = None
    where: dict[str, list[tuple[str, str]]] = {}
    for line in text.splitlines():
        if line.startswith("## "):
            section = line[3:].strip()
        for c in doc["claims"]:
            if c["text"] in line:
                where.setdefault(c["id"], []).append((section, line))
    for c in doc["claims"]:
        found = where.get(c["id"], [])
        if len(found) != 1:
            problems.append(f"claim {c['id']} appears {len(found)} times (once expected)")
            continue
        section, line = found[0]
        if section != SECTIONS[c["status"]]:
            problems.append(f"claim {c['id']} ({c['status']}) is written under '{section}'")
        if not line.startswith(f"- **{c['status']}**"):
            problems.append(f"claim {c['id']} is not worded as '{c['status']}'")
        for other in SECTIONS:
            if other != c["status"] and f"**{other}**" in line:
                problems.append(f"claim {c['id']} ({c['status']}) is also worded as '{other}'")
    problems += verdict_problems(text, doc)
    problems += card_gaps(doc)
    return problems


def verdict_problems(text: str, doc: dict) -> list[str]:
    """Each served learned model's verdict against each baseline must be printed beside its own paired numbers
    (both rows on the same windows, with their count), in the line of its model and table."""
    from .report import label_for, verdict_cell
    problems = []
    lines = text.splitlines()
    for v in doc.get("verdicts") or []:
        want = verdict_cell(doc, v)
        where = [ln for ln in lines if ln.startswith(f"| {label_for(doc, v['row'])} |") and f"(`{v['table']}`)" in ln]
        if not any(f"| {want} |" in ln for ln in where):
            problems.append(f"{v['row']} against {v['baseline']} in {v['table']} is not printed beside its paired "
                            f"numbers ('{want}')")
    return problems


def card_gaps(doc: dict) -> list[str]:
    """Sections of the card that would find no data in these results (an old or partial results document)."""
    gaps = []
    if not (doc.get("data") or {}).get("per_action"):
        gaps.append("the data section finds no per-action data (results.data.per_action)")
    if not doc.get("served_learned"):
        gaps.append("the baselines section finds no served learned models (results.served_learned)")
    elif not doc.get("verdicts"):
        gaps.append("the baselines section finds no verdicts (results.verdicts)")
    have = {t["id"] for t in doc.get("tables", [])}
    for tid in dict.fromkeys(v["table"] for v in doc.get("verdicts") or []):
        if tid not in have:
            gaps.append(f"the baselines section reads table {tid}, which the results do not hold")
    if not doc.get("summary"):
        gaps.append("the summary is missing (results.summary)")
    if not doc.get("claims"):
        gaps.append("the claims sections find no claims")
    if not any(k in doc.get("classifiers", {}) for k in ("pose_gru", "moac")):
        gaps.append("the classifiers section finds no classifier")
    return gaps


def read_results(path: Path) -> dict:
    return json.loads(Path(path).read_text())
