"""Writers for the evaluation: public/results.json (the Results page reads it), docs/RESULTS.md and
docs/MODEL_CARD.md (export/eval/card.py), all from the one results document."""
from __future__ import annotations

import json
import math
from pathlib import Path

from ..paths import DOCS_DIR, PUBLIC
from .harness import COLUMNS

RESULTS_JSON = PUBLIC / "results.json"
RESULTS_MD = DOCS_DIR / "RESULTS.md"

SECTIONS = (("accuracy", "Accuracy against the captured future"), ("diversity", "Diversity"),
            ("recognition", "Recognition"), ("plausibility", "Plausibility of the raw futures"))


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
    """mean ± std (bootstrap over people and takes and seed variance combined); the mean alone when the std is 0."""
    if not v:
        return "—"
    return f"{fmt(v['mean'], unit)} ± {fmt(v['std'], unit)}" if v.get("std") else fmt(v["mean"], unit)


def label_of(col: str) -> str:
    c = COLUMNS.get(col)
    return f"{c.label} ({c.unit})" if c and c.unit else (c.label if c else col)


def status_text(x: dict) -> str:
    """A part's or claim's status; an unusable one also says what the data alone would say."""
    return x["status"] + (f"; the data would say: {x['data_status']}" if x.get("data_status") else "")


def _holm(p: dict) -> str:
    return f", p {fmt(p['p'])}, Holm {fmt(p['p_holm'])}" if p.get("p_holm") is not None else ""


def trend_text(p: dict) -> str:
    """A trend part: each setting's paired value, the slope per step in rank and the fitted change over the range."""
    label = COLUMNS[p["metric"]].label if p["metric"] in COLUMNS else p["metric"]
    unit = COLUMNS[p["metric"]].unit if p["metric"] in COLUMNS else ""
    where = f"{label}, {p['table']}, {p['setting']} {', '.join(fmt(x) for x in p['settings'])}"
    if p["status"] == "not evaluated" and p.get("missing"):
        return f"trend of {where}: missing {', '.join(p['missing'])}"
    values = " → ".join(fmt(v, unit) for v in p.get("values", []))
    text = (f"trend of {where} (on the {p['items']} items every row predicts: {values}; least-squares slope per step "
            f"in rank {fmt(p['slope'], unit)}, change over the range {fmt(p['difference'], unit)}, 2σ "
            f"{fmt(p['bar'], unit)}{_holm(p)}; {p['people']} people, {p['takes']} takes): {status_text(p)}")
    return text + (f" ({p['reason']})" if p.get("reason") else "")


def part_text(p: dict) -> str:
    if p.get("kind") == "trend":
        return trend_text(p)
    label = COLUMNS[p["metric"]].label if p["metric"] in COLUMNS else p["metric"]
    if p["status"] == "not evaluated":
        return f"{p['a']} vs {p['b']} ({label}, {p['table']}): missing {', '.join(p['missing'])}"
    unit = COLUMNS[p["metric"]].unit if p["metric"] in COLUMNS else ""
    other = "" if p["metric_b"] == p["metric"] else f" {COLUMNS[p['metric_b']].label}"
    margin = f", margin {fmt(p['margin'], unit)}" if p.get("margin") else ""
    paired = ""
    if p.get("a_paired") is not None and (fmt(p["a_paired"], unit) != fmt(p["a_value"]["mean"], unit)
                                          or fmt(p["b_paired"], unit) != fmt(p["b_value"]["mean"], unit)):
        paired = f" on the {p['items']} items both predict: {fmt(p['a_paired'], unit)} vs {fmt(p['b_paired'], unit)};"
    text = (f"{p['a']} {cell(p['a_value'], unit)} vs {p['b']}{other} {cell(p['b_value'], unit)} "
            f"({label}, {p['table']};{paired} difference {fmt(p['difference'], unit)}, 2σ {fmt(p['bar'], unit)}{margin}"
            f"{_holm(p)}; {p['people']} people, {p['takes']} takes): {status_text(p)}")
    return text + (f" ({p['reason']})" if p.get("reason") else "")


def tally_text(t: dict) -> str:
    return (f"{t['holds']} hold, {t['fails']} fail, {t['inconclusive']} inconclusive, {t.get('no difference', 0)} no "
            f"difference, {t['insufficient data']} insufficient data, {t['unusable']} unusable, {t['not evaluated']} "
            f"not evaluated; {t['by_construction']} true by construction (not counted)")


