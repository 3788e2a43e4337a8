"""Writers for the evaluation: public/results.json (the Results page reads it), docs/RESULTS.md and
docs/MODEL_CARD.md (export/eval/card.py), all from the one results document."""
from __future__ import annotations

import json
import math
from pathlib import Path

from ..paths import DOCS_DIR, PUBLIC
from .harness import COLUMNS
from .targets import STATUS, group_windows, row_of, table_of, tally, targets

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
    """The one-sided p and its Holm-adjusted value, when the comparison was counted in a family."""
    return f", p {fmt(p['p'])}, Holm-adjusted {fmt(p['p_holm'])}" if p.get("p_holm") is not None else ""


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
    """A pair part: both rows' values on the items both predict (never each row's own mean beside the
    other's), the count, the difference and its bar, p and Holm, and the status."""
    if p.get("kind") == "trend":
        return trend_text(p)
    label = COLUMNS[p["metric"]].label if p["metric"] in COLUMNS else p["metric"]
    if p["status"] == "not evaluated" or p.get("a_paired") is None:
        missing = f": missing {', '.join(p['missing'])}" if p.get("missing") else ""
        return f"{p['a']} vs {p['b']} ({label}, {p['table']}){missing}: {status_text(p)}"
    unit = COLUMNS[p["metric"]].unit if p["metric"] in COLUMNS else ""
    other = "" if p["metric_b"] == p["metric"] else f" {COLUMNS[p['metric_b']].label}"
    margin = f", margin {fmt(p['margin'], unit)}" if p.get("margin") else ""
    text = (f"{p['a']} {fmt(p['a_paired'], unit)} vs {p['b']}{other} {fmt(p['b_paired'], unit)} ({label}, "
            f"{p['table']}; on the {p['items']} items both predict, {p['people']} people, {p['takes']} takes; "
            f"difference {fmt(p['difference'], unit)}, 2σ {fmt(p['bar'], unit)}{margin}{_holm(p)}): {status_text(p)}")
    return text + (f" ({p['reason']})" if p.get("reason") else "")


def tally_text(t: dict) -> str:
    return (f"{t['holds']} hold, {t['fails']} fail, {t['inconclusive']} inconclusive, {t.get('no difference', 0)} no "
            f"difference, {t['insufficient data']} insufficient data, {t['unusable']} unusable, {t['not evaluated']} "
            f"not evaluated; {t['by_construction']} true by construction (not counted)")


def windows_text(r: dict, t: dict) -> str:
    """A row's windows: how many of the table's it predicts, and its refusal rate when it refuses some."""
    of = t.get("items") or t.get("windows") or 0
    n, out = r.get("items", 0), refused(r, t)
    return f"{n}/{of}" + (f" ({fmt(100.0 * out / of, '%')}% refused)" if out and of else "")


def counted(n: int, one: str, many: str = "") -> str:
    """"1 window", "9 windows", "1 person", "3 people"."""
    return f"{n} {one if n == 1 else many or one + 's'}"


def flag_text(flag: str) -> str:
    return f"does not predict: {flag}"


def row_label(r: dict) -> str:
    """A row's label, marked when its futures are not predictions (harness.does_not_predict)."""
    return r["label"] + (f" — **{flag_text(r['flag'])}**" if r.get("flag") else "")


def ahead(doc: dict, tid: str) -> str:
    """How far ahead a table predicts, in seconds ("2 s")."""
    t = table_of(doc, tid)
    return f"{t['horizon_frames'] / doc['fps']:g} s" if t else tid


# --- the served learned models against the baselines (Evaluation v3, item 6) ----------------------

VERDICT_BASELINES = ("zero-velocity", "regression-gru", "nearest-window")
# what a copying status says of a model against a baseline, after Holm
VERDICT_WORDS = {"holds": "beats", "no difference": "is no different from", "fails": "is worse than",
                 "inconclusive": "is not shown to beat", "insufficient data": "is not shown to beat",
                 "not evaluated": "was not compared with"}


