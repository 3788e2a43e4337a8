"""Writers for the evaluation: public/results.json (the Results page reads it) and docs/RESULTS.md."""
from __future__ import annotations

import json
import math
from pathlib import Path

from ..paths import DOCS_DIR, PUBLIC
from .harness import COLUMNS

RESULTS_JSON = PUBLIC / "results.json"
RESULTS_MD = DOCS_DIR / "RESULTS.md"


def _round(x, digits: int = 5):
    """Floats to `digits` significant digits, recursively, so the committed JSON stays small and stable."""
    if isinstance(x, float):
        if not math.isfinite(x) or x == 0:
            return x if math.isfinite(x) else None
        return float(f"{x:.{digits}g}")
    if isinstance(x, dict):
        return {k: _round(v, digits) for k, v in x.items()}
    if isinstance(x, list):
        return [_round(v, digits) for v in x]
    return x


def write_json(doc: dict, path: Path = RESULTS_JSON) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(_round(doc), separators=(",", ":")) + "\n")


def fmt(value: float | None, unit: str = "") -> str:
    if value is None or (isinstance(value, float) and not math.isfinite(value)):
        return "—"
    a = abs(value)
    if unit == "%":
        return f"{value:.1f}"
    if a == 0:
        return "0"
    if a >= 100:
        return f"{value:.0f}"
    if a >= 10:
        return f"{value:.1f}"
    if a >= 0.01:
        return f"{value:.3f}"
    return f"{value:.2e}"


def cell(v: dict | None, unit: str) -> str:
    if not v:
        return "—"
    return f"{fmt(v['mean'], unit)} ± {fmt(v['std'], unit)}" if v["n"] > 1 else fmt(v["mean"], unit)


def _part_text(p: dict) -> str:
    label = COLUMNS.get(p["metric"], (p["metric"],))[0]
    if p["status"] == "not evaluated":
        return f"{p['a']} vs {p['b']} ({label}, {p['table']}): missing {', '.join(p['missing'])}"
    unit = COLUMNS.get(p["metric"], ("", ""))[1]
    other = "" if p["metric_b"] == p["metric"] else f" {COLUMNS[p['metric_b']][0]}"
    return (f"{p['a']} {cell(p['a_value'], unit)} vs {p['b']}{other} {cell(p['b_value'], unit)} "
            f"({label}, {p['table']}; difference {fmt(p['difference'], unit)}, 2σ {fmt(p['bar'], unit)}): {p['status']}")


def _comparisons(doc: dict) -> list[str]:
    """One small table per comparison and table: columns are the rows compared, lines the metrics."""
    from .rows import COMPARISONS
    out = []
    by_table = {t["id"]: {r["id"]: r for r in t["rows"] if not r.get("skipped")} for t in doc["tables"]}
    for c in COMPARISONS:
        blocks = []
        for tid in c.tables:
            rows = [by_table.get(tid, {}).get(r) for r in c.rows]
            shown = [r for r in rows if r]
            if len(shown) < 2:
                continue
            blocks += [f"Table `{tid}`:", "", "| metric | " + " | ".join(r["label"] for r in shown) + " |",
                       "|---|" + "---|" * len(shown)]
            for m in c.metrics:
                if any(m in r["values"] for r in shown):
                    blocks.append(f"| {COLUMNS[m][0]}{f' ({COLUMNS[m][1]})' if COLUMNS[m][1] else ''} | "
                                  + " | ".join(cell(r["values"].get(m), COLUMNS[m][1]) for r in shown) + " |")
            blocks.append("")
        if blocks:
            out += [f"## Side by side: {c.text} ({c.paper})", ""] + blocks
    return out


