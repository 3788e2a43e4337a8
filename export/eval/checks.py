"""The checks on a finished evaluation: sanity rows and classifier checks (each can fail), the papers' claims,
the copying and memorising baselines against every model, and the disclosed variants."""
from __future__ import annotations

import math

import numpy as np

from ..data.skeleton import SKELETON
from . import metrics as M
from . import stats as S
from .harness import COLUMNS, RECOGNITION
from .rows import CLAIMS, SHAPE_METRICS, SHAPE_PAIRS, SHAPE_TOLERANCE

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
                    sa.seed_std[metric], sb.seed_std[metric_b], direction, COLUMNS[metric].balanced, margin)
    return {**out, **res}


def evaluate_claims(by_table: dict, store: dict, tabs: dict, recognition: list[dict]) -> list[dict]:
    failed = {(c["table"], c["metric"]) for c in recognition if not c["passed"]}
    out = []
    for claim in CLAIMS:
        parts = []
        for p in claim.parts:
            part = compare_rows(by_table, store, tabs, p.table, p.a, p.b, p.metric, p.direction, p.metric_b, p.margin)
            if by_table.get(p.table, {}).get("in_sample"):
                part.update(status=S.IN_SAMPLE, reason="an in-sample table never backs a claim")
            elif p.construction or claim.construction:
                part.update(status=S.BY_CONSTRUCTION, reason=p.construction or claim.construction)
            elif part["status"] != S.MISSING and {p.metric, p.metric_b} & set(RECOGNITION) and \
                    any((p.table, m) in failed for m in {p.metric, p.metric_b} & set(RECOGNITION)):
                part.update(status=S.UNUSABLE, reason="the ground truth does not score best on this classifier in "
                                                      f"table {p.table}, so its recognition numbers cannot rank rows")
            parts.append(part)
        counted = [x["status"] for x in parts if x["status"] != S.BY_CONSTRUCTION]
        status = S.BY_CONSTRUCTION if claim.construction else S.combine(counted)
        out.append({"id": claim.id, "paper": claim.paper, "text": claim.text, "status": status,
                    "reason": claim.construction or next((x.get("reason") for x in parts if x["status"] == status
                                                          and x.get("reason")), ""),
                    "parts": parts})
    return out


def claims_tally(claims: list[dict]) -> dict:
    """How many claims have each status; "by construction" ones are listed and not counted."""
    counted = [c for c in claims if c["status"] != S.BY_CONSTRUCTION]
    out = {s: sum(c["status"] == s for c in counted) for s in S.STATUSES if s != S.BY_CONSTRUCTION}
    out.update(counted=len(counted), by_construction=len(claims) - len(counted))
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
            if r["kind"] != "model" or "ade" not in r.get("values", {}):
                continue
            cycle = f"repeat-cycle-{r.get('history_frames')}"
            for base in ("nearest-window", cycle if cycle in rows else None, "repeat-cycle-60", "zero-velocity"):
                if base is None or base not in rows or base == r["id"]:
                    continue
                c = compare_rows(by_table, store, tabs, tid, r["id"], base, "ade", "less")
                what = {"nearest-window": "memorising", "zero-velocity": "standing still"}.get(base, "copying its history")
                verdict = (f"beats {rows[base]['label'].lower()}" if c["status"] == S.HOLDS else
                           f"does not beat {rows[base]['label'].lower()}: its accuracy is no better than {what}")
                out.append({**c, "row": r["id"], "label": r["label"], "baseline": base,
                            "baseline_label": rows[base]["label"], "verdict": verdict})
    return out


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
                out.append({"table": tid, "with": with_, "without": without, "metric": metric,
                            "with_value": a, "without_value": b, "ratio": ratio,
                            "within": bool(abs(ratio - 1) <= SHAPE_TOLERANCE), "tolerance": SHAPE_TOLERANCE,
                            "difference": c["difference"], "bar": c["bar"]})
    return out


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
