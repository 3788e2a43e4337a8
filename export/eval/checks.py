"""The checks on a finished evaluation: sanity rows and classifier checks (each can fail), the papers' claims,
the copying and memorising baselines against every model, and the disclosed variants."""
from __future__ import annotations

import math

import numpy as np

from ..data.skeleton import SKELETON
from . import metrics as M
from . import stats as S
from .harness import COLUMNS, RECOGNITION
from .rows import CLAIMS, SHAPE_METRICS, SHAPE_PAIRS, SHAPE_TOLERANCE, Part, Trend

COPY_BASELINES = ("nearest-window", "repeat-cycle")


def sanity_checks(tables: list[dict], clf_report: dict, cfg: dict) -> list[dict]:
    """The checks that can fail: each {"id", "table", "text", "expected", "measured", "passed"}."""
    out = []
    sigma = float(cfg["noise_sigma"])
    expected = M.noise_diversity(sigma, SKELETON.num_joints * 3)
    for table in tables:
        noise = next((r for r in table["rows"] if r["id"] == "noise" and "div" in r.get("values", {})), None)
        if noise:
            got = noise["values"]["div"]["mean"]
            out.append({"id": "noise-diversity", "table": table["id"],
                        "text": f"Ground truth + N(0, {sigma} m²) has the analytic diversity "
                                f"2σ·Γ((D+1)/2)/Γ(D/2) with D = {SKELETON.num_joints * 3} (Eq. 10), within 5%",
                        "expected": expected, "measured": got, "passed": abs(got / expected - 1) < 0.05})
    shuffled = clf_report.get("pose_gru_shuffled")
    if shuffled and shuffled.get("check_snippets"):
        chance = shuffled["check_chance"]
        n = int(shuffled["check_snippets"])
        lo, hi = S.binomial_band(n, chance / 100, 0.99)
        got = shuffled["check_accuracy"]
        out.append({"id": "shuffled-labels", "table": None,
                    "text": f"The pose GRU trained on shuffled labels scores at chance on held-out people: "
                            f"{chance:.1f}% (its own prediction frequencies against the true ones; uniform "
                            f"guessing: {shuffled['chance']:.1f}%), 99% binomial band [{100 * lo:.1f}, "
                            f"{100 * hi:.1f}] over {n} non-overlapping held-out snippets",
                    "expected": chance, "measured": got, "low": 100 * lo, "high": 100 * hi,
                    "passed": 100 * lo <= got <= 100 * hi})
    return out


def _capture_accuracy(clf: dict, actions: list[str]) -> float | None:
    """A classifier's held-out accuracy on captured snippets, the mean over `actions` (as the tables balance)."""
    vals = [clf["test_groups"][a]["accuracy"] for a in actions if a in clf.get("test_groups", {})]
    return float(np.mean(vals)) if vals else None


def recognition_checks(tables: list[dict], clf_report: dict) -> list[dict]:
    """"The ground truth scores best on recognition", per table and classifier, as it comes out: the captured
    futures (the oracle row; in a table without ground truth, the held-out captured snippets of the requested
    actions) against every other row. A failure makes that table's recognition claims unusable."""
    out = []
    for table in tables:
        oracle = next((r for r in table["rows"] if r["id"] == "oracle" and r.get("values")), None)
        for col in RECOGNITION:
            kind = "pose_gru" if col == "acc_pose" else "moac"
            if oracle is not None:
                if col not in oracle["values"]:
                    continue
                truth, what = oracle["values"][col]["mean"], "the captured futures"
            elif not table["truth"] and kind in clf_report:
                truth, what = _capture_accuracy(clf_report[kind], table["actions"]), \
                    "held-out captured snippets of the requested actions"
                if truth is None:
                    continue
            else:
                continue
            others = [(r["label"], r["values"][col]["mean"]) for r in table["rows"]
                      if r["kind"] not in ("oracle", "noise") and col in r.get("values", {})]
            if not others:
                continue
            best = max(others, key=lambda x: x[1])
            out.append({"id": f"oracle-best-{col}", "table": table["id"], "metric": col,
                        "text": f"Ground truth scores best on recognition ({COLUMNS[col].label}): {what} against "
                                f"every row; best other: {best[0]}",
                        "expected": best[1], "measured": truth, "passed": truth >= best[1]})
    return out


