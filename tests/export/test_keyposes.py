"""Keyposes: training data, a tiny train + export with parity, and the committed model's predictor
(K futures, no jump, marks and ghosts, bad input)."""
import json
import shutil

import numpy as np
import pytest

from export.config import load_config, override
from export.data.clip_json import read_clip
from export.manifest import manifest_document, read_manifest, write_manifest
from export.methods import method_for
from export.methods.keyposes import cluster_keyposes, centre_distances
from export.onnx.export import check_parity, to_onnx
from export.ops.proximity import label_distribution
from export.paths import CLIPS_DIR, MODELS_DIR
from export.pipeline import export, train
from export.sample.keyposes import KeyposesPredictor
from export.sample.predictor import load_predictor
from export.sample.request import PredictError, Request
from export.vectors_keyposes import first_accepted_start

CFG = load_config("keyposes.json")
MANIFEST = read_manifest(MODELS_DIR / "manifest.json")
ENTRY = next((m for m in MANIFEST["models"] if m["method"] == "keyposes"), None)
committed = pytest.mark.skipif(ENTRY is None, reason="no Keyposes model in public/models")

TINY = {"keyposes.clusters": 12, "model.hidden": 8, "model.refine.hidden": 8, "model.refine.bases": 6,
        "future_frames": 40, "train.steps": 4, "train.batch_size": 16, "train.stride": 4}


def _history(clip: str, start: int, frames: int) -> np.ndarray:
    return read_clip(CLIPS_DIR / f"{clip}.json").positions[start:start + frames]


# Held-out histories from the served clips: the site's default walk and a held-out dance.
INDEX = json.loads((CLIPS_DIR / "index.json").read_text())
WALK = INDEX["default"]["clip"]
DANCE = next(c["name"] for c in INDEX["clips"] if c["role"] == "test" and c["action"] == "dance" and c.get("subject") == 61)
# Keyposes needs 3 keyposes in its 30-frame history (the held-out walk starts slowly), so histories
# start at the first frame from here that the served model accepts.
START = 15


@pytest.fixture(scope="module")
def clips(deepmimic):
    """Tiny models train on the DeepMimic clips (small, named)."""
    return deepmimic


def test_training_windows_come_from_train_ranges_only(clips):
    method = method_for(CFG)
    ws = method._windows(list(clips.values()))
    assert ws
    for w in ws:
        ranges = clips[w.clip].split.train
        assert all(any(a <= f < b for a, b in ranges) for f in w.frames), w.clip
        assert len(w.positions) >= CFG["history_frames"] + CFG["keyposes"]["min_future_frames"]


def test_tiny_model_trains_exports_and_predicts(clips, tmp_path):
    cfg = override(CFG, **TINY)
    subset = [clips[n] for n in ("walk", "run", "kick", "jump")]
    method, model = train(cfg, subset, progress=False)
    data = method.notes
    assert data["windows"] > 0 and sum(data["observed_histogram"]) >= data["windows"]
    assert 0.59 < data["mean_top_probability"] < 0.61          # the temperature hits its target
    for role, graph in method.graphs(model).items():
        assert check_parity(graph, to_onnx(graph)) < 1e-4, role
    entry = export(method, model, cfg, tmp_path, ["walk"], "sha256:" + "0" * 64, "keyposes.json")
    assert set(entry["graphs"]) == {"step", "refine"} and entry["files"] == {"centres": "keyposes.centres.json"}
    doc = json.loads((tmp_path / "keyposes.centres.json").read_text())
    assert np.asarray(doc["centres"]).shape == (12, 18, 3)
    manifest = manifest_document([entry], ["walk"], "sha256:" + "0" * 64)
    write_manifest(manifest, tmp_path / "manifest.json")
    pred = KeyposesPredictor(entry, manifest, tmp_path).predict(
        _history(WALK, START, 30), Request(k=3, seed=1, horizon_frames=40))
    assert pred.futures.shape == (3, 40, 18, 3) and np.all(np.isfinite(pred.futures))


@committed
def test_committed_centres_and_temperature_meet_their_targets(default_clips):
    k = ENTRY["params"]["keyposes"]
    centres = np.asarray(json.loads((MODELS_DIR / ENTRY["files"]["centres"]).read_text())["centres"])
    values = cluster_keyposes(list(default_clips.values()), k["threshold"], True)
    d = centre_distances(values, centres)
    # The size cap keeps K at 192 for the training keyposes of many people, so centres are coarser than
    # the 0.2 m extraction: measured 0.39 m on average (1.9 thresholds; the 128 centres at 0.3 m read
    # 0.41 m). Guard: no coarser than those 128 were (issue 28 asks for finer; not met).
    assert d["l2"] <= 0.41
    top = label_distribution(values, centres, ENTRY["params"]["label_temperature"]).max(-1).mean()
    assert 0.3 <= top <= 0.9


