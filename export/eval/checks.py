"""The checks on a finished evaluation: the sanity rows (each can fail) and the papers' claims."""
from __future__ import annotations

import math

from ..data.skeleton import SKELETON
from . import metrics as M
from .harness import COLUMNS
from .rows import CLAIMS
from .stats import combine, compare


def sanity_checks(tables: list[dict], clf_report: dict, cfg: dict) -> list[dict]:
    """The checks that can fail: each {"id", "text", "expected", "measured", "passed"}."""
    out = []
    sigma = float(cfg["noise_sigma"])
    expected = M.noise_diversity(sigma, SKELETON.num_joints * 3)
    for table in tables:
        noise = next((r for r in table["rows"] if r["id"] == "noise" and "div" in r["values"]), None)
        if noise:
            got = noise["values"]["div"]["mean"]
            out.append({"id": "noise-diversity", "table": table["id"],
                        "text": f"Ground truth + N(0, {sigma} m²) has the analytic diversity "
                                f"2σ·Γ((D+1)/2)/Γ(D/2) with D = {SKELETON.num_joints * 3} (Eq. 10), within 5%",
                        "expected": expected, "measured": got, "passed": abs(got / expected - 1) < 0.05})
    shuffled = clf_report.get("pose_gru_shuffled")
    if shuffled:
        chance = shuffled["chance"]
        # Test snippets of one clip are strongly correlated, so the effective sample size is the
        # number of test clips (7), not of snippets: a 99% binomial band at n = 7 around chance.
        n = 7
        band = 100 * 2.576 * math.sqrt((chance / 100) * (1 - chance / 100) / n)
        got = shuffled["test_balanced_accuracy"]
        out.append({"id": "shuffled-labels", "table": None,
                    "text": f"The pose GRU trained on shuffled labels scores at chance ({chance:.1f}% ± {band:.1f}) on the test split",
                    "expected": chance, "measured": got, "passed": abs(got - chance) <= band})
    for table in tables:
        oracle = next((r for r in table["rows"] if r["id"] == "oracle"), None)
        if not oracle:
            continue
        for col in ("acc_pose", "acc_moac"):
            if col not in oracle["values"]:
                continue
            others = [(r["label"], r["values"][col]["mean"]) for r in table["rows"]
                      if r["kind"] == "model" and col in r.get("values", {})]
            best_other = max(others, key=lambda x: x[1]) if others else ("none", -math.inf)
            got = oracle["values"][col]["mean"]
            out.append({"id": f"oracle-best-{col}", "table": table["id"],
                        "text": f"The ground truth scores best on recognition ({COLUMNS[col][0]}); best other: {best_other[0]}",
                        "expected": best_other[1] if others else None, "measured": got,
                        "passed": got >= best_other[1]})
    return out


def evaluate_claims(tables: list[dict]) -> list[dict]:
    by_table = {t["id"]: {r["id"]: r for r in t["rows"]} for t in tables}
    out = []
    for claim in CLAIMS:
        parts = []
        for p in claim.parts:
            rows = by_table.get(p.table, {})
            a = rows.get(p.a, {}).get("values", {}).get(p.metric)
            b = rows.get(p.b, {}).get("values", {}).get(p.metric_b or p.metric)
            status, diff, bar = compare(a, b, p.direction)
            missing = [x for x, v in ((p.a, a), (p.b, b)) if v is None]
            parts.append({"table": p.table, "a": p.a, "b": p.b, "metric": p.metric, "metric_b": p.metric_b or p.metric,
                          "direction": p.direction, "status": status,
                          "a_value": a, "b_value": b, "difference": None if math.isnan(diff) else diff,
                          "bar": None if math.isnan(bar) else bar, "missing": missing})
        out.append({"id": claim.id, "paper": claim.paper, "text": claim.text,
                    "status": combine([p["status"] for p in parts]), "parts": parts})
    return out