def _value(by_table: dict, table: str, row: str, metric: str) -> dict | None:
    t = by_table.get(table)
    r = next((x for x in (t or {}).get("rows", []) if x["id"] == row), None)
    return (r or {}).get("values", {}).get(metric)


def compare_rows(by_table: dict, store: dict, tabs: dict, table: str, a: str, b: str, metric: str, direction: str,
                 metric_b: str | None = None, margin: float = 0.0) -> dict:
    """One paired comparison with its numbers; "not evaluated" (and what is missing) when a row has no values."""
    metric_b = metric_b or metric
    sa, sb = store.get(table, {}).get(a), store.get(table, {}).get(b)
    av, bv = _value(by_table, table, a, metric), _value(by_table, table, b, metric_b)
    out = {"table": table, "a": a, "b": b, "metric": metric, "metric_b": metric_b, "direction": direction,
           "margin": margin, "a_value": av, "b_value": bv,
           "missing": [x for x, s, m in ((a, sa, metric), (b, sb, metric_b)) if s is None or m not in s.items]}
    if out["missing"]:
        return {**out, "status": S.MISSING, "difference": None, "bar": None, "people": 0, "takes": 0, "items": 0}
    res = S.compare(sa.items[metric], sb.items[metric_b], tabs[table].units, tabs[table].weights,
                    sa.seed_std[metric], sb.seed_std[metric_b], direction, COLUMNS[metric].balanced, margin,
                    COLUMNS[metric].unit)
    return {**out, **res}


def compare_trend(by_table: dict, store: dict, tabs: dict, t: Trend) -> dict:
    """A trend part with its numbers. It also carries a (the last setting's row) and b (the first's), so a reader
    of pairs still reads it: its difference is the fitted change from b's setting to a's."""
    rows = list(t.rows)
    stats_ = [store.get(t.table, {}).get(r) for r in rows]
    out = {"kind": "trend", "table": t.table, "rows": rows, "setting": t.setting, "settings": t.settings(),
           "a": rows[-1], "b": rows[0], "metric": t.metric, "metric_b": t.metric, "direction": t.direction,
           "margin": 0.0, "a_value": _value(by_table, t.table, rows[-1], t.metric),
           "b_value": _value(by_table, t.table, rows[0], t.metric),
           "missing": [r for r, s in zip(rows, stats_) if s is None or t.metric not in s.items]}
    if out["missing"]:
        return {**out, "status": S.MISSING, "difference": None, "bar": None, "p": None, "people": 0, "takes": 0,
                "items": 0}
    spec = COLUMNS[t.metric]
    res = S.trend([s.items[t.metric] for s in stats_], tabs[t.table].units, tabs[t.table].weights,
                  [s.seed_std[t.metric] for s in stats_], t.direction, spec.balanced, spec.unit)
    return {**out, **res}


def holm_correct(family: list[dict], what: str, alpha: float = S.ALPHA) -> None:
    """Holm over a family of comparisons (each with its "p"): each gets "p_holm"; one the data say holds but Holm
    does not pass is inconclusive, with the reason."""
    for x, q in zip(family, S.holm([x["p"] for x in family])):
        x["p_holm"] = float(q)
        if x["status"] == S.HOLDS and q > alpha:
            x.update(status=S.INCONCLUSIVE,
                     reason=f"beyond its 2σ bar, but not after Holm's correction over {len(family)} {what} "
                            f"(adjusted p {q:.2g} > {alpha})")


def _claim_part(by_table: dict, store: dict, tabs: dict, claim, p: Part | Trend) -> dict:
    """A part as the data say, or labelled in-sample / by construction (neither is counted)."""
    if isinstance(p, Trend):
        part = compare_trend(by_table, store, tabs, p)
    else:
        part = compare_rows(by_table, store, tabs, p.table, p.a, p.b, p.metric, p.direction, p.metric_b, p.margin)
    construction = getattr(p, "construction", "") or claim.construction
    if by_table.get(p.table, {}).get("in_sample"):
        part.update(status=S.IN_SAMPLE, reason="an in-sample table never backs a claim")
    elif construction:
        part.update(status=S.BY_CONSTRUCTION, reason=construction)
    return part


def counted(part: dict) -> bool:
    """A comparison made on the data: not by construction, in-sample or missing."""
    return part["status"] not in (S.BY_CONSTRUCTION, S.IN_SAMPLE, S.MISSING)


def _unusable(part: dict, failed: set) -> bool:
    rec = {part["metric"], part["metric_b"]} & set(RECOGNITION)
    return counted(part) and any((part["table"], m) in failed for m in rec)