def _verdict_flag(doc: dict, v: dict) -> str:
    return (row_of(table_of(doc, v["table"]), v["row"]) or {}).get("flag", "")


def verdict_numbers(doc: dict, v: dict) -> str:
    """The numbers a verdict rests on: both rows' ADE on the same windows, with their count."""
    if v.get("a_paired") is None:
        return "no windows both predict"
    c = next((x for x in doc.get("copying", []) if (x["row"], x["table"], x["baseline"]) ==
              (v["row"], v["table"], v["baseline"])), {})
    holm = f", Holm-adjusted p {fmt(c['p_holm'])}" if c.get("p_holm") is not None else ""
    return (f"{fmt(v['a_paired'], 'm')} m against {fmt(v['b_paired'], 'm')} m on the same {v['items']} windows, "
            f"difference {fmt(v['difference'], 'm')} m, 2σ {fmt(v['bar'], 'm')} m{holm}")


def verdict_cell(doc: dict, v: dict) -> str:
    """One verdict beside its paired numbers: "beats (holds): 0.700 m against 0.800 m on the same 97 windows, …"."""
    flag = _verdict_flag(doc, v)
    if flag:
        return flag_text(flag)
    return f"{VERDICT_WORDS.get(v['status'], v['status'])} ({v['status']}): {verdict_numbers(doc, v)}"


def label_for(doc: dict, rid: str) -> str:
    """A row's label wherever the results name it (a table, or the rows not evaluated), else its id."""
    for t in doc["tables"]:
        r = row_of(t, rid)
        if r:
            return r["label"]
    return next((x["label"] for x in doc.get("skipped", []) if x["row"] == rid), rid)


def _baseline_name(doc: dict, base: str) -> str:
    """"zero-velocity", "the regression GRU", "the nearest training window": a baseline inside a sentence."""
    name = label_for(doc, base)
    return name.lower() if name.lower().startswith("zero") else f"the {name[0].lower()}{name[1:]}"


def verdict_table(doc: dict) -> list[str]:
    """Each served learned model per held-out table, against each baseline, its verdict beside its numbers."""
    verdicts = doc.get("verdicts") or []
    if not verdicts:
        return []
    bases = [b for b in VERDICT_BASELINES if any(v["baseline"] == b for v in verdicts)]
    lines = ["| served model | ahead | " + " | ".join(f"vs {_baseline_name(doc, b)}" for b in bases) + " |",
             "|---|---|" + "---|" * len(bases)]
    for row in dict.fromkeys(v["row"] for v in verdicts):
        for tid in dict.fromkeys(v["table"] for v in verdicts if v["row"] == row):
            got = {v["baseline"]: v for v in verdicts if v["row"] == row and v["table"] == tid}
            lines.append(f"| {label_for(doc, row)} | {ahead(doc, tid)} (`{tid}`) | "
                         + " | ".join(verdict_cell(doc, got[b]) if b in got else "— (itself)" for b in bases) + " |")
    return lines


def beaten_line(doc: dict, base: str) -> str | None:
    """In plain words, which served learned models are shown to beat one baseline, and at which horizons."""
    vs = [v for v in doc.get("verdicts") or [] if v["baseline"] == base]
    if not vs:
        return None
    horizons = " or ".join(ahead(doc, t) for t in dict.fromkeys(v["table"] for v in vs))
    beats, rest, missing, flagged = [], [], [], []
    for row in dict.fromkeys(v["row"] for v in vs):
        mine = [v for v in vs if v["row"] == row]
        won = [ahead(doc, v["table"]) for v in mine if v["status"] == "holds"]
        label = label_for(doc, row)
        if any(_verdict_flag(doc, v) for v in mine):
            flagged.append(label)
        elif won:
            beats.append(f"{label} at {' and '.join(won)}")
        elif all(v["status"] == "not evaluated" for v in mine):
            missing.append(label)
        else:
            rest.append(label)
    name = _baseline_name(doc, base)
    how = "best-of-K ADE on the same windows, after Holm"
    if beats:
        text = f"Shown to beat {name} ({how}): {'; '.join(beats)}"
        text += f"; not shown at {horizons}: {', '.join(rest)}" if rest else ""
    else:
        text = f"No served learned model is shown to beat {name} at {horizons} ({how}"
        text += f"; compared: {', '.join(rest)})" if rest else ")"
    text += f"; not evaluated: {', '.join(missing)}" if missing else ""
    return text + (f"; not scored, as they do not predict: {', '.join(flagged)}" if flagged else "") + "."