def markdown(doc: dict) -> str:
    lines = ["# Results", "",
             "Written by `python -m export evaluate` from `configs/eval.json` and `export/eval/rows.py`; "
             "the same numbers are on the site's Results page (`results.html`). Do not edit by hand.", "",
             f"- K = {doc['k']} futures per history for stochastic models (1 for deterministic ones); "
             f"training seeds {doc['training_seeds']} × sampling seeds {doc['sampling_seeds']}.",
             "- Every cell is mean ± std over runs (training seed × sampling seed; deterministic models and the "
             "oracle have one run per training seed). A paper claim **holds** only when the difference lies in the "
             "claimed direction by more than twice the std of the difference (√(s_a² + s_b²)), **fails** when it lies "
             "the other way by as much, and is **inconclusive** otherwise.",
             "- Accuracy columns are the mean over the table's actions of each action's accuracy (LCP-VAE's "
             "\"mean class accuracy\"): about 90% of the test windows are walking, so plain accuracy would reward a "
             "classifier that maps every static input to \"walk\".",
             "- Predictions go through the Python predictor (`export/sample/predictor.py`), the code path the "
             "end-to-end vectors tie to the browser.",
             f"- Evaluation wall time: {doc['seconds']:.0f} s.", "",
             "Served models evaluated (hash of `public/models/manifest.json`):", ""]
    lines += [f"- `{mid}`: `{h}`" for mid, h in sorted(doc["models"].items())] + [""]

    lines += ["## Paper claims", "", "| claim | paper | status | numbers |", "|---|---|---|---|"]
    for c in doc["claims"]:
        nums = "<br>".join(_part_text(p) for p in c["parts"])
        lines.append(f"| {c['text']} | {c['paper']} | **{c['status']}** | {nums} |")
    lines.append("")

    lines += _comparisons(doc)

    lines += ["## Sanity checks", "",
              "Each check can fail, and a failure is reported here rather than tuned away. A pose-based classifier "
              "may prefer a frozen pose to real motion: Keyposes (appendix 6.6, Tables 16-17) reports the same of its "
              "full classifier, which is why it argues for the motion-only one.", "",
              "| check | table | expected | measured | result |", "|---|---|---|---|---|"]
    for s in doc["sanity"]:
        lines.append(f"| {s['text']} | {s['table'] or '—'} | {fmt(s['expected'])} | {fmt(s['measured'])} | "
                     f"{'pass' if s['passed'] else '**FAIL**'} |")
    lines.append("")

    lines += ["## Classifiers", "",
              f"Trained on the training split only, on {doc['classifier_config']['snippet_frames']}-frame snippets "
              "(mirrors added), accuracy in % of test snippets. Longer motions are classified by averaging the "
              "scores of their sliding snippets.", "",
              "**Risk: one take per action.** Every action has a single capture. Only walking has a second take "
              "(the walker clips); the other test snippets are the later frames of the very take the classifier "
              "was trained on. A classifier can therefore learn to recognise the take (its performer, its exact "
              "poses) instead of the action, and its accuracy on other motion, generated or real, says less about "
              "the action than the numbers suggest. The per-group accuracies below show how it transfers.", "",
              "| classifier | train acc. | test acc. (snippets) | test acc. (mean per action) | walker (2nd take) | "
              "getup_faceup tail | spin tail | chance |",
              "|---|---|---|---|---|---|---|---|"]
    for name, r in doc["classifiers"].items():
        g = r["test_groups"]
        lines.append(f"| {name} | {r['train_accuracy']:.1f} | {r['test_accuracy']:.1f} | "
                     f"{r['test_balanced_accuracy']:.1f} | "
                     + " | ".join(f"{g[k]['accuracy']:.1f}" if k in g else "—" for k in ("walker", "getup_faceup", "spin"))
                     + f" | {r['chance']:.1f} |")
    lines += ["", "Both classifiers have a class for no motion, trained on training poses held still; a future "
                  "classified as it counts as wrong for every action. What a held pose (the first training frame, "
                  "still for a whole snippet) is classified as:", ""]
    lines += [f"- {name}: **{r['motionless_class']}**" for name, r in doc["classifiers"].items()
              if r.get("motionless_class")]
    lines += ["", "What the test snippets were classified as (snippet counts):", ""]
    for name, r in doc["classifiers"].items():
        lines.append(f"- {name}: " + "; ".join(
            f"{g} → " + ", ".join(f"{a} {n}" for a, n in v.get("predicted", {}).items())
            for g, v in r["test_groups"].items()))
    lines.append("")

    for t in doc["tables"]:
        cols = t["columns"]
        lines += [f"## {t['title']} (`{t['id']}`)", "", t["about"], "",
                  (f"History {t['history_frames']} frames, " if t["history_frames"] else
                   "History: each model's own length (in its notes), ")
                  + f"horizon {t['horizon_frames']} frames ({t['horizon_frames'] / doc['fps']:.1f} s), K = {t['k']}, "
                  + (f"{t['windows']} windows" if t["windows"] else "windows") + f" from {', '.join(t['clips'])}.", "",
                  "| row | runs | " + " | ".join(f"{COLUMNS[c][0]}{f' ({COLUMNS[c][1]})' if COLUMNS[c][1] else ''}"
                                                 for c in cols) + " |",
                  "|---|---|" + "---|" * len(cols)]
        notes = []
        for r in t["rows"]:
            if r.get("skipped"):
                notes.append(f"- {r['label']}: skipped, {r['skipped']}")
                continue
            lines.append(f"| {r['label']} | {r['runs']} | " + " | ".join(cell(r["values"].get(c), COLUMNS[c][1])
                                                                       for c in cols) + " |")
            notes += [f"- {r['label']}: {n}" for n in r["notes"]]
            for col, (lo, hi) in r.get("intervals", {}).items():
                notes.append(f"- {r['label']}: {COLUMNS[col][0]} 95% bootstrap interval (first run) "
                             f"[{fmt(lo)}, {fmt(hi)}]")
        notes += [f"- {n}" for n in t.get("notes", [])]
        lines += [""] + notes + ([""] if notes else [])
    if doc["skipped"]:
        lines += ["## Rows not evaluated yet", ""]
        lines += [f"- {s['label']} (`{s['row']}`): {s['reason']}" for s in doc["skipped"]]
        lines.append("")
    return "\n".join(lines)


def write_markdown(doc: dict, path: Path = RESULTS_MD) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(markdown(_round(doc)))