# The practical minimum (stats.practical_minimum), in words.
PRACTICAL_MINIMUM = ("1 mm or 1% of the baseline's value, whichever is larger, for lengths (m, mm); 1 point for % "
                     "metrics; 1% of the baseline otherwise")


def _claims(doc: dict) -> list[str]:
    n = (doc.get("comparisons") or {}).get("claims")
    lines = ["## Paper claims on held-out people", "",
             f"{tally_text(doc['tally'])}. A part **holds** only when the paired difference lies in the claimed "
             "direction by more than its 2σ bar, which combines a two-level cluster bootstrap (the held-out people "
             "resampled, then each drawn person's takes) with the seed variance, and only when it also passes Holm's "
             f"step-down correction at family-wise α 0.05 over the {'' if n is None else f'{n} '}claim parts "
             "counted (not by construction, in-sample or missing; one-sided p = 1 − Φ(difference in the claimed "
             "direction / σ), σ half the bar); a difference below the practical minimum "
             f"({PRACTICAL_MINIMUM}), or identical predictions, is **no difference**, never holds or fails; "
             f"fewer than {doc['min_people']} held-out people or {doc['min_takes']} held-out takes among the items both "
             "rows predict make it **insufficient data**; a trend over settings is tested as one trend, the "
             "bootstrapped least-squares slope of the metric against the settings' rank (its change over the range "
             "against the same bar, rules and correction); a recognition part in a table where the ground truth does "
             "not score best is **unusable** (with what the data alone would say); a claim that holds whatever the data "
             "is **by construction** and not counted.", "",
             "| claim | paper | status | numbers |", "|---|---|---|---|"]
    for c in doc["claims"]:
        nums = "<br>".join(part_text(p) for p in c["parts"])
        lines.append(f"| {c['text']} | {c['paper']} | **{c['status']}**"
                     + (f"; the data would say: {c['data_status']}" if c.get("data_status") else "")
                     + f" | {nums} |")
    return lines + [""]


COPY_WORDS = {"holds": "beats", "no difference": "no different from"}


def _copying(doc: dict) -> list[str]:
    if not doc.get("copying"):
        return []
    lines = ["## Copying and memorising", "",
             "Every model against the baselines that copy the history (repeat its last cycle) and memorise the "
             "training people (the nearest training window's future), on best-of-K ADE (root-relative), paired on the "
             "windows both predict. A model that does not beat the nearest training window on held-out people reports "
             "memorisation; one that does not beat repeating the last cycle reports copying. "
             + _copying_rule(doc), ""]
    by_table: dict[str, dict[str, dict[str, dict]]] = {}
    keys = {"nearest-window": "nearest", "repeat-cycle-60": "long", "zero-velocity": "zero"}
    for c in doc["copying"]:
        by_table.setdefault(c["table"], {}).setdefault(c["label"], {})[keys.get(c["baseline"], "own")] = c
    for tid, rows in by_table.items():
        lines += [f"Table `{tid}` (ADE difference model − baseline, its 2σ bar, and the verdict):", "",
                  "| model | vs nearest training window | vs repeat last cycle (own history) "
                  "| vs repeat last cycle (60 frames) | vs zero-velocity |", "|---|---|---|---|---|"]
        for label, cs in rows.items():
            cells = []
            for key in ("nearest", "own", "long", "zero"):
                c = cs.get(key)
                cells.append("—" if not c else f"{fmt(c['difference'], 'm')} m, 2σ {fmt(c['bar'], 'm')}: "
                                               f"{COPY_WORDS.get(c['status'], 'does not beat')} ({c['status']})")
            lines.append(f"| {label} | " + " | ".join(cells) + " |")
        lines.append("")
    memo = [c for c in doc["copying"] if c["baseline"] == "nearest-window" and c["status"] != "holds"]
    if memo:
        lines += ["Not beating the nearest training window (reporting memorisation): "
                  + "; ".join(f"{c['label']} in `{c['table']}` ({c['status']})" for c in memo) + ".", ""]
    return lines


def _copying_rule(doc: dict) -> str:
    n = (doc.get("comparisons") or {}).get("copying")
    return (f"A model **beats** a baseline when its ADE is lower by more than the 2σ bar and the comparison passes "
            f"Holm's step-down correction at family-wise α 0.05 over the {'' if n is None else f'{n} '}copying "
            "comparisons (a family of their own, apart from the claims); a difference below the practical minimum "
            "(1 mm or 1% of the baseline's ADE) is **no different from**.")