def _verdicts(doc: dict) -> list[str]:
    table = verdict_table(doc)
    if not table:
        return []
    n = (doc.get("comparisons") or {}).get("copying")
    learned = ", ".join(f"`{r}`" for r in doc.get("served_learned", []))
    return ["## Served learned models against the baselines", "",
            f"Each model the site serves that learns from data ({learned}) against standing still (zero-velocity), "
            "the regression GRU and the nearest training window's future, on held-out people: best-of-K ADE "
            "(root-relative) of both rows on the same windows (those the model accepts), with their count. A model "
            "**beats** a baseline when its ADE is lower by more than the 2σ bar and the comparison passes Holm's "
            f"correction over the {'' if n is None else f'{n} '}copying comparisons.", ""]\
        + [f"- {x}" for x in (beaten_line(doc, b) for b in VERDICT_BASELINES) if x] + [""] + table + [""]


# --- motion realism (Evaluation v3, items 2 and 5) --------------------------------------------------

def realism_rows(doc: dict, t: dict) -> list[dict]:
    """The rows a realism table shows: the ground truth, the baselines and the served models, each also
    with its own root where the table has that row (feet not planted, rows.py)."""
    return [r for r in t["rows"] if r.get("values") and not r.get("skipped")
            and (r["kind"] in ("oracle", "baseline") or (r["kind"] == "model" and (
                r["id"] in doc["models"] or r["id"].removesuffix("-own-root") in doc["models"])))]


def _per_second(t: dict, prefix: str) -> list[str]:
    return [c for c in t["columns"] if c.startswith(prefix)]


def refused(r: dict, t: dict) -> int:
    """How many of the table's windows a row refuses (older results carry only its items)."""
    of = t.get("items") or t.get("windows") or 0
    return (r.get("refused") or {}).get("items", of - r.get("items", of))


def truth_beside(t: dict, r: dict, col: str) -> str:
    """The ground truth's value of `col` on exactly the windows `r` predicts: the oracle row's when `r`
    predicts them all, its `paired` value when it refuses some, "—" when the results do not hold that."""
    if r["kind"] == "oracle":
        return "—"
    if not refused(r, t):
        return cell((row_of(t, "oracle") or {}).get("values", {}).get(col), COLUMNS[col].unit)
    x = ((r.get("paired") or {}).get("rows", {}).get("oracle") or {}).get(col)
    return fmt(x, COLUMNS[col].unit) if x is not None else "—"


def calibrated(r: dict) -> str:
    """The share of windows a calibrated sampler of K futures leaves outside: 100/(K+1)."""
    k = r.get("k") or 1
    return fmt(100.0 / (k + 1), "%") if k > 1 else "—"


