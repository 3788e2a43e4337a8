"""A tiny full evaluation on held-out people (few windows, one training seed, short classifier training)
through tiny models trained here, plus the rows that must be skipped with a reason, and the report writers."""
import copy
import json
from collections import Counter

import numpy as np
import pytest

from export.config import load_config, override
from export.data.split import TEST_PEOPLE
from export.eval import stats as S
from export.eval.card import card_problems, model_card, summary
from export.eval.harness import evaluate, load_eval_config, requested_actions, table_windows
from export.eval.report import _round, markdown, write_json, write_markdown
from export.eval.rows import CLAIMS, ROWS, Row
from export.manifest import manifest_document, write_manifest


def tiny_config():
    cfg = copy.deepcopy(load_eval_config())
    cfg.update(k=3, training_seeds=[0], sampling_seeds=[0, 1])
    cfg["bootstrap"]["rounds"] = 200
    cfg["classifier"].update(steps=15, batch_size=16, stride=10)
    cfg["classifier"]["selection"].update(steps=3, stride=30)
    cfg["fid"]["bootstrap"] = 5
    cfg["nearest"]["stride"] = 4
    keep = {"heldout_1s": 8, "heldout_2s": 8, "in_sample": 4}
    cfg["tables"] = [dict(t, stride=t["stride"] * keep[t["id"]]) for t in cfg["tables"] if t["id"] in keep]
    return cfg


@pytest.fixture(scope="module")
def models(clips, tmp_path_factory):
    """Zero-velocity, the regression GRU and LCP-VAE, trained for a few steps on the default data."""
    from export.pipeline import export, train
    out = tmp_path_factory.mktemp("models")
    actions = sorted({c.action for c in clips.values()})
    entries = []
    for name in ("zero_velocity.json", "regression.json", "lcp_vae.json"):
        cfg = override(load_config(name), **{"train.steps": 2, "train.batch_size": 8, "train.stride": 16})
        method, model = train(cfg, list(clips.values()), progress=False)
        entries.append(export(method, model, cfg, out, actions, "sha256:" + "0" * 64, name))
    write_manifest(manifest_document(entries, actions, "sha256:" + "0" * 64), out / "manifest.json")
    return out


@pytest.fixture(scope="module")
def doc(clips, models, tmp_path_factory):
    keep = {"oracle", "noise", "zero-velocity", "constant-velocity", "repeat-cycle-10", "repeat-cycle-60",
            "nearest-window", "regression-gru", "lcp-vae", "lcp-vae-projected", "wat-rnn"}
    rows = [r for r in ROWS if r.id in keep] + [Row("ghost", "Not written", config="no_such_method.json")]
    return evaluate(list(clips.values()), tiny_config(), rows=rows, models_dir=models,
                    seeds_root=tmp_path_factory.mktemp("seeds"), cache_dir=tmp_path_factory.mktemp("classifiers"),
                    progress=lambda *_: None)


def table(doc, tid):
    return next(t for t in doc["tables"] if t["id"] == tid)


def row(doc, tid, rid):
    return next((r for r in table(doc, tid)["rows"] if r["id"] == rid), None)


def test_windows_are_world_frame_slices_of_the_held_out_takes(clips):
    cfg = load_eval_config()
    t = next(t for t in cfg["tables"] if t["id"] == "heldout_2s")
    wins = table_windows(list(clips.values()), t)
    assert wins and {clips[w.clip].split.role for w in wins} == {"test"}
    assert {str(w.subject) for w in wins} <= {str(p) for p in TEST_PEOPLE}
    for w in wins[::7]:
        c = clips[w.clip].positions
        n = len(w.history)
        assert 30 <= n <= 60 and w.truth.shape == (60, 18, 3)
        assert np.array_equal(w.history, c[w.present - n + 1:w.present + 1])       # world positions, not canonical
        assert np.array_equal(w.truth, c[w.present + 1:w.present + 61])