def _shape(doc: dict) -> list[str]:
    if not doc.get("shape"):
        return []
    lines = ["## With and without the shape terms (issue 17)", "",
             "Each stochastic model against its ablation without the seam layer, fixed bone lengths and floor term: "
             f"APD and best-of-K ADE, and whether the model without them is within "
             f"{round(100 * doc['shape'][0]['tolerance'])}% of the model with them. A measurement, not a claim.", "",
             "| model | table | metric | with | without | without / with | within |", "|---|---|---|---|---|---|---|"]
    for s in doc["shape"]:
        unit = COLUMNS[s["metric"]].unit
        lines.append(f"| {s['with']} | {s['table']} | {COLUMNS[s['metric']].label} | {cell(s['with_value'], unit)} | "
                     f"{cell(s['without_value'], unit)} | {fmt(s['ratio'])} | {'yes' if s['within'] else 'no'} |")
    return lines + [""]


def _comparisons(doc: dict) -> list[str]:
    """One small table per comparison and table: columns are the rows compared, lines the metrics."""
    from .rows import COMPARISONS
    out = []
    by_table = {t["id"]: {r["id"]: r for r in t["rows"] if r.get("values")} for t in doc["tables"]}
    for c in COMPARISONS:
        blocks = []
        for tid in c.tables:
            shown = [r for r in (by_table.get(tid, {}).get(x) for x in c.rows) if r]
            if len(shown) < 2:
                continue
            blocks += [f"Table `{tid}`:", "", "| metric | " + " | ".join(r["label"] for r in shown) + " |",
                       "|---|" + "---|" * len(shown)]
            for m in c.metrics:
                if any(m in r["values"] for r in shown):
                    blocks.append(f"| {label_of(m)} | " + " | ".join(cell(r["values"].get(m), COLUMNS[m].unit)
                                                                    for r in shown) + " |")
            blocks.append("")
        if blocks:
            out += [f"## Side by side: {c.text} ({c.paper})", ""] + blocks
    return out


def _rows(doc: dict) -> list[str]:
    """Every row once, with what it is: the baselines' rules, the variants, the labelled extras."""
    seen, lines = set(), ["## Rows", ""]
    for t in doc["tables"]:
        for r in t["rows"]:
            if r["id"] in seen or not r.get("note"):
                continue
            seen.add(r["id"])
            lines.append(f"- **{r['label']}** ({r['kind']}): {r['note']}.")
    return lines + [""] if len(lines) > 2 else []


def _variants(doc: dict) -> list[str]:
    v = doc.get("variants") or {}
    lines = ["## Choices that change the numbers", "",
             "- **Eq. 4** is reported both ways: as printed, (1/2L) Σᵢ ‖ẑᵢ − z̃ᵢ‖₂² (mm², column "
             "\"Eq. 4 as printed\"), and as the authors' code computes it, the mean of the unsquared per-pose norm "
             "(1/2L) Σᵢ ‖ẑᵢ − z̃ᵢ‖₂ (mm, \"Eq. 4 as the authors' code\"). Ranking of the models by each:"]
    for e in v.get("eq4", []):
        lines.append(f"  - `{e['table']}`: {'the same order' if e['same_order'] else 'different orders'} "
                     f"(printed: {', '.join(e['printed'])}; code: {', '.join(e['code'])})")
    lines += ["- **Keyposes' interpolation**: the paper's tables use linear interpolation between keyposes (rows "
              "\"linear\", the claims' rows); the site serves the refinement network (row \"refined: served\").",
              f"- **Keypose extraction**: the paper's text stops splitting a segment on the mean error (served and "
              f"trained); the authors' code stops on the maximum error (row \"max-error extraction\", an evaluation "
              f"variant). Keyposes per {v.get('keypose_history_frames', 30)}-frame held-out history:", ""]
    rules = v.get("keypose_rules") or {}
    if rules:
        lines += ["| action | histories | mean-error rule | max-error rule |", "|---|---|---|---|"]
        lines += [f"| {a} | {r['histories']} | {fmt(r['mean'])} | {fmt(r['max'])} |" for a, r in rules.items()]
    return lines + [""]


def _sanity(doc: dict) -> list[str]:
    lines = ["## Sanity checks", "",
             "Each check can fail, and a failure is reported here rather than tuned away. Where the ground truth does "
             "not score best on a classifier, that table's recognition claims are unusable.", "",
             "| check | table | expected | measured | result |", "|---|---|---|---|---|"]
    for s in doc["sanity"]:
        lines.append(f"| {s['text']} | {s['table'] or '—'} | {fmt(s['expected'])} | {fmt(s['measured'])} | "
                     f"{'pass' if s['passed'] else '**FAIL**'} |")
    return lines + [""]