def _realism_table(doc: dict, t: dict) -> list[str]:
    rows = realism_rows(doc, t)
    joint, root = _per_second(t, "speed_ratio_s"), _per_second(t, "root_ratio_s")
    j = doc.get("data", {}).get("joints", 18)
    v = lambda r, c: cell(r["values"].get(c), COLUMNS[c].unit)
    head = lambda *names: ["| row | windows | " + " | ".join(names) + " |", "|---|---|" + "---|" * len(names)]
    line = lambda r, cells: f"| {row_label(r)} | {windows_text(r, t)} | " + " | ".join(cells) + " |"
    out = [f"### {t['title']} (`{t['id']}`)", "",
           f"{t['items']} windows from {t['takes']} takes of {len(t['people'])} people. Every value is over the "
           "windows the row predicts (its count beside it); the ground truth's value beside a row is on those same "
           "windows.", "",
           f"Error per joint (cm) beside the field's whole-pose ADE and FDE (m): the whole-pose L2 is about √{j} × "
           f"the per-joint distance for {j} joints.", ""]
    out += head("per joint, best of K (cm)", "per joint at the horizon (cm)", "ADE best of K (m)", "FDE best of K (m)")
    out += [line(r, [v(r, "mpjpe_cm"), v(r, "mpjpe_f_cm"), v(r, "ade"), v(r, "fde")]) for r in rows] + [""]
    if joint or root:
        out += ["Speed against the truth's, second by second: the prediction's mean speed over the truth's on the "
                "same windows (1 is the truth's speed; 0 stands still).", ""]
        out += head(*[f"joints, second {c.rsplit('s', 1)[1]} (×)" for c in joint],
                    *[f"root, second {c.rsplit('s', 1)[1]} (×)" for c in root])
        out += [line(r, [v(r, c) for c in joint + root]) for r in rows] + [""]
    out += ["Following the history, feet, coverage and spread: ρ is Spearman's between the history's joint speed and "
            "the first predicted second's over the windows (the truth's own ρ beside it); skating is the median "
            "speed of a foot in contact (the captures' beside it); a calibrated sampler of K futures leaves the truth "
            "outside every sample in 100/(K+1)% of windows, and the audit's rule (farther from the samples' mean than "
            "every sample) is reported beside it; full length is the share of samples lasting the whole horizon "
            "(WAT's stop can end them early).", ""]
    out += head("ρ", "truth's ρ", "skating (m/s)", "captures' skating (m/s)", "truth outside (%)",
                "calibrated 100/(K+1) (%)", "outside, the audit's rule (%)", "spread at the last frame (cm)",
                "full length (%)")
    out += [line(r, [v(r, "follow"), truth_beside(t, r, "follow"), v(r, "skate"), truth_beside(t, r, "skate"),
                     v(r, "outside"), calibrated(r), v(r, "outside_naive"), v(r, "spread_cm"), v(r, "full")])
            for r in rows] + [""]
    if any(c in r["values"] for r in rows for c in ("pskl_gp", "pskl_pg", "cmd")):
        out += ["Distributions: PSKL both ways (Keyposes sec. 4.3) and CMD (BeLFusion), each row's futures against the "
                "captured futures of the windows it predicts.", ""]
        out += head(*[label_of(c) for c in ("pskl_gp", "pskl_pg", "cmd")])
        out += [line(r, [v(r, c) for c in ("pskl_gp", "pskl_pg", "cmd")]) for r in rows] + [""]
    return out + _on_accepted(doc, t, rows) + _realism_groups(doc, t, rows)


def _on_accepted(doc: dict, t: dict, rows: list[dict]) -> list[str]:
    """A row that refuses windows beside the baselines and the truth on exactly the windows it accepts."""
    out = []
    for r in rows:
        paired = r.get("paired") or {}
        if not paired.get("rows"):
            continue
        order = [r["id"], *[x for x in paired["rows"] if x != r["id"]]]
        cols = [c for c in COLUMNS if any(c in paired["rows"][x] for x in order)]
        share = fmt(100.0 * refused(r, t) / t["items"], "%")
        out += [f"{r['label']} predicts {paired['items']} of the {t['items']} windows ({share}% refused); on exactly "
                "those windows, beside the truth and the baselines:", "",
                "| row | " + " | ".join(label_of(c) for c in cols) + " |", "|---|" + "---|" * len(cols)]
        for x in order:
            label = (row_of(t, x) or {"label": x})["label"]
            out.append(f"| {label} | " + " | ".join(fmt(paired["rows"][x].get(c), COLUMNS[c].unit) for c in cols)
                       + " |")
        out.append("")
    return out


