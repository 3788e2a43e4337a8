"""Issue 28's targets read from a results document (export/eval/targets.py): each check's value beside its
limit, met or missed by that limit, and a missing value never counted as met."""
from export.eval.report import markdown
from export.eval.targets import tally, targets


def _vals(**cols):
    return {c: {"mean": v, "std": 0.0, "n": 4} for c, v in cols.items()}


def _doc(model_vals: dict, refused: int = 0, status: str = "holds", a: float = 0.5, b: float = 0.7) -> dict:
    oracle = {"id": "oracle", "kind": "oracle", "values": _vals(skate=0.1, hip_range=0.4),
              "by_group": {"jump": {"items": 4, "people": 2, "takes": 2, "values": _vals(hip_range=0.4, mpjpe_cm=0.0)}}}
    zv = {"id": "zero-velocity", "kind": "model", "values": _vals(ade=b),
          "by_group": {"jump": {"items": 4, "people": 2, "takes": 2, "values": _vals(ade=b)}}}
    model = {"id": "wat-rnn", "label": "WAT (RNN)", "kind": "model", "values": _vals(**model_vals), "refused": {"items": refused, "of": 4,
                                                                                        "share": 25.0 * refused},
             "by_group": {"jump": {"items": 4, "people": 2, "takes": 2, "values": _vals(ade=a, hip_range=0.2, mpjpe_cm=9.0)}}}
    table = {"id": "heldout_2s", "horizon_frames": 60, "rows": [oracle, zv, model]}
    verdicts = [{"row": "wat-rnn", "table": "heldout_2s", "baseline": "zero-velocity", "status": status,
                 "a_paired": a, "b_paired": b},
                {"row": "wat-rnn", "table": "heldout_2s", "baseline": "regression-gru", "status": "inconclusive",
                 "a_paired": a, "b_paired": a}]
    return {"fps": 30, "served_learned": ["wat-rnn"], "verdicts": verdicts, "tables": [table]}


def _by(rows, target, group="all"):
    return next(x for x in rows if x["target"].startswith(target) and x["group"] == group)


def test_each_target_is_met_or_missed_by_its_own_limit():
    rows = targets(_doc(dict(speed_ratio_s1=0.9, speed_ratio_s2=0.6, follow=0.7, skate=0.25, outside=40.0,
                              spread_cm=9.0, full=80.0, bone=0.1, foot=3.0, jump=100.0)))
    assert _by(rows, "1. ADE")["value"] == 0.5 / 0.7 and _by(rows, "1. ADE")["met"]
    assert _by(rows, "1. the difference holds")["met"]
    assert not _by(rows, "1. beats the regression GRU")["met"]
    assert _by(rows, "2. joint speed / truth's, second 1")["met"]
    assert not _by(rows, "2. joint speed / truth's, second 2")["met"]
    assert _by(rows, "3.")["met"]
    assert not _by(rows, "4.")["met"] and abs(_by(rows, "4.")["value"] - 2.5) < 1e-12   # 0.25 against 0.1
    assert not _by(rows, "5.", "jump")["met"]                                           # 0.2 against 0.4
    assert not _by(rows, "6. truth outside")["met"] and _by(rows, "6. pose spread")["met"]
    assert _by(rows, "7.")["met"]
    assert not _by(rows, "9. frames with a foot")["met"] and _by(rows, "9. bone")["met"]


def test_a_missing_value_is_not_measured_and_never_met():
    rows = targets(_doc(dict(bone=0.1)))
    follow = _by(rows, "3.")
    assert follow["value"] is None and follow["met"] is None
    assert tally(rows)["wat-rnn"]["not measured"] >= 1


def test_an_inconclusive_difference_misses_even_below_the_ratio():
    rows = targets(_doc(dict(bone=0.1), status="inconclusive"))
    assert _by(rows, "1. ADE")["met"] and not _by(rows, "1. the difference holds")["met"]


def test_the_report_prints_each_check_beside_its_limit():
    doc = _doc(dict(follow=0.3, bone=0.1))
    doc.update({"k": 10, "training_seeds": [0], "sampling_seeds": [0], "bootstrap": {"rounds": 10}, "seconds": 1,
                "models": {}, "skipped": [], "tables": doc["tables"]})
    from export.eval.report import _targets
    text = "\n".join(_targets(doc))
    assert "| 3. speed follows the history (Spearman rho) | 0.300 | >= 0.6 | **missed** |" in text


def test_without_a_verdict_the_ratio_comes_from_the_tables_means_on_every_window():
    doc = _doc(dict(ade=0.6, bone=0.1))
    doc["verdicts"] = []
    rows = targets(doc)
    assert abs(_by(rows, "1. ADE")["value"] - 0.6 / 0.7) < 1e-12
    assert not any(x["target"].startswith("1. the difference holds") for x in rows)
    doc["tables"][0]["rows"][2]["refused"]["items"] = 1     # a refusing row has no whole-table pair
    assert _by(targets(doc), "1. ADE")["value"] is None