def _classifiers(doc: dict) -> list[str]:
    clf = doc["classifiers"]
    lines = ["## Classifiers", "",
             f"Trained on the training people only, on {doc['classifier_config']['snippet_frames']}-frame snippets "
             "(mirrors added); accuracy in % of held-out snippets (people no classifier saw). Longer motions are "
             "classified by averaging the scores of their sliding snippets. The configuration of each was chosen by "
             "leave-one-person-out validation inside the training people, never by the test:", ""]
    for kind in ("pose_gru", "moac"):
        sel = clf.get(kind, {}).get("selection")
        if not sel:
            continue
        lines.append(f"- {kind}: chose **{sel['chosen']}** ({sel['steps']} steps per fold; folds "
                     f"{', '.join(sel['people'])}): " + "; ".join(f"{c['name']} {fmt(c['score'], '%')}"
                                                                 for c in sel["candidates"]))
    lines += ["", "| classifier | train acc. | held-out acc. (snippets) | held-out acc. (mean per action) | chance |",
              "|---|---|---|---|---|"]
    for name, r in clf.items():
        lines.append(f"| {name} | {fmt(r['train_accuracy'], '%')} | {fmt(r['test_accuracy'], '%')} | "
                     f"{fmt(r['test_balanced_accuracy'], '%')} | {fmt(r['chance'], '%')} |")
    actions = sorted({a for r in clf.values() for a in r.get("test_groups", {})})
    names = [n for n in clf if not n.endswith("_shuffled")]
    lines += ["", "Held-out accuracy per action (%; snippets in brackets):", "",
              "| action | " + " | ".join(names) + " |", "|---|" + "---|" * len(names)]
    for a in actions:
        g = [clf[n]["test_groups"].get(a) for n in names]
        lines.append(f"| {a} ({next((x['snippets'] for x in g if x), 0)}) | "
                     + " | ".join(fmt(x["accuracy"], "%") if x else "—" for x in g) + " |")
    lines += ["", "A motionless snippet (a training pose held still) is classified as: "
              + "; ".join(f"{n}: **{r['motionless_class']}**" for n, r in clf.items() if r.get("motionless_class")) + ".",
              ""]
    return lines


def _table(doc: dict, t: dict) -> list[str]:
    lines = [f"## {t['title']} (`{t['id']}`)" + (" — in-sample" if t.get("in_sample") else ""), "", t["about"], "",
             f"History {t['history_frames']} frames (context up to {t['context_frames']}), horizon "
             f"{t['horizon_frames']} frames ({t['horizon_frames'] / doc['fps']:.1f} s), K = {t['k']}, stride "
             f"{t['stride']}: {t['windows']} windows ({t['items']} items) from {t['takes']} takes of "
             f"{len(t['people'])} people ({', '.join(t['people'])}); actions {', '.join(t['actions'])}.", ""]
    if t.get("exceptions"):
        lines += ["Horizon exceptions (no held-out take of the action holds history + horizon; never padded): "
                  + ", ".join(e["action"] for e in t["exceptions"]) + ".", ""]
    if t.get("mmade"):
        mm = t["mmade"]
        lines += [f"MMADE/MMFDE: similar histories are those whose last root-relative pose lies within "
                  f"{fmt(mm['threshold'])} m (whole pose) of the window's, the smallest threshold giving a median set of "
                  f"at least 5 (median {fmt(mm['median_set'])}); the window itself is always in its set, so no set is "
                  f"empty: {mm['alone']} windows have only themselves and count with their own truth (their term is "
                  f"their ADE), as in DLow. Sensitivity below at half ({fmt(mm['half']['threshold'])} m, "
                  f"{mm['half']['alone']} alone) and double ({fmt(mm['double']['threshold'])} m, "
                  f"{mm['double']['alone']} alone).", ""]
    rows = [r for r in t["rows"] if not r.get("skipped")]
    notes = []
    for key, title in SECTIONS:
        cols = [c for c in t["columns"] if COLUMNS[c].section == key]
        if not cols:
            continue
        lines += [f"**{title}**", "", "| row | windows | runs | " + " | ".join(label_of(c) for c in cols) + " |",
                  "|---|---|---|" + "---|" * len(cols)]
        for r in rows:
            lines.append(f"| {r['label']} | {r.get('items', 0)}/{t['items']} | {r.get('runs', 0)} | "
                         + " | ".join(cell(r.get("values", {}).get(c), COLUMNS[c].unit) for c in cols) + " |")
        lines.append("")
    if t.get("mmade") and any("mmade_half" in r.get("values", {}) for r in rows):
        lines += ["MMADE / MMFDE sensitivity to the threshold (m):", "",
                  "| row | MMADE ½ | MMADE | MMADE 2× | MMFDE ½ | MMFDE | MMFDE 2× |", "|---|---|---|---|---|---|---|"]
        for r in rows:
            v = r.get("values", {})
            lines.append(f"| {r['label']} | " + " | ".join(cell(v.get(c), "m") for c in (
                "mmade_half", "mmade", "mmade_double", "mmfde_half", "mmfde", "mmfde_double")) + " |")
        lines.append("")
    acts = t["actions"]
    if t["truth"] and not t.get("in_sample") and any(r.get("by_action", {}).get("ade") for r in rows):
        lines += ["ADE best of K (root-relative, m) per action:", "",
                  "| row | " + " | ".join(acts) + " |", "|---|" + "---|" * len(acts)]
        for r in rows:
            per = r.get("by_action", {}).get("ade", {})
            lines.append(f"| {r['label']} | " + " | ".join(fmt(per.get(a)) for a in acts) + " |")
        lines.append("")
    for r in t["rows"]:
        if r.get("skipped"):
            notes.append(f"- {r['label']}: skipped, {r['skipped']}")
        notes += [f"- {r['label']}: {n}" for n in r.get("notes", [])]
    notes += [f"- {n}" for n in t.get("notes", [])]
    return lines + notes + ([""] if notes else [])