def _group_windows(r: dict, g: dict) -> str:
    """A row's windows in an action group: the items of its per-item values there, of the group's."""
    return f"{group_windows(g)}/{g['items']}"


def _realism_groups(doc: dict, t: dict, rows: list[dict]) -> list[str]:
    """The same measures per action group, each group over its own windows (means; the bars are in results.json)."""
    order = doc.get("data", {}).get("groups") or list(dict.fromkeys(g for r in rows for g in r.get("by_group", {})))
    joint, root = _per_second(t, "speed_ratio_s"), _per_second(t, "root_ratio_s")
    oracle = row_of(t, "oracle") or {}
    out = []
    for name in order:
        have = [r for r in rows if name in r.get("by_group", {})]
        if not have:
            continue
        g0 = have[0]["by_group"][name]
        truth = (oracle.get("by_group") or {}).get(name, {}).get("values", {})
        jump = name == "jump"
        out += [f"*{name}*: {counted(g0['items'], 'window')}, {counted(g0['people'], 'person', 'people')}, "
                f"{counted(g0['takes'], 'take')}.", "",
                "| row | windows | per joint (cm) | per joint at the horizon (cm) | ADE (m) | joint speed / truth's, "
                "by second (×) | root speed / truth's, by second (×) | ρ | truth's ρ | skating (m/s) | captures' "
                "skating (m/s) | truth outside (%) | calibrated (%) | spread (cm) | full length (%) |"
                + (" hip range (m) | captures' hip range (m) |" if jump else ""),
                "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|" + ("---|---|" if jump else "")]
        for r in have:
            g = r["by_group"][name]
            m = lambda c: fmt(g["values"][c]["mean"], COLUMNS[c].unit) if c in g["values"] else "—"
            whole = group_windows(g) == g["items"]
            beside = lambda c: "—" if r["kind"] == "oracle" or not whole or c not in truth \
                else fmt(truth[c]["mean"], COLUMNS[c].unit)
            cells = [m("mpjpe_cm"), m("mpjpe_f_cm"), m("ade"), " · ".join(m(c) for c in joint) or "—",
                     " · ".join(m(c) for c in root) or "—", m("follow"), beside("follow"), m("skate"), beside("skate"),
                     m("outside"), calibrated(r), m("spread_cm"), m("full")]
            cells += [m("hip_range"), beside("hip_range")] if jump else []
            out.append(f"| {row_label(r)} | {_group_windows(r, g)} | " + " | ".join(cells) + " |")
        out.append("")
    if out:
        out = ["By action group (each group over its own windows; means, their bars are in `results.json`; the "
               "truth's value beside a row only where the row predicts every window of the group; the hip's vertical "
               "range is read for jump):", ""] + out
    return out


def _realism(doc: dict) -> list[str]:
    tables = [t for t in doc["tables"] if t["truth"] and not t.get("in_sample")
              and any(COLUMNS[c].section == "realism" for c in t["columns"] if c in COLUMNS)]
    if not tables:
        return []
    lines = ["## Motion realism", "",
             "Does the motion look like people's? For every served model and baseline, and the ground truth (its "
             "values are the captured motion's own), on held-out people. A row that refuses windows says how many, "
             "and is set beside the baselines and the truth on exactly the windows it accepts.", ""]
    for t in tables:
        lines += _realism_table(doc, t)
    return lines


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


COPY_COLUMNS = (("nearest-window", "vs nearest training window"), ("own", "vs repeat last cycle (own history)"),
                ("repeat-cycle-60", "vs repeat last cycle (60 frames)"), ("zero-velocity", "vs zero-velocity"),
                ("regression-gru", "vs regression GRU"))


