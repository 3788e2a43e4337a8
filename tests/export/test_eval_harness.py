"""A tiny full evaluation (few windows, one training seed, short classifier training) through the
served baselines, plus the rows that must be skipped with a reason, and the report writers."""
import copy
import json
from collections import Counter

import numpy as np
import pytest

from export.eval.harness import evaluate, load_eval_config, requested_actions, table_windows
from export.eval.report import markdown, write_json, write_markdown
from export.eval.rows import Row
from export.manifest import read_manifest
from export.paths import MODELS_DIR


def tiny_config():
    cfg = copy.deepcopy(load_eval_config())
    cfg.update(k=3, training_seeds=[0], sampling_seeds=[0, 1])
    cfg["classifier"].update(steps=15, batch_size=16)
    cfg["fid"]["bootstrap"] = 5
    keep = {"test_1s": 8, "walker_5s": 12, "in_sample": 4}
    cfg["tables"] = [dict(t, stride=t["stride"] * keep[t["id"]]) for t in cfg["tables"] if t["id"] in keep]
    return cfg


@pytest.fixture(scope="module")
def doc(clips, tmp_path_factory):
    rows = [Row("oracle", "Ground truth", kind="oracle"),
            Row("noise", "Noise", kind="noise", tables=("test_1s",)),
            Row("zero-velocity", "Zero-velocity", config="zero_velocity.json"),
            Row("regression-gru", "Regression GRU", config="regression.json"),
            Row("ghost", "Not written", config="no_such_method.json")]
    return evaluate(list(clips.values()), tiny_config(), rows=rows,
                    cache_dir=tmp_path_factory.mktemp("classifiers"), progress=lambda *_: None)


def row(doc, table, rid):
    t = next(t for t in doc["tables"] if t["id"] == table)
    return next((r for r in t["rows"] if r["id"] == rid), None)


def test_windows_stay_inside_the_test_parts(clips):
    cfg = load_eval_config()
    t = next(t for t in cfg["tables"] if t["id"] == "test_1s")
    wins = table_windows(list(clips.values()), t)
    assert {w.clip for w in wins} == {"getup_faceup", "spin", *[c for c in clips if c.startswith("walker")]}
    assert all(w.history.shape == (10, 18, 3) and w.truth.shape == (30, 18, 3) for w in wins)


def test_a_broken_eval_config_names_the_problem(tmp_path):
    cfg = load_eval_config()
    del cfg["tables"][0]["horizon_frames"]
    (tmp_path / "eval.json").write_text(json.dumps(cfg))
    with pytest.raises(ValueError, match=r"table test_1s is missing \['horizon_frames'\]"):
        load_eval_config(tmp_path / "eval.json")
    cfg = load_eval_config()
    cfg["tables"][0]["history_frames"] = "model"
    (tmp_path / "eval.json").write_text(json.dumps(cfg))
    with pytest.raises(ValueError, match="ground truth needs one history length"):
        load_eval_config(tmp_path / "eval.json")
    with pytest.raises(FileNotFoundError, match="evaluation config not found"):
        load_eval_config(tmp_path / "missing.json")


def test_requested_actions_rotate_evenly_over_windows():
    acts = list("abcdefghijklmno")
    table = {"actions": "all", "actions_per_window": 5}
    assert Counter(a for i in range(6) for a in requested_actions(table, acts, i, "a")) == {a: 2 for a in acts}
    assert requested_actions({"actions": "all"}, acts, 0, "a") == acts
    assert requested_actions({}, acts, 3, "walk") == ["walk"]


def test_the_oracle_is_perfect_and_the_noise_row_has_its_analytic_diversity(doc):
    oracle = row(doc, "test_1s", "oracle")["values"]
    for col in ("ade", "ade_w", "mpjpe_1s_ave", "mpjpe_1s_best", "div"):
        assert oracle[col]["mean"] == pytest.approx(0.0, abs=1e-9), col
    check = next(s for s in doc["sanity"] if s["id"] == "noise-diversity")
    assert check["passed"] and check["measured"] == pytest.approx(check["expected"], rel=0.05)
    assert row(doc, "test_1s", "noise")["runs"] == 2     # two sampling seeds


def test_baselines_predict_through_the_served_models(doc):
    manifest = read_manifest(MODELS_DIR / "manifest.json")
    assert doc["models"] == {m["id"]: m["hash"] for m in manifest["models"] if m["id"] in doc["models"]}
    zv = row(doc, "test_1s", "zero-velocity")
    assert zv["values"]["speed"]["mean"] == 0.0 and zv["values"]["div"]["mean"] == 0.0
    assert zv["values"]["ade"]["mean"] > 0.1
    reg = row(doc, "test_1s", "regression-gru")
    assert reg["k"] == 1 and reg["values"]["speed"]["mean"] > 0.0
    assert 0.0 <= reg["values"]["acc_pose"]["mean"] <= 100.0
    walker = row(doc, "walker_5s", "zero-velocity")
    assert walker.get("skipped") or walker["values"]["mpjpe_h_best"]["mean"] > 0


def test_rows_that_cannot_run_are_skipped_with_the_reason(doc):
    skipped = {s["row"]: s["reason"] for s in doc["skipped"]}
    assert skipped["ghost"] == "configs/no_such_method.json does not exist yet"
    claims = {c["id"]: c for c in doc["claims"]}
    assert claims["wat-ade"]["status"] == "not evaluated"
    assert "wat-rnn" in claims["wat-ade"]["parts"][0]["missing"]
    assert all(c["status"] in ("holds", "fails", "inconclusive", "not evaluated") for c in claims.values())


def test_tables_state_their_horizon_history_and_k(doc):
    for t in doc["tables"]:
        assert t["horizon_frames"] > 0 and t["k"] == 3
        assert (t["history_frames"] > 0 and t["windows"] > 0) if t["truth"] else t["history_frames"] is None
        for r in t["rows"]:
            if not r.get("skipped"):
                assert sum(sum(c) for c in r["lengths"].values()) > 0
                assert t["truth"] or any(n.startswith("history 10 frames") for n in r["notes"])
    in_sample = next(t for t in doc["tables"] if t["id"] == "in_sample")
    assert "ade" not in in_sample["columns"] and "fid_te" not in in_sample["columns"]


def test_reports_round_trip(doc, tmp_path):
    write_json(doc, tmp_path / "results.json")
    back = json.loads((tmp_path / "results.json").read_text())
    assert back["tables"][0]["rows"][0]["values"]["ade"]["mean"] == pytest.approx(0.0, abs=1e-9)
    write_markdown(doc, tmp_path / "RESULTS.md")
    text = (tmp_path / "RESULTS.md").read_text()
    assert text == markdown(back)
    for t in doc["tables"]:
        assert t["title"] in text
    assert "## Paper claims" in text and "one take per action" in text.lower()
    assert not np.isnan(back["seconds"])


def test_classifiers_have_a_no_motion_class_that_catches_a_held_pose(clips):
    from export.eval.classifiers import NO_MOTION, split_snippets, train_classifier
    cfg = dict(load_eval_config()["classifier"], steps=150, batch_size=32)
    clf = train_classifier("moac", list(clips.values()), cfg, seed=0)
    assert clf.classes == [*clf.actions, NO_MOTION]
    x, _, _ = split_snippets(list(clips.values()), "test", clf.frames, 10)
    held = x[:, :1].repeat(clf.frames, axis=1)           # test poses, never seen held still in training
    scores, _ = clf.snippet_outputs(held)
    assert (scores.argmax(1) == len(clf.actions)).mean() > 0.9
