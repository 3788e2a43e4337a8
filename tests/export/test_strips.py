"""`python -m export strips`: held-out futures drawn at 0-3 s with the numbers read from the same futures."""
import json

import numpy as np

from export import strips
from export.sample.request import PredictError


def test_standing_still_reads_zero_speed_beside_a_walking_truth(tmp_path):
    summary = strips.run(["zero-velocity"], tmp_path)
    walk = summary["zero-velocity"]["walk"]
    assert all(s == 0 for sample in walk["samples"] for s in sample["root_speed"])
    assert min(walk["truth_measures"]["root_speed"]) > 1.0          # cmu_08_03 walks at ~1.5 m/s
    assert summary["zero-velocity"]["walk -> jump -> kick"] == {"skipped": "takes no action sequence"}
    assert (tmp_path / "zero-velocity.png").stat().st_size > 10_000
    assert json.loads((tmp_path / "strips.json").read_text()) == summary


def test_redrawing_one_model_keeps_the_others_entries(tmp_path):
    (tmp_path / "strips.json").write_text(json.dumps({"wat-rnn": {"walk": {"refused": "x"}}}))
    summary = strips.run(["zero-velocity"], tmp_path)
    written = json.loads((tmp_path / "strips.json").read_text())
    assert written == {"wat-rnn": {"walk": {"refused": "x"}}, **summary} and "zero-velocity" in summary


def test_a_refused_history_is_drawn_with_its_reason(tmp_path):
    class Refuses:
        def predict(self, history, req):
            raise PredictError("the history yields 2 keyposes")
    entry = {"params": {"history_frames": 10}, "controls": [{"id": "k"}]}
    case = strips.CASES[0]
    res = strips.predict_case(Refuses(), entry, case, np.zeros((200, 18, 3)))
    assert res == {"refused": "the history yields 2 keyposes"}
    strips.draw("a model", [(case, res)], tmp_path / "m.png")
    assert (tmp_path / "m.png").exists()