def _copy_cell(c: dict | None) -> str:
    if not c:
        return "—"
    return (f"{fmt(c['difference'], 'm')} m, 2σ {fmt(c['bar'], 'm')}{_holm(c)}: "
            f"{COPY_WORDS.get(c['status'], 'does not beat')} ({c['status']})")


def _copying(doc: dict) -> list[str]:
    if not doc.get("copying"):
        return []
    lines = ["## Copying and memorising", "",
             "Every model against the baselines that copy the history (repeat its last cycle) and memorise the "
             "training people (the nearest training window's future), and against standing still and the regression "
             "GRU, on best-of-K ADE (root-relative), paired on the windows both predict (their count in the windows "
             "column). A model that does not beat the nearest training window on held-out people reports "
             "memorisation; one that does not beat repeating the last cycle reports copying. " + _copying_rule(doc), ""]
    by_table: dict[str, dict[str, dict[str, dict]]] = {}
    for c in doc["copying"]:
        key = c["baseline"] if c["baseline"] in dict(COPY_COLUMNS) else "own"
        by_table.setdefault(c["table"], {}).setdefault(c["label"], {})[key] = c
    for tid, rows in by_table.items():
        keys = [(k, h) for k, h in COPY_COLUMNS if any(k in cs for cs in rows.values())]
        lines += [f"Table `{tid}` (ADE difference model − baseline, its 2σ bar, and the verdict):", "",
                  "| model | windows | " + " | ".join(h for _, h in keys) + " |", "|---|---|" + "---|" * len(keys)]
        for label, cs in rows.items():
            n = "/".join(str(x) for x in dict.fromkeys(c["items"] for c in cs.values()))
            lines.append(f"| {label} | {n} | " + " | ".join(_copy_cell(cs.get(k)) for k, _ in keys) + " |")
        lines.append("")
    memo = [c for c in doc["copying"] if c["baseline"] == "nearest-window" and c["status"] != "holds"]
    if memo:
        lines += ["Not beating the nearest training window (reporting memorisation): "
                  + "; ".join(f"{c['label']} in `{c['table']}` ({c['status']})" for c in memo) + ".", ""]
    unscored = [(t["id"], r) for t in doc["tables"] if t["truth"] and not t.get("in_sample")
                for r in t["rows"] if r.get("flag") and r["kind"] == "model"]
    if unscored:
        lines += ["Not scored here, as their futures are not predictions: "
                  + "; ".join(f"{r['label']} in `{tid}` ({flag_text(r['flag'])})" for tid, r in unscored) + ".", ""]
    return lines


def _copying_rule(doc: dict) -> str:
    n = (doc.get("comparisons") or {}).get("copying")
    return (f"A model **beats** a baseline when its ADE is lower by more than the 2σ bar and the comparison passes "
            f"Holm's step-down correction at family-wise α 0.05 over the {'' if n is None else f'{n} '}copying "
            "comparisons (a family of their own, apart from the claims); a difference below the practical minimum "
            "(1 mm or 1% of the baseline's ADE) is **no different from**.")


def _shape_windows(doc: dict, s: dict) -> str:
    t = table_of(doc, s["table"]) or {"items": 0, "rows": []}
    return " / ".join(windows_text(row_of(t, x) or {"items": 0}, t) for x in (s["with"], s["without"]))


def _within(s: dict) -> str:
    """"yes"/"no", and why never "yes" for a row that does not predict."""
    return ("yes" if s["within"] else "no") + (f" ({flag_text(s['flag'])})" if s.get("flag") else "")


