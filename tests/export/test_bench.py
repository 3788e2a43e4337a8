"""The benchmark's pure parts (export/bench): planning, graph facts, statistics, profile, tables."""
import numpy as np
import onnx
import pytest
from onnx import TensorProto, helper, numpy_helper

from export.bench import dist_sizes, profile_summary
from export.bench.native import cap_mb, graph_facts, plan, rel_diff
from export.bench.report import changes, ratio, spread, summary, table

ACTIONS = ["walk", "run", "jump"]


def _entry(mid, method, controls):
    return {"id": mid, "method": method, "config": f"{mid}.json", "params": {}, "controls": controls, "graphs": {}}


def test_plan_covers_k_and_adds_a_three_action_row_for_action_models():
    manifest = {"actions": ACTIONS, "models": [
        _entry("det", "regression", [{"id": "horizon"}]),
        _entry("wat", "wat", [{"id": "k"}, {"id": "actions", "default": ["walk"]}]),
    ]}
    cases = plan(manifest)
    assert [c["id"] for c in cases] == ["det/k1", "wat/k1", "wat/k10", "wat/k50", "wat/k10-a3"]
    seq = cases[-1]["request"]["actions"]
    assert seq == ["walk", "run", "jump"]
    assert cases[1]["request"]["actions"] == ["walk"] and cases[2]["request"]["k"] == 10


def test_caps_follow_the_method_and_the_transformer_variant():
    assert cap_mb(_entry("lcp-vae", "lcp_vae", [])) == 0.25
    assert cap_mb(_entry("wat-transformer", "wat", [])) == 0.55
    assert cap_mb(_entry("wat-rnn", "wat", [])) == 0.45
    assert cap_mb(_entry("zero", "zero_velocity", [])) is None


def test_graph_facts_count_nodes_ops_and_parameters(tmp_path):
    w = numpy_helper.from_array(np.ones((4, 3), np.float32), "w")
    c = helper.make_node("Constant", [], ["b"], value=numpy_helper.from_array(np.zeros(3, np.float32)))
    mm = helper.make_node("MatMul", ["x", "w"], ["h"])
    add = helper.make_node("Add", ["h", "b"], ["y"])
    relu = helper.make_node("Relu", ["y"], ["z"])
    g = helper.make_graph([c, mm, add, relu], "g", [helper.make_tensor_value_info("x", TensorProto.FLOAT, [1, 4])],
                          [helper.make_tensor_value_info("z", TensorProto.FLOAT, [1, 3])], [w])
    path = tmp_path / "g.onnx"
    onnx.save(helper.make_model(g), path)
    facts = graph_facts(path)
    assert facts["nodes"] == 4 and facts["params"] == 12 + 3
    assert facts["ops"] == {"Constant": 1, "MatMul": 1, "Add": 1, "Relu": 1}
    assert 0 < facts["gzip_bytes"] and facts["bytes"] == path.stat().st_size


def test_spread_is_median_and_quartiles_and_ratio_uses_medians():
    s = spread([4.0, 1.0, 3.0, 2.0, 5.0])
    assert (s["median"], s["q1"], s["q3"], s["iqr"], s["n"]) == (3.0, 2.0, 4.0, 2.0, 5)
    assert ratio([10.0, 12.0, 100.0], [2.0, 3.0, 4.0]) == pytest.approx(4.0)
    with pytest.raises(ValueError, match="no runs"):
        spread([])


def test_rel_diff_is_relative_to_the_output_rms():
    a = {"y": np.array([3.0, -3.0, 3.0, -3.0], np.float32)}
    assert rel_diff(a, {"y": a["y"] + np.array([0, 0.3, 0, 0], np.float32)}) == pytest.approx(0.1)


def test_profile_summary_sums_kernel_time_per_op_and_averages_runs():
    events = [{"cat": "Session", "name": "model_run", "dur": 900},
              {"cat": "Session", "name": "model_run", "dur": 1100},
              {"cat": "Node", "name": "a_kernel_time", "dur": 300, "args": {"op_name": "MatMul"}},
              {"cat": "Node", "name": "b_kernel_time", "dur": 500, "args": {"op_name": "MatMul"}},
              {"cat": "Node", "name": "c_kernel_time", "dur": 200, "args": {"op_name": "Add"}},
              {"cat": "Node", "name": "c_fence_before", "dur": 999, "args": {"op_name": "Add"}}]
    p = profile_summary("m/g/b10", events, runs=2)
    assert list(p["op_ms"]) == ["MatMul", "Add"]
    assert p["op_ms"]["MatMul"] == pytest.approx(0.4) and p["node_ms"] == pytest.approx(0.5)
    assert p["run_ms"] == pytest.approx(1.0)


def test_table_checks_row_width_and_dist_sizes_sum_files(tmp_path):
    assert table(["a", "b"], [["1", "2"]]).splitlines() == ["| a | b |", "|---|---|", "| 1 | 2 |"]
    with pytest.raises(ValueError, match="2 headers"):
        table(["a", "b"], [["1"]])
    (tmp_path / "x").mkdir()
    (tmp_path / "x" / "a.txt").write_bytes(b"a" * 1000)
    (tmp_path / "b.bin").write_bytes(bytes(range(256)))
    d = dist_sizes(tmp_path)
    assert d["files"] == 2 and d["bytes"] == 1256 and d["largest"][0]["file"] == "b.bin"
    with pytest.raises(FileNotFoundError, match="no built site"):
        dist_sizes(tmp_path / "empty")


