"""The read-out vector's generator (export/vectors_readout.py): windows chosen from the clip index by
role and length (the index's default first), and the committed numbers are the evaluation's own."""
import json

import numpy as np
import pytest

from export.eval import metrics as M
from export.paths import CLIPS_DIR, VECTORS_DIR
from export.vectors_readout import MIN_HORIZON, _windows


def _index(clips, default=None):
    doc = {"clips": [{"name": n, "file": f"{n}.json", "action": "walk", "frames": f, "role": role, "train": [], "test": test}
                     for n, f, role, test in clips]}
    if default:
        doc["default"] = default
    return doc


def test_windows_come_from_test_ranges_longest_first():
    index = _index([("a", 60, "test", [[0, 60]]), ("b", 200, "train", []), ("c", 120, "train+test", [[70, 120]]),
                    ("d", 20, "test", [[0, 20]])])
    got = [(c["name"], s, h) for c, s, h in _windows(index, 10, 90)]
    # d holds fewer than MIN_HORIZON frames after a 10-frame history; b has no test range
    assert got == [("a", 0, 50), ("c", 70, 40)]
    assert all(h >= MIN_HORIZON for *_, h in got)


def test_windows_cap_the_horizon_and_put_the_index_default_first():
    index = _index([("a", 300, "test", [[0, 300]]), ("z", 150, "test", [[0, 150]])], default={"clip": "z", "start": 20})
    got = [(c["name"], s, h) for c, s, h in _windows(index, 10, 90)]
    assert got == [("z", 20, 90), ("a", 0, 90)]
    # a default outside every test range is not used
    index["default"] = {"clip": "z", "start": 145}
    assert [c["name"] for c, _, _ in _windows(index, 10, 90)] == ["a", "z"]


@pytest.fixture(scope="module")
def vector():
    path = VECTORS_DIR / "readout.json"
    if not path.exists():
        pytest.skip("contract/vectors/readout.json is not written yet")
    return json.loads(path.read_text())


def test_committed_cases_are_test_windows_with_the_evaluations_numbers(vector):
    index = json.loads((CLIPS_DIR / "index.json").read_text())
    by_name = {c["name"]: c for c in index["clips"]}
    assert vector["cases"]
    for case in vector["cases"]:
        clip = by_name[case["clip"]]
        n, h = len(case["history"]), case["horizon_frames"]
        assert any(a <= case["start"] and case["start"] + n + h <= b for a, b in clip["test"]), case["clip"]
        assert len(case["truth"]) == h == case["request"]["horizon_frames"]
        # stops keep a margin (each case's own curve tolerance is checked when it was chosen; this is its floor)
        assert case["min_margin"] is None or case["min_margin"] >= 1e-6
        truth = np.asarray(case["truth"])
        for kind, relative in (("root_relative", True), ("world", False)):
            e = case[kind]
            assert e["ade"] == min(e["ade_per_sample"]) and e["fde"] == min(e["fde_per_sample"])
            assert len(e["ade_per_sample"]) == case["request"]["k"]
            # the truth is the clip's own frames after the history
            assert M.ade_fde(truth[None], truth, root_relative=relative) == (0.0, 0.0)