def evaluate_claims(by_table: dict, store: dict, tabs: dict, recognition: list[dict]) -> list[dict]:
    """Every claim with its parts. The counted parts of all claims are one Holm family; a part on a classifier that
    failed its check is then unusable, keeping what the data would say in "data_status"."""
    failed = {(c["table"], c["metric"]) for c in recognition if not c["passed"]}
    parts_of = [[_claim_part(by_table, store, tabs, claim, p) for p in claim.parts] for claim in CLAIMS]
    holm_correct([x for parts in parts_of for x in parts if counted(x)], "claim parts")
    out = []
    for claim, parts in zip(CLAIMS, parts_of):
        for part in parts:
            if _unusable(part, failed):
                part.update(data_status=part["status"], status=S.UNUSABLE,
                            reason="the ground truth does not score best on this classifier in table "
                                   f"{part['table']}, so its recognition numbers cannot rank rows")
        statuses = [x["status"] for x in parts if x["status"] != S.BY_CONSTRUCTION]
        status = S.BY_CONSTRUCTION if claim.construction else S.combine(statuses)
        doc = {"id": claim.id, "paper": claim.paper, "text": claim.text, "status": status,
               "reason": claim.construction or next((x.get("reason") for x in parts if x["status"] == status
                                                     and x.get("reason")), ""),
               "parts": parts}
        if status == S.UNUSABLE:
            doc["data_status"] = S.combine([x.get("data_status", x["status"]) for x in parts
                                            if x["status"] != S.BY_CONSTRUCTION])
        out.append(doc)
    return out


def comparisons(claims: list[dict], copying: list[dict]) -> dict:
    """How many comparisons each family made, and how they are corrected."""
    return {"claims": sum(counted(p) for c in claims for p in c["parts"]),
            "copying": sum(counted(c) for c in copying),
            "correction": f"{S.CORRECTION}; two families (the claim parts, the copying comparisons), each corrected "
                          "on its own"}


def claims_tally(claims: list[dict]) -> dict:
    """How many claims have each status; "by construction" ones are listed and not counted."""
    listed = [c for c in claims if c["status"] != S.BY_CONSTRUCTION]
    out = {s: sum(c["status"] == s for c in listed) for s in S.STATUSES if s != S.BY_CONSTRUCTION}
    out.update(counted=len(listed), by_construction=len(claims) - len(listed))
    return out


def _history_of(by_table: dict, table: str, row: str) -> int | None:
    r = next((x for x in by_table[table]["rows"] if x["id"] == row), None)
    return (r or {}).get("history_frames")


def copying_checks(by_table: dict, store: dict, tabs: dict) -> list[dict]:
    """Every model row of every held-out table with ground truth against the baselines that copy (repeat the
    last cycle: its own history length, and the longer one) and memorise (the nearest training window), and
    against standing still (zero-velocity), on best-of-K ADE (root-relative). Not beating them is reported as
    copying or memorising."""
    out = []
    for tid, table in by_table.items():
        if not table["truth"] or table.get("in_sample"):
            continue
        rows = {r["id"]: r for r in table["rows"] if r.get("values")}
        for r in table["rows"]:
            # a row whose futures are not predictions (harness.does_not_predict) is marked, not scored
            if r["kind"] != "model" or "ade" not in r.get("values", {}) or r.get("flag"):
                continue
            cycle = f"repeat-cycle-{r.get('history_frames')}"
            for base in ("nearest-window", cycle if cycle in rows else None, "repeat-cycle-60", "zero-velocity",
                         "regression-gru"):
                if base is None or base not in rows or base == r["id"]:
                    continue
                c = compare_rows(by_table, store, tabs, tid, r["id"], base, "ade", "less")
                out.append({**c, "row": r["id"], "label": r["label"], "baseline": base,
                            "baseline_label": rows[base]["label"]})
    holm_correct([c for c in out if counted(c)], "copying comparisons")
    for c in out:
        c["verdict"] = copying_verdict(c)
    return out