def test_a_broken_eval_config_names_the_problem(tmp_path):
    cfg = load_eval_config()
    del cfg["tables"][0]["horizon_frames"]
    (tmp_path / "eval.json").write_text(json.dumps(cfg))
    with pytest.raises(ValueError, match=r"table heldout_1s is missing \['horizon_frames'\]"):
        load_eval_config(tmp_path / "eval.json")
    cfg = load_eval_config()
    cfg["tables"][0]["source"] = "walker"
    (tmp_path / "eval.json").write_text(json.dumps(cfg))
    with pytest.raises(ValueError, match="source must be test"):
        load_eval_config(tmp_path / "eval.json")
    with pytest.raises(FileNotFoundError, match="evaluation config not found"):
        load_eval_config(tmp_path / "missing.json")


def test_requested_actions_rotate_evenly_over_windows():
    acts = list("abcdefghijklmno")
    t = {"actions": "heldout", "actions_per_window": 5}
    assert Counter(a for i in range(6) for a in requested_actions(t, acts, i, "a")) == {a: 2 for a in acts}
    assert requested_actions({"actions": "heldout"}, acts, 0, "a") == acts
    assert requested_actions({}, acts, 3, "walk") == ["walk"]


def test_no_claim_rests_on_an_in_sample_table():
    cfg = load_eval_config()
    in_sample = {t["id"] for t in cfg["tables"] if t["source"] == "train"}
    assert in_sample and not {p.table for c in CLAIMS for p in c.parts} & in_sample
    assert {p.table for c in CLAIMS for p in c.parts} <= {t["id"] for t in cfg["tables"]}


def test_the_oracle_is_perfect_and_the_noise_row_has_its_analytic_diversity(doc):
    oracle = row(doc, "heldout_1s", "oracle")["values"]
    for col in ("ade", "fde", "ade_full", "fde_full", "mpjpe_h_best", "apd"):
        assert oracle[col]["mean"] == pytest.approx(0.0, abs=1e-9), col
    check = next(s for s in doc["sanity"] if s["id"] == "noise-diversity")
    assert check["passed"] and check["measured"] == pytest.approx(check["expected"], rel=0.05)
    assert row(doc, "heldout_1s", "noise")["runs"] == 2     # two sampling seeds


def test_deterministic_rows_get_a_bar_from_the_take_bootstrap(doc):
    zv = row(doc, "heldout_2s", "zero-velocity")
    assert zv["runs"] == 1 and zv["values"]["apd"]["mean"] == 0.0 and zv["values"]["speed"]["mean"] < 1e-6
    assert zv["values"]["ade"]["mean"] > 0.1 and zv["values"]["ade"]["boot_std"] > 0 and zv["values"]["ade"]["std"] > 0
    assert zv["values"]["jump"]["mean"] == 100.0
    cv = row(doc, "heldout_2s", "constant-velocity")
    assert cv["values"]["ade_full"]["mean"] > 0 and cv["k"] == 1
    assert row(doc, "heldout_2s", "repeat-cycle-10")["values"]["ade"]["mean"] == pytest.approx(
        zv["values"]["ade"]["mean"], abs=1e-6)                              # 10 frames hold no cycle: the last pose
    assert any("fewer than 60 frames" in n for n in row(doc, "heldout_2s", "repeat-cycle-60")["notes"])
    assert row(doc, "heldout_2s", "nearest-window")["values"]["ade"]["mean"] > 0


def test_stochastic_rows_predict_k_futures_and_the_projection_is_an_extra_row(doc):
    lcp = row(doc, "heldout_2s", "lcp-vae")
    assert lcp["k"] == 3 and lcp["runs"] == 2 and lcp["values"]["apd"]["mean"] > 0
    proj = row(doc, "heldout_2s", "lcp-vae-projected")
    assert proj["kind"] == "projected" and proj["parent"] == "lcp-vae" and proj["runs"] == 2
    assert proj["values"]["bone"]["mean"] <= lcp["values"]["bone"]["mean"] + 0.5
    rows = [r["id"] for r in table(doc, "heldout_2s")["rows"]]
    assert rows.index("lcp-vae") < rows.index("lcp-vae-projected")           # raw outputs first
    assert row(doc, "heldout_1s", "lcp-vae-projected") is None


def test_rows_that_cannot_run_are_skipped_with_the_reason(doc):
    skipped = {s["row"]: s["reason"] for s in doc["skipped"]}
    assert skipped["ghost"] == "configs/no_such_method.json does not exist yet"
    assert "training seeds [0] not found" in skipped["wat-rnn"]
    claims = {c["id"]: c for c in doc["claims"]}
    assert claims["wat-ade"]["status"] == "not evaluated"
    assert "wat-rnn" in claims["wat-ade"]["parts"][0]["missing"]


