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


def _row(doc: dict, table: str, row: str) -> dict | None:
    t = next((x for x in doc["tables"] if x["id"] == table), None)
    return next((r for r in (t or {}).get("rows", []) if r["id"] == row and r.get("values")), None)


def _val(doc: dict, table: str, row: str, metric: str) -> float | None:
    r = _row(doc, table, row)
    v = (r or {}).get("values", {}).get(metric)
    return v["mean"] if v else None


def copying_tally(doc: dict, table: str = "heldout_2s") -> dict:
    """How many model rows of `table` beat the nearest training window and the 60-frame repeated cycle."""
    rows = {c["row"] for c in doc.get("copying", []) if c["table"] == table}
    beat = lambda base: sum(1 for c in doc.get("copying", []) if c["table"] == table and c["baseline"] == base
                            and c["status"] == "holds")
    return {"table": table, "models": len(rows), "beat_nearest": beat("nearest-window"),
            "beat_cycle": beat("repeat-cycle-60")}


def recognition_tally(doc: dict) -> dict:
    """How many "ground truth scores best" checks pass on held-out people (the in-sample ones are reported,
    not counted)."""
    held = {t["id"] for t in doc["tables"] if not t.get("in_sample")}
    checks = [s for s in doc.get("sanity", []) if s["id"].startswith("oracle-best") and s["table"] in held]
    return {"checks": len(checks), "passed": sum(bool(s["passed"]) for s in checks)}


def summary(doc: dict) -> list[str]:
    """The card's five lines, every number taken from `doc` as the card and the results page print it."""
    d = doc["data"]
    lines = [f"Tested on {len(d['heldout_people'])} held-out people (subjects {', '.join(d['heldout_people'])}) "
             f"whose {d['heldout_takes']} takes ({_fmt(d['heldout_seconds'])} s, {len(d['heldout_actions'])} actions) "
             f"no model saw; trained on {d['train_people']} other performers ({d['train_takes']} takes)."]
    t = "heldout_2s"
    # the served models only: an ablation or variant is a measurement, not what the site runs
    ranked = sorted((r for r in next((x["rows"] for x in doc["tables"] if x["id"] == t), [])
                     if r["kind"] == "model" and r["id"] in doc.get("models", {}) and "ade" in r.get("values", {})),
                    key=lambda r: r["values"]["ade"]["mean"])
    zero, near = _val(doc, t, "zero-velocity", "ade"), _val(doc, t, "nearest-window", "ade")
    if ranked:
        best = ranked[0]
        lines.append(f"2 s ahead on held-out people the lowest best-of-K ADE (root-relative) of the served models is "
                     f"{_fmt(best['values']['ade']['mean'])} m ({best['label']}), against {_fmt(zero)} m for zero-velocity and "
                     f"{_fmt(near)} m for the nearest training window.")
    c = doc.get("copying_tally") or copying_tally(doc)
    if c["models"]:
        rest = c["models"] - c["beat_nearest"]
        lines.append(f"{c['beat_nearest']} of {c['models']} models beat the nearest training window 2 s ahead"
                     + (f" ({rest} report memorisation)" if rest else "") + f", {c['beat_cycle']} beat repeating "
                     "the last cycle of a 60-frame history.")
    k = doc["tally"]
    lines.append(f"Paper claims on held-out people: {k['holds']} hold, {k['fails']} fail, {k['inconclusive']} "
                 f"inconclusive, {k.get('no difference', 0)} no difference, {k['insufficient data']} insufficient data, "
                 f"{k['unusable']} unusable, "
                 f"{k['not evaluated']} not evaluated; {k['by_construction']} true by construction are not counted.")
    clf, rec = doc["classifiers"], doc.get("recognition_tally") or recognition_tally(doc)
    if "pose_gru" in clf and "moac" in clf:
        lines.append(f"The action classifiers reach {_fmt(clf['pose_gru']['test_balanced_accuracy'], '%')}% (pose GRU) "
                     f"and {_fmt(clf['moac']['test_balanced_accuracy'], '%')}% (MOAC) mean per-action accuracy on "
                     f"held-out people; the ground truth scores best in {rec['passed']} of {rec['checks']} "
                     "recognition checks.")
    return lines[:5]


