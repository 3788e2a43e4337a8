"""One speed envelope for every model (issue 30): the speed quantities are measured on the same last
frames by every model, tempo sees a history played at another speed, and the manifest gives every
model the same speed ranges and tempo reference (export/ops/envelope.py, export/manifest.py)."""
import json

import numpy as np
import pytest

from export.data.clip_json import read_clip
from export.data.windows import windows
from export.manifest import manifest_document, read_manifest, write_manifest
from export.ops.envelope import SHARED, SPEED_FRAMES, envelope, measure, tempo
from export.ops.facing import canonicalise
from export.data.skeleton import SKELETON
from export.paths import CLIPS_DIR, MODELS_DIR

INDEX = json.loads((CLIPS_DIR / "index.json").read_text())
CLIPS = [read_clip(CLIPS_DIR / f"{c['name']}.json") for c in INDEX["clips"]]
WALKS = [c.positions for c, e in zip(CLIPS, INDEX["clips"]) if e["role"] == "test" and e["action"] == "walk"]


def retime(p: np.ndarray, factor: float) -> np.ndarray:
    """A motion played `factor` times as fast (Catmull-Rom between frames)."""
    out = []
    for t in np.arange(0, len(p) - 1, factor):
        i, u = int(t), t - int(t)
        p0, p1, p2, p3 = p[max(i - 1, 0)], p[i], p[min(i + 1, len(p) - 1)], p[min(i + 2, len(p) - 1)]
        out.append(0.5 * (2 * p1 + (p2 - p0) * u + (2 * p0 - 5 * p1 + 4 * p2 - p3) * u * u + (3 * p1 - p0 - 3 * p2 + p3) * u ** 3))
    return np.asarray(out)


@pytest.fixture(scope="module")
def envs():
    """Envelopes of the served clips' training windows for a 10- and a 30-frame history."""
    return {n: envelope([w.positions[:n] for w in windows(CLIPS, "train", n + 1, n)], 30.0) for n in (10, 30)}


def canon(m):
    return canonicalise(m, len(m) - 1, SKELETON)[0]


def test_speed_is_measured_on_the_same_last_frames_whatever_the_history_length():
    walk = WALKS[0][:40]
    short, long = measure(canon(walk[-SPEED_FRAMES:]), 30.0), measure(canon(walk), 30.0)
    for q in ("root_speed", "joint_speed"):
        assert short[q] == pytest.approx(long[q], rel=1e-9), q


def test_tempo_follows_the_playing_speed(envs):
    ref = envs[10]["tempo_poses"]

    def median_tempo(factor):
        ts = [tempo(canon(m[a:a + SPEED_FRAMES]), 30.0, ref) for w in WALKS for m in [retime(w, factor) if factor != 1 else w]
              for a in range(0, len(m) - SPEED_FRAMES, 5)]
        ts = [t for t in ts if t is not None]
        assert len(ts) >= 10, factor
        return float(np.median(ts))

    base = median_tempo(1)
    for f in (0.5, 2.0):
        assert median_tempo(f) / base == pytest.approx(f, rel=0.25), f


def test_a_history_that_does_not_travel_has_no_tempo(envs):
    frozen = np.repeat(WALKS[0][:1], 20, axis=0)
    assert tempo(canon(frozen), 30.0, envs[10]["tempo_poses"]) is None


def test_every_model_in_the_manifest_gets_the_same_speed_envelope(envs, tmp_path):
    manifest = read_manifest(MODELS_DIR / "manifest.json")
    entries = [dict(e, params=dict(e["params"], envelope=envs[10 if e["params"]["history_frames"] < 30 else 30]))
               for e in manifest["models"]]
    assert {json.dumps(e["params"]["envelope"]["tempo_poses"]) for e in entries}.__len__() == 2
    doc = manifest_document(entries, manifest["actions"], manifest["data_hash"])
    # stored once: no model's envelope in the file carries a shared quantity or tempo's poses
    assert all(not set(m["params"]["envelope"]) & {*SHARED, "tempo_poses"} for m in doc["models"])
    write_manifest(doc, tmp_path / "manifest.json")
    assert json.loads((tmp_path / "manifest.json").read_text()) == json.loads(json.dumps(doc))
    read = read_manifest(tmp_path / "manifest.json")   # what every model uses: the shared part put back
    assert "speed_envelope" not in read
    shared = {json.dumps({q: m["params"]["envelope"][q] for q in (*SHARED, "tempo_poses")}) for m in read["models"]}
    assert len(shared) == 1
    shortest = min(entries, key=lambda e: e["params"]["history_frames"])["params"]["envelope"]
    assert all(read["models"][0]["params"]["envelope"][q] == pytest.approx(shortest[q]) for q in SHARED)
    assert read["models"][0]["params"]["envelope"]["tempo_poses"] == json.loads(json.dumps(shortest["tempo_poses"]))
    for m, e in zip(read["models"], entries):      # the other quantities stay the model's own
        assert m["params"]["envelope"]["root_height"] == pytest.approx(e["params"]["envelope"]["root_height"])