def test_claim_statuses_can_fail_and_construction_is_not_counted(doc):
    assert all(c["status"] in S.STATUSES for c in doc["claims"])
    claims = {c["id"]: c for c in doc["claims"]}
    assert claims["moac-static"]["status"] == S.BY_CONSTRUCTION and claims["moac-static"]["reason"]
    assert doc["tally"]["by_construction"] == sum(c["status"] == S.BY_CONSTRUCTION for c in doc["claims"])
    assert doc["tally"]["counted"] + doc["tally"]["by_construction"] == len(doc["claims"])
    for c in doc["claims"]:
        for p in c["parts"]:
            if p["status"] == S.HOLDS:
                assert p["bar"] > 0 and p["people"] >= S.MIN_PEOPLE and p["takes"] >= S.MIN_TAKES
                assert p["p_holm"] <= S.ALPHA and abs(p["difference"]) >= p["minimum"]
    counted = [p for c in doc["claims"] for p in c["parts"] if "p_holm" in p]
    assert doc["comparisons"]["claims"] == len(counted) and "Holm" in doc["comparisons"]["correction"]
    assert doc["comparisons"]["copying"] == sum("p_holm" in c for c in doc["copying"])
    assert (doc["min_people"], doc["min_takes"]) == (S.MIN_PEOPLE, S.MIN_TAKES)
    failed = {(s["table"], s["metric"]) for s in doc["sanity"] if s["id"].startswith("oracle-best") and not s["passed"]}
    for c in doc["claims"]:
        for p in c["parts"]:
            if (p["table"], p["metric"]) in failed and p["status"] not in (S.MISSING, S.BY_CONSTRUCTION):
                assert p["status"] == S.UNUSABLE


def test_copying_and_memorising_baselines_meet_every_model(doc):
    got = {(c["table"], c["row"], c["baseline"]) for c in doc["copying"]}
    for tid in ("heldout_1s", "heldout_2s"):
        for rid in ("zero-velocity", "regression-gru", "lcp-vae"):
            assert (tid, rid, "nearest-window") in got and (tid, rid, "repeat-cycle-60") in got
    assert ("heldout_2s", "regression-gru", "repeat-cycle-10") in got       # its own history length
    for c in doc["copying"]:
        assert c["verdict"].startswith("beats") == (c["status"] == S.HOLDS)
        assert ("no different from" in c["verdict"]) == (c["status"] == S.NO_DIFFERENCE)
    # 10 frames hold no cycle: repeat-cycle-10 holds the last pose, as zero-velocity does
    same = next(c for c in doc["copying"] if c["row"] == "zero-velocity" and c["baseline"] == "repeat-cycle-10")
    enough = same["people"] >= S.MIN_PEOPLE and same["takes"] >= S.MIN_TAKES
    assert same["status"] == (S.NO_DIFFERENCE if enough else S.INSUFFICIENT) or same["status"] == S.NO_DIFFERENCE
    assert not any(c["table"] == "in_sample" for c in doc["copying"])


def test_tables_state_their_windows_people_and_exceptions(doc):
    for t in doc["tables"]:
        assert t["horizon_frames"] > 0 and t["k"] == 3 and t["windows"] > 0 and t["history_frames"] == 30
        assert t["in_sample"] == (t["id"] == "in_sample")
    assert table(doc, "heldout_2s")["people"] and table(doc, "heldout_2s")["takes"] >= 5
    assert {"action": "run", "horizon_frames": 60} in table(doc, "heldout_2s")["exceptions"]
    mm = table(doc, "heldout_1s")["mmade"]
    assert mm["half"]["threshold"] == pytest.approx(mm["threshold"] / 2) and mm["median_set"] >= 5
    sanity = {(s["id"], s["table"]) for s in doc["sanity"]}
    assert ("oracle-best-acc_pose", "heldout_1s") in sanity and ("shuffled-labels", None) in sanity