def _part(p: dict, doc: dict) -> str:
    unit = doc["columns"].get(p["metric"], {}).get("unit", "")
    label = doc["columns"].get(p["metric"], {}).get("label", p["metric"])
    from .report import status_text
    if p["a_value"] is None or p["b_value"] is None:
        return f"{p['a']} vs {p['b']} ({label}, `{p['table']}`): not evaluated"
    if p.get("kind") == "trend" and "values" in p:
        return (f"{label} over {p['setting']} {', '.join(_fmt(x) for x in p['settings'])} (`{p['table']}`, on the "
                f"{p['items']} items every row predicts): " + " → ".join(_fmt(v, unit) for v in p["values"])
                + f", change over the range {_fmt(p['difference'], unit)}, 2σ {_fmt(p['bar'], unit)}: {status_text(p)}")
    a, b = p.get("a_paired", p["a_value"]["mean"]), p.get("b_paired", p["b_value"]["mean"])
    return (f"{p['a']} {_fmt(a, unit)} vs {p['b']} {_fmt(b, unit)} ({label}, `{p['table']}`, on the {p['items']} "
            f"items both predict, 2σ {_fmt(p['bar'], unit)}): {status_text(p)}")


def model_card(doc: dict) -> str:
    """The whole card, from the (rounded) results document."""
    d, clf = doc["data"], doc["classifiers"]
    lines = ["# Model card: motion futures", "",
             "Generated from `public/results.json` by `python -m export evaluate` (`export/eval/card.py`): do not edit "
             "by hand. The site's Model card page reads the same file, and `docs/RESULTS.md` has every table.", "",
             "## In short", ""] + [f"- {s}" for s in doc.get("summary", [])] + [""]
    lines += ["## The data", "",
              f"- {d['clips']} clips of {d['actions']} actions, {d['joints']} joints in metres at {_fmt(d['fps'])} "
              "frames per second, in the world frame (the root travels over the floor).",
              f"- Split by person: the held-out people ({', '.join(d['heldout_people'])}) give {d['heldout_takes']} "
              f"takes ({_fmt(d['heldout_seconds'])} s) of {len(d['heldout_actions'])} actions "
              f"({', '.join(d['heldout_actions'])}); {d['train_people']} other performers give {d['train_takes']} "
              f"training takes ({_fmt(d['train_seconds'])} s).",
              "- Claims rest only on actions with held-out people; the in-sample table backs none.", "",
              "## The models evaluated", ""]
    lines += [f"- `{mid}` (hash `{h}`)" for mid, h in sorted(doc["models"].items())] + [""]
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
    memo = [c for c in doc.get("copying", []) if c["baseline"] == "nearest-window"]
    if memo:
        lines += ["## Against copying and memorising", "",
                  "Best-of-K ADE (root-relative) of each model against the nearest training window's future, paired on "
                  "the windows both predict:", ""]
        for c in memo:
            lines.append(f"- **{c['status']}** (`{c['table']}`): {c['label']} {c['verdict']} "
                         f"(difference {_fmt(c['difference'])} m, 2σ {_fmt(c['bar'])} m).")
        lines.append("")
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
              "- Few people: every number rests on the held-out people above, and each action has few takes; a "
              "comparison with too few people or takes is reported as insufficient data.",
              "- Keyposes refuses histories with too little motion (too few keyposes); its rows say how many windows "
              "it predicted, and its comparisons are paired on those windows.",
              "- The recognition numbers are only as good as the classifiers above.", "",
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
    the results rounds to, or a claim missing, repeated, or written under another status than its own."""
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
    for c in doc.get("copying", []):
        if c["baseline"] != "nearest-window":
            continue
        lines = [ln for ln in text.splitlines() if f"{c['label']} {c['verdict']}" in ln and f"`{c['table']}`" in ln]
        if lines and not all(ln.startswith(f"- **{c['status']}**") for ln in lines):
            problems.append(f"{c['label']} against the nearest window in {c['table']} is not worded as '{c['status']}'")
    return problems


def read_results(path: Path) -> dict:
    return json.loads(Path(path).read_text())