def test_a_recorded_change_is_reported_as_earlier_to_now_medians():
    def run(first_ms, nodes):
        return {"sizes": [{"model": "m", "onnx_gzip_bytes": 200_000, "graphs": {"decoder": {"nodes": nodes}}}],
                "native": {"load_ms": {"m": 3.0}},
                "browser": {"load": {"m": {"round_trip_ms": [10.0, 12.0, 14.0]}},
                            "cases": [{"id": "m/k10", "worker_ms": [5.0, 6.0, 7.0]}, {"id": "m/k1", "worker_ms": [1.0]}],
                            "navigation": [{"model": "m", "first_prediction_ms": first_ms}]}}
    before = summary(run([4000.0, 4100.0, 4200.0], 1800))
    assert before["m"] == {"nodes": 1800, "gzip_bytes": 200_000, "native_load_ms": 3.0, "browser_load_ms": 12.0,
                           "k10_worker_ms": 6.0, "first_prediction_ms": 4100.0}
    now = run([2000.0, 2100.0], 450) | {"earlier": [{"date": "d", "change": "fused", "note": "n.", "summary": before}]}
    text = "\n".join(changes(now))
    assert "### fused" in text
    assert "| m | 1800 → 450 | 200 → 200 | 3 → 3 | 12 → 12 | 6.0 → 6.0 | 4100 → 2050 |" in text


def test_the_machine_line_names_the_renderer_the_stage_reported():
    from export.bench.report import _renderer
    assert _renderer("software") == "software WebGL, drawn without multisampling"
    assert _renderer("gpu") == "WebGL on a GPU, multisampled"
    assert _renderer(None) == "WebGL renderer not reported"


def test_a_missed_frame_gap_is_placed_before_or_after_the_result():
    from export.bench.report import analysis
    def doc(gaps):
        return {"native": {"graphs": [], "cases": []}, "sizes": [], "machine": {"vector": []}, "profiles": [],
                "browser": {"graphs": [], "cases": [], "load": {}, "navigation": [],
                            "frames": [{"model": "m", "k": 50, "gaps_ms": gaps, "max_gap_ms": max(gaps), "fps": 25.0}]}}
    after, = analysis(doc([17, 17, 33, 117, 50]))
    assert "first frames after the result" in after and "117 ms" in after and "40 ms on average" in after
    during, = analysis(doc([17, 83, 17, 33, 17]))
    assert "while the worker predicts" in during
    assert analysis(doc([17, 33, 33])) == []   # met: nothing to explain


def test_a_small_graph_that_misses_is_split_into_call_cost_and_cost_per_batch_row():
    from export.bench.report import analysis
    ids = ["m/step/b1", "m/step/b50"]
    native = {"m/step/b1": [0.05] * 3, "m/step/b50": [0.099] * 3}
    browser = {"m/step/b1": [0.05] * 3, "m/step/b50": [0.54] * 3}   # 10 µs a row against 1 µs
    doc = {"native": {"graphs": [{"id": i, "model": "m", "role": "step", "native_ms": native[i]} for i in ids], "cases": []},
           "sizes": [{"model": "m", "graphs": {"step": {"nodes": 50}}}], "machine": {"vector": ["avx2", "fma"]}, "profiles": [],
           "browser": {"graphs": [{"id": i, "ms": browser[i]} for i in ids], "cases": [], "load": {}, "navigation": [], "frames": []}}
    line = next(x for x in analysis(doc) if x.startswith("m/step:"))
    assert "10.0 µs against 1.0 µs, 10.0x" in line and "more than the up to 4x" in line


def test_graphs_slower_after_other_graphs_are_named_and_the_ratio_uses_the_fresh_worker():
    from export.bench.report import analysis, targets
    ids = ["m/step/b1", "m/step/b50"]
    native = {"m/step/b1": [0.04] * 3, "m/step/b50": [0.1] * 3}
    fresh = {"m/step/b1": [0.05] * 3, "m/step/b50": [0.3] * 3}
    shared = {"m/step/b1": [0.055] * 3, "m/step/b50": [0.6] * 3}
    doc = {"native": {"graphs": [{"id": i, "model": "m", "role": "step", "native_ms": native[i]} for i in ids], "cases": []},
           "sizes": [{"model": "m", "graphs": {"step": {"nodes": 50}}, "onnx_gzip_bytes": 1000, "within_cap": True}],
           "machine": {"vector": []}, "profiles": [],
           "browser": {"graphs": [{"id": i, "ms": fresh[i], "shared_ms": shared[i]} for i in ids], "cases": [], "load": {},
                       "navigation": [], "frames": []}}
    line = next(x for x in analysis(doc) if x.startswith("Order effect"))
    assert "1 graph(s)" in line and "m/step/b50 2.0x" in line and "m/step/b1" not in line
    ratio_target = next(t for t in targets(doc["native"], doc["browser"], doc["sizes"], {"gzip_bytes": 0}, [])
                        if t["target"].startswith("browser/native"))
    assert ratio_target["met"] is True   # 3.0 alone; the shared worker's 6.0 is reported, not the target