def _shape(doc: dict) -> list[str]:
    if not doc.get("shape"):
        return []
    lines = ["## With and without the shape terms (issue 17)", "",
             "Each stochastic model against its ablation without the seam layer, fixed bone lengths and floor term: "
             f"APD and best-of-K ADE, and whether the model without them is within "
             f"{round(100 * doc['shape'][0]['tolerance'])}% of the model with them (never, when a row does not "
             "predict). A measurement, not a claim; each row's windows are beside it.", "",
             "| model | table | windows (with / without) | metric | with | without | without / with | within |",
             "|---|---|---|---|---|---|---|---|"]
    for s in doc["shape"]:
        unit = COLUMNS[s["metric"]].unit
        lines.append(f"| {s['with']} | {s['table']} | {_shape_windows(doc, s)} | {COLUMNS[s['metric']].label} | "
                     f"{cell(s['with_value'], unit)} | {cell(s['without_value'], unit)} | {fmt(s['ratio'])} | "
                     f"{_within(s)} |")
    return lines + [""]


def _comparisons(doc: dict) -> list[str]:
    """One small table per comparison and table: columns are the rows compared, lines the metrics."""
    from .rows import COMPARISONS
    out = []
    by_table = {t["id"]: {r["id"]: r for r in t["rows"] if r.get("values")} for t in doc["tables"]}
    by_doc = {t["id"]: t for t in doc["tables"]}
    for c in COMPARISONS:
        blocks = []
        for tid in c.tables:
            shown = [r for r in (by_table.get(tid, {}).get(x) for x in c.rows) if r]
            if len(shown) < 2:
                continue
            blocks += [f"Table `{tid}`:", "", "| metric | " + " | ".join(row_label(r) for r in shown) + " |",
                       "|---|" + "---|" * len(shown), "| windows | " + " | ".join(windows_text(r, by_doc[tid])
                                                                         for r in shown) + " |"]
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
    lines += ["- **Planted feet** (ours, every model): the site and the served rows re-derive the root's horizontal "
              "travel while a foot is on the floor, so that foot stays put in the world (export/ops/foot_plant.py; "
              "heights, root-relative poses and lengths unchanged). Rows \"own root (feet not planted)\" keep each "
              "method's own root travel, on the same windows.",
              "- **Training variants** (ours, labelled config keys; each served config says whether it uses one, and "
              "each choice's measurement is in a comment beside it): slowed same-action pairs (`augment`, "
              "export/ops/time_scale.py); a speed term on a future drawn from the prior (`loss.prior_speed`, "
              "export/ops/speed_term.py); the root read as per-frame steps and the history's steps beside its poses "
              "(`model.root_input`, `model.history_steps`, export/models/inputs.py); for Keyposes, training futures "
              "with a keypose every 30 frames inside longer gaps, so a held pose is learnt as its own label (sec. 3.2 "
              "prunes it to one 30-frame step; `keyposes.split_holds`, export/ops/keyposes.py).",
              "- **Keyposes' interpolation**: the paper's tables use linear interpolation between keyposes (rows "
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
            lines.append(f"| {row_label(r)} | {windows_text(r, t)} | {r.get('runs', 0)} | "
                         + " | ".join(cell(r.get("values", {}).get(c), COLUMNS[c].unit) for c in cols) + " |")
        lines.append("")
    if t.get("mmade") and any("mmade_half" in r.get("values", {}) for r in rows):
        lines += ["MMADE / MMFDE sensitivity to the threshold (m):", "",
                  "| row | MMADE ½ | MMADE | MMADE 2× | MMFDE ½ | MMFDE | MMFDE 2× |", "|---|---|---|---|---|---|---|"]
        for r in rows:
            v = r.get("values", {})
            lines.append(f"| {row_label(r)} | " + " | ".join(cell(v.get(c), "m") for c in (
                "mmade_half", "mmade", "mmade_double", "mmfde_half", "mmfde", "mmfde_double")) + " |")
        lines.append("")
    acts = t["actions"]
    if t["truth"] and not t.get("in_sample") and any(r.get("by_action", {}).get("ade") for r in rows):
        lines += ["ADE best of K (root-relative, m) per action:", "",
                  "| row | " + " | ".join(acts) + " |", "|---|" + "---|" * len(acts)]
        for r in rows:
            per = r.get("by_action", {}).get("ade", {})
            lines.append(f"| {row_label(r)} | " + " | ".join(fmt(per.get(a)) for a in acts) + " |")
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
    lines += _data(doc) + _targets(doc) + _verdicts(doc) + _claims(doc) + _copying(doc) + _shape(doc) + _realism(doc) + _rows(doc)
    lines += _comparisons(doc) + _variants(doc) + _sanity(doc)
    lines += _classifiers(doc)
    for t in sorted(doc["tables"], key=lambda t: bool(t.get("in_sample"))):
        lines += _table(doc, t)
    if doc["skipped"]:
        lines += ["## Rows not evaluated yet", ""]
        lines += [f"- {s['label']} (`{s['row']}`): {s['reason']}" for s in doc["skipped"]]
        lines.append("")
    return "\n".join(lines)


def _target_value(x: dict) -> str:
    v = x["value"]
    if v is None:
        return "not measured"
    if isinstance(v, str):
        return v
    unit = "×" if x["limit"].endswith("x") else ""
    return fmt(v) + unit


def _targets(doc: dict) -> list[str]:
    """Issue 28's targets per served learned model: value beside limit, met or missed (export/eval/targets.py)."""
    rows = targets(doc)
    if not rows:
        return []
    lines = ["## Futures that move like people: the targets", "",
             "Each served learned model against the targets of \"Futures that move like people\", read from the tables "
             "below (held-out people; the rules are in `export/eval/targets.py`). " + "; ".join(
                 f"{label_for(doc, m)}: {t['met']} met, {t['missed']} missed" + (f", {t['not measured']} not measured"
                                                                                 if t["not measured"] else "")
                 for m, t in tally(rows).items()) + ".", "",
             "| model | table | group | target | value | limit | |", "|---|---|---|---|---|---|---|"]
    for x in rows:
        mark = "**missed**" if x["met"] is False else STATUS[x["met"]]
        lines.append(f"| {label_for(doc, x['model'])} | `{x['table']}` | {x['group']} | {x['target']} | "
                     f"{_target_value(x)} | {x['limit']} | {mark} |")
    return lines + [""]


def _data(doc: dict) -> list[str]:
    """The split: per action, who the models learn from and who they are tested on, and what cannot be
    evaluated (actions without a held-out person; horizons no held-out take of an action holds)."""
    d = doc.get("data", {})
    per = d.get("per_action")
    if not per:
        return []
    lines = ["## The data and the split", "",
             f"Held out: subjects {', '.join(d['heldout_people'])} ({d['heldout_takes']} takes, {fmt(d['heldout_seconds'])} s); "
             f"trained on: {', '.join(d.get('train_people_list', []))} ({d['train_takes']} takes, {fmt(d['train_seconds'])} s). "
             f"The {d.get('balance', '')} (`export/data/balance.py`).", "",
             "| action | group | train people | train takes | train s | held-out people | held-out takes | held-out s |",
             "|---|---|---|---|---|---|---|---|"]
    for a, v in per.items():
        tr, te = v["train"], v["test"]
        lines.append(f"| {a} | {v['group']} | {', '.join(tr['people']) or '—'} | {tr['takes']} | {tr['seconds']:.1f} | "
                     f"{', '.join(te['people']) or '— (trained on only)'} | {te['takes']} | {te['seconds']:.1f} |")
    exceptions = [f"`{t['id']}`: {', '.join(sorted(e['action'] for e in t['exceptions']))}"
                  for t in doc["tables"] if t.get("exceptions")]
    lines += ["", "Not evaluated: " + (", ".join(d.get("train_only_actions", [])) or "none")
              + " (no held-out person). Horizon exceptions (no held-out take of the action holds history + horizon; "
              "never padded): " + ("; ".join(exceptions) or "none") + ".", ""]
    return lines


def write_markdown(doc: dict, path: Path = RESULTS_MD) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(markdown(_round(doc)))