def test_classifiers_are_chosen_inside_the_training_people(doc, clips):
    held = {str(c.subject) for c in clips.values() if c.split.role == "test"}
    for kind in ("pose_gru", "moac"):
        sel = doc["classifiers"][kind]["selection"]
        assert sel["chosen"] in [c["name"] for c in sel["candidates"]]
        assert sel["people"] and not set(sel["people"]) & held
        assert set(doc["classifiers"][kind]["test_groups"]) == {c.action for c in clips.values() if c.split.role == "test"}


def test_reports_and_the_card_round_trip(doc, tmp_path):
    write_json(doc, tmp_path / "results.json")
    back = json.loads((tmp_path / "results.json").read_text())
    write_markdown(doc, tmp_path / "RESULTS.md")
    text = (tmp_path / "RESULTS.md").read_text()
    assert text == markdown(back)
    for t in doc["tables"]:
        assert t["title"] in text
    assert "## Paper claims on held-out people" in text and "## Copying and memorising" in text
    assert back["summary"] == summary(back) and 3 <= len(back["summary"]) <= 5
    card = model_card(back)
    assert model_card(_round(doc)) == card
    assert card_problems(card, back) == []


def test_classifiers_have_a_no_motion_class_that_catches_a_held_pose(deepmimic):
    """On the small DeepMimic clips (their own split), a short training already learns the class; on the real
    data the evaluation reports what a held pose is called (results.json, classifiers.*.motionless_class)."""
    from export.eval.classifiers import NO_MOTION, split_snippets, train_classifier
    cfg = dict(load_eval_config()["classifier"], steps=150, batch_size=32)
    cfg.pop("selection")
    clips = deepmimic
    clf = train_classifier("moac", list(clips.values()), cfg, seed=0)
    assert clf.classes == [*clf.actions, NO_MOTION]
    x, _, _ = split_snippets(list(clips.values()), "test", clf.frames, 10)
    held = x[:, :1].repeat(clf.frames, axis=1)           # test poses, never seen held still in training
    scores, _ = clf.snippet_outputs(held)
    assert (scores.argmax(1) == len(clf.actions)).mean() > 0.9


def test_per_window_mmade_averages_to_dlows_mmade(clips):
    """The harness keeps MMADE per window (for the take bootstrap); their mean is metrics.mmade_mmfde."""
    from export.data.skeleton import SKELETON
    from export.eval import metrics as M
    from export.eval.harness import Sample, Table, mm_metrics, to_window_frame
    from export.ops.facing import canonicalise
    t = dict(next(x for x in load_eval_config()["tables"] if x["id"] == "heldout_1s"), stride=90)
    wins = table_windows(list(clips.values()), t)[:12]
    placements = [canonicalise(w.history[-30:], 29, SKELETON)[1] for w in wins]
    truths = np.stack([to_window_frame(w.truth, p) for w, p in zip(wins, placements)])
    last = np.stack([to_window_frame(w.history[-1:], p) for w, p in zip(wins, placements)])
    thr = M.choose_threshold(last, 3)
    sets = {"chosen": M.similar_sets(last, thr), "half": M.similar_sets(last, thr / 2),
            "double": M.similar_sets(last, thr * 2)}
    items = [(i, w.action) for i, w in enumerate(wins)]
    u = S.units([w.clip for w in wins], [w.action for w in wins], [w.subject for w in wins])
    tab = Table(t, wins, items, u, S.bootstrap_weights(int(u.take.max()) + 1, 10), placements,
                M.root_relative(truths).reshape(len(wins), 30, -1), sets, thr)
    rng = np.random.default_rng(0)
    futures = [w.truth[None] + rng.normal(0, 0.05, (3, *w.truth.shape)) for w in wins]
    per = [mm_metrics(Sample(f, np.full(3, 30)), i, tab) for i, f in enumerate(futures)]
    in_frame = [to_window_frame(f, p) for f, p in zip(futures, placements)]
    for name, suffix in (("chosen", ""), ("half", "_half"), ("double", "_double")):
        mmade, mmfde = M.mmade_mmfde(in_frame, truths, sets[name])
        assert np.mean([p[f"mmade{suffix}"] for p in per]) == pytest.approx(mmade)
        assert np.mean([p[f"mmfde{suffix}"] for p in per]) == pytest.approx(mmfde)