def markdown(doc: dict) -> str:
    lines = ["# Results", "",
             "Written by `python -m export evaluate` from `configs/eval.json` and `export/eval/rows.py`; the same numbers "
             "are on the site's Results page (`results.html`) and in `docs/MODEL_CARD.md`. Do not edit by hand.", "",
             "- Every table with a claim is cut from the held-out people's takes (world frame); the in-sample table is "
             "labelled and backs no claim. Every row of a table predicts from the same windows, each model from the "
             "last frames of its own history length.",
             f"- K = {doc['k']} futures per history for stochastic models (1 for deterministic ones); training seeds "
             f"{doc['training_seeds']} × sampling seeds {doc['sampling_seeds']} (a row says how many runs it has).",
             f"- A cell is the mean over runs ± the combined std: a two-level cluster bootstrap ({doc['bootstrap']['rounds']} "
             "resamples of the held-out people, then of each drawn person's takes; windows overlap and cluster within "
             "a take, takes within a person) and the std over runs.",
             "- Accuracy columns are the mean over the table's actions of each action's accuracy (LCP-VAE's "
             "\"mean class accuracy\").",
             "- Predictions go through the Python predictor (`export/sample/predictor.py`), the code path the "
             "end-to-end vectors tie to the browser; futures are the raw outputs (bone-projected rows are labelled extras).",
             f"- Evaluation wall time: {doc['seconds']:.0f} s, of which {doc.get('classifier_seconds', 0):.0f} s "
             "choosing and training the classifiers (cached in `runs/eval` after the first run)"
             + (f"; training the extra seeds and ablations before it (`make results`, seeds already in `runs/seeds` "
                f"kept): {doc['seed_training_seconds']:.0f} s." if doc.get("seed_training_seconds") is not None else "."), "",
             "Served models evaluated (hash of the manifest they were read from):", ""]
    lines += [f"- `{mid}`: `{h}`" for mid, h in sorted(doc["models"].items())] + [""]
    if doc.get("summary"):
        lines += ["## In short", ""] + [f"- {s}" for s in doc["summary"]] + [""]
    lines += _claims(doc) + _copying(doc) + _shape(doc) + _rows(doc) + _comparisons(doc) + _variants(doc) + _sanity(doc)
    lines += _classifiers(doc)
    for t in sorted(doc["tables"], key=lambda t: bool(t.get("in_sample"))):
        lines += _table(doc, t)
    if doc["skipped"]:
        lines += ["## Rows not evaluated yet", ""]
        lines += [f"- {s['label']} (`{s['row']}`): {s['reason']}" for s in doc["skipped"]]
        lines.append("")
    return "\n".join(lines)


def write_markdown(doc: dict, path: Path = RESULTS_MD) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(markdown(_round(doc)))