def served_verdicts(copying: list[dict], served: list[str], tables=("heldout_1s", "heldout_2s"),
                    baselines=("zero-velocity", "regression-gru", "nearest-window")) -> list[dict]:
    """The tally a reader needs (Evaluation v3, item 6): for each served learned model, whether it is shown
    to beat zero-velocity, the regression GRU and the nearest training window, in each held-out table; the
    statuses are the copying family's, after Holm."""
    out = []
    for row in served:
        for table in tables:
            for base in baselines:
                if base == row:
                    continue
                c = next((x for x in copying if x["row"] == row and x["table"] == table and x["baseline"] == base), None)
                out.append({"row": row, "table": table, "baseline": base,
                            "status": c["status"] if c else S.MISSING,
                            "difference": c.get("difference") if c else None, "bar": c.get("bar") if c else None,
                            "a_paired": c.get("a_paired") if c else None, "b_paired": c.get("b_paired") if c else None,
                            "p": c.get("p") if c else None, "p_holm": c.get("p_holm") if c else None,
                            "items": c.get("items") if c else 0, "label": c["label"] if c else row,
                            "baseline_label": c["baseline_label"] if c else base})
    return out


def copying_verdict(c: dict) -> str:
    """What a copying comparison says, after Holm (a model "beats" a baseline only when the comparison holds)."""
    base = c["baseline_label"].lower()
    what = {"nearest-window": "memorising", "zero-velocity": "standing still"}.get(c["baseline"], "copying its history")
    if c["status"] == S.HOLDS:
        return f"beats {base}"
    if c["status"] == S.NO_DIFFERENCE:
        return f"is no different from {base} (the difference is below the practical minimum): no better than {what}"
    if c["status"] == S.FAILS:
        return f"does not beat {base}: its accuracy is worse than {what}"
    return f"does not beat {base}: its accuracy is not shown to be better than {what}"


def shape_comparison(by_table: dict, store: dict, tabs: dict) -> list[dict]:
    """Issue 17's shape terms: each stochastic model with and without them, APD and best-of-K ADE in the held-out
    tables; "within" says whether the model without them is within 10% of the model with them."""
    out = []
    for tid, table in by_table.items():
        if table.get("in_sample") or not table["truth"]:
            continue
        for with_, without in SHAPE_PAIRS:
            for metric in SHAPE_METRICS:
                a, b = _value(by_table, tid, with_, metric), _value(by_table, tid, without, metric)
                if a is None or b is None:
                    continue
                c = compare_rows(by_table, store, tabs, tid, without, with_, metric, "greater")
                ratio = b["mean"] / a["mean"] if a["mean"] else math.nan
                flags = [_flag_of(by_table, tid, x) for x in (with_, without)]
                out.append({"table": tid, "with": with_, "without": without, "metric": metric,
                            "with_value": a, "without_value": b, "ratio": ratio,
                            # a row that does not predict is never "within 10%" of one that does
                            "within": bool(abs(ratio - 1) <= SHAPE_TOLERANCE) and not any(flags),
                            "flag": "; ".join(f for f in flags if f), "tolerance": SHAPE_TOLERANCE,
                            "difference": c["difference"], "bar": c["bar"]})
    return out


def _flag_of(by_table: dict, table: str, row: str) -> str:
    r = next((x for x in by_table.get(table, {}).get("rows", []) if x["id"] == row), None)
    return (r or {}).get("flag", "")


def variant_report(by_table: dict, tabs: dict) -> dict:
    """The choices that change the numbers, disclosed (issue 18, item 6): Eq. 4 squared vs unsquared (does the
    ranking of the rows change?), and keyposes per history under the mean-error and the max-error rules."""
    eq4 = []
    for tid, table in by_table.items():
        rows = [r for r in table["rows"] if r["kind"] == "model" and "smooth" in r.get("values", {})
                and "smooth_unsq" in r["values"]]
        if len(rows) < 2:
            continue
        printed = [r["id"] for r in sorted(rows, key=lambda r: r["values"]["smooth"]["mean"])]
        code = [r["id"] for r in sorted(rows, key=lambda r: r["values"]["smooth_unsq"]["mean"])]
        eq4.append({"table": tid, "printed": printed, "code": code, "same_order": printed == code})
    rules = {}
    from .variants import keypose_counts
    kp_history = 30
    for tid in ("heldout_1s",):
        tab = tabs.get(tid)
        if tab is None:
            continue
        for action in sorted({w.action for w in tab.wins}):
            hists = [w.history[-kp_history:] for w in tab.wins if w.action == action and len(w.history) >= kp_history]
            if hists:
                rules[action] = {**keypose_counts(hists), "histories": len(hists)}
    return {"eq4": eq4, "keypose_rules": rules, "keypose_history_frames": kp_history}