@committed
def test_k_futures_differ_join_the_history_and_mark_their_keyposes():
    n = ENTRY["params"]["history_frames"]
    p = load_predictor(ENTRY["id"])
    history = _history(DANCE, first_accepted_start(p, read_clip(CLIPS_DIR / f"{DANCE}.json").positions, n, 81), n)
    pred = p.predict(history, Request(k=10, seed=3))
    assert pred.futures.shape == (10, 150, 18, 3) and pred.lengths.tolist() == [150] * 10
    assert len({tuple(s["labels"]) for s in pred.samples}) > 1
    step = np.linalg.norm(pred.futures[:, 0] - history[-1], axis=-1).max()
    assert step < 0.15                                            # no jump at the present
    for s, frames, poses in zip(pred.samples, pred.ghosts["frames"], pred.ghosts["poses"]):
        assert s["marks"] == frames and len(s["labels"]) == len(s["marks"]) == len(poses)
        assert all(0 <= m < 150 for m in s["marks"]) and s["marks"] == sorted(s["marks"])
    assert pred.margins and min(pred.margins) > 0
    again = load_predictor(ENTRY["id"]).predict(history, Request(k=10, seed=3))
    np.testing.assert_array_equal(again.futures, pred.futures)


@committed
def test_refinement_keeps_the_start_and_changes_the_motion():
    n = ENTRY["params"]["history_frames"]
    p = load_predictor(ENTRY["id"])
    history = _history(WALK, first_accepted_start(p, read_clip(CLIPS_DIR / f"{WALK}.json").positions, n, START), n)
    raw = p.predict(history, Request(k=4, seed=5, controls={"refine": False}))
    ref = p.predict(history, Request(k=4, seed=5, controls={"refine": True}))
    assert [s["labels"] for s in raw.samples] == [s["labels"] for s in ref.samples]
    # the correction ramps in from the present (kp_refine.py), so the refined future still has no jump
    assert np.linalg.norm(ref.futures[:, 0] - history[-1], axis=-1).max() < 0.15
    assert np.linalg.norm(ref.futures[:, 0] - raw.futures[:, 0], axis=-1).max() < 0.05
    assert np.abs(ref.futures - raw.futures).max() > 1e-3


@committed
@pytest.mark.parametrize("controls, message", [
    ({"temperature": 0}, "Temperature must be between 0.05 and 1.5, got 0"),
    ({"temperature": -0.5}, "Temperature must be between"),
    ({"refine": 1}, "Refine must be true or false"),
])
def test_bad_controls_get_clear_messages(controls, message):
    with pytest.raises(PredictError, match=message):
        load_predictor(ENTRY["id"]).predict(_history(WALK, START, 30), Request(k=2, controls=controls))


@committed
def test_a_held_pose_is_predicted_and_a_stricter_model_refuses_it_by_name():
    """The served model needs 2 observed keyposes (a held pose gives its two ends); one needing 3 refuses
    the same history with the count and the threshold."""
    still = np.repeat(_history(WALK, START, 1), ENTRY["params"]["history_frames"], axis=0)
    pred = load_predictor(ENTRY["id"]).predict(still, Request(k=2, horizon_frames=30))
    assert np.all(np.isfinite(pred.futures))
    assert np.linalg.norm(pred.futures[:, 0] - still[-1], axis=-1).mean() < 0.1   # starts from the held pose
    k = ENTRY["params"]["keyposes"]
    strict = {**ENTRY, "params": {**ENTRY["params"], "keyposes": {**k, "min_observed": 3}}}
    with pytest.raises(PredictError, match=f"the history yields (1 keypose|2 keyposes) at the {k['threshold']} m threshold; "
                                           "Keyposes needs at least 3"):
        KeyposesPredictor(strict, MANIFEST, MODELS_DIR).predict(still, Request(k=2))


@committed
def test_a_missing_centres_file_is_named(tmp_path):
    shutil.copy(MODELS_DIR / "manifest.json", tmp_path / "manifest.json")
    for g in ENTRY["graphs"].values():
        shutil.copy(MODELS_DIR / g["file"], tmp_path / g["file"])
    p = load_predictor(ENTRY["id"], tmp_path)
    with pytest.raises(FileNotFoundError, match="keyposes.centres.json: keypose centres file missing"):
        p.predict(_history(WALK, START, 30), Request(k=2))


@pytest.mark.parametrize("split_holds", [False, True])
def test_a_held_pose_in_a_training_future_is_a_run_of_its_label_only_with_split_holds(clips, split_holds):
    """30 frames of a walk, then the last pose held for 4 s: pruned (sec. 3.2), the hold is one 'very long'
    step, played as 30 frames; split, it is a run of the held pose's own label, each step at most 30."""
    from export.data.windows import Window
    from export.ops import keyposes as kp
    from export.ops.facing import root_relative
    from export.ops.proximity import face_forward
    cfg = override(CFG, **{**TINY, "future_frames": 150, "keyposes.clusters": 3, "keyposes.split_holds": split_holds})
    method = method_for(cfg)
    walk = clips["walk"].positions[:31]
    motion = np.concatenate([walk, np.repeat(walk[-1:], 150, axis=0)])
    method.centres = face_forward(root_relative(walk[[0, 15, 30]]))
    row = method._sequence(Window("walk", "walk", motion, np.arange(len(motion))))
    m = int(row["fut_mask"].sum())
    durations = [kp.DURATION_LENGTHS[c] for c in row["fut_duration"][:m]]
    labels = row["fut_label"][:m].tolist()
    if split_holds:
        assert m >= 4 and labels.count(labels[-1]) >= 4, labels       # the hold: its label again and again
        assert max(row["fut_duration"][:m]) == len(kp.DURATION_LENGTHS) - 1 and sum(durations) >= 120
    else:
        assert m <= 1 and sum(durations) <= 30, (labels, durations)    # left after one step of 30 frames
