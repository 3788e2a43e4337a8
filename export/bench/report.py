"""The benchmark's numbers into targets and a markdown page: pure functions of the two sides' JSON."""
from __future__ import annotations

from collections import defaultdict

import numpy as np

# The targets of issue 9 on this machine (ms, MB = 10^6 bytes).
STEP_K10_MS = 30.0
ACTIONS3_K10_MS = 100.0
K50_MS = 250.0
MAX_RATIO = 4.0
FUTURES_DRAWN_MS = 1500.0  # issue 29: navigation -> the first frame with futures drawn
FRAME_GAP_MS = 50.0        # the K = 50 frame gaps' 95th percentile (issue 29) and their longest (issue 9)
FRAME_GAP_PERCENTILE = 95.0
# The first-futures timeline (bench/browser.ts: the page's mf: marks and its files), in order.
STARTUP_STAGES = ["DOMContentLoaded", "app-start", "app-built", "manifest fetched", "manifest-in", "last script fetched",
                  "last clip file fetched", "clip-in", "last ONNX fetched", "wasm fetched", "model-loaded", "predict-asked",
                  "prediction-received", "show-start", "tracks-set", "futures-drawn", "prediction-shown"]
ORDER_EFFECT = 1.5     # shared-worker over fresh-worker time worth a line in the analysis
ONNX_TOTAL_GZ = 2e6
DIST_GZ = 6e6          # dist/ without the served clips
CLIPS_GZ = 1.5e6       # the served clips (issue 17: their own measured budget)


def spread(values: list[float]) -> dict:
    """Median and interquartile range (numpy's linear quantiles); n to show how many runs."""
    if not values:
        raise ValueError("no runs to summarise")
    q1, med, q3 = (float(x) for x in np.percentile(np.asarray(values, np.float64), [25, 50, 75]))
    return {"median": med, "q1": q1, "q3": q3, "iqr": q3 - q1, "n": len(values)}


def ratio(browser_ms: list[float], native_ms: list[float]) -> float:
    """Browser median over native median."""
    native = spread(native_ms)["median"]
    if native <= 0:
        raise ValueError("native median is not positive")
    return spread(browser_ms)["median"] / native


def fmt_ms(s: dict) -> str:
    """Median [q1–q3] with enough decimals for sub-millisecond graphs."""
    d = 1 if s["median"] >= 1 else 2 if s["median"] >= 0.1 else 3
    return f"{s['median']:.{d}f} [{s['q1']:.{d}f}–{s['q3']:.{d}f}]"


def table(headers: list[str], rows: list[list[str]]) -> str:
    """A GitHub markdown table; every row must have one cell per header."""
    for r in rows:
        if len(r) != len(headers):
            raise ValueError(f"row {r} has {len(r)} cells for {len(headers)} headers")
    def cell(text: str) -> str:
        return str(text).replace("|", "\\|").replace("\n", " ")
    lines = ["| " + " | ".join(map(cell, headers)) + " |", "|" + "|".join("---" for _ in headers) + "|"]
    return "\n".join(lines + ["| " + " | ".join(map(cell, r)) + " |" for r in rows])


def gap_percentile(gaps: list[float] | None, q: float = FRAME_GAP_PERCENTILE) -> float | None:
    """The q-th percentile (numpy's linear) of a prediction's frame gaps; None without gaps."""
    return float(np.percentile(np.asarray(gaps, np.float64), q)) if gaps else None


def startup(navigation: list[dict]) -> dict[str, dict[str, float]]:
    """Per navigation target: the median time of each start-up stage and of the futures drawn (ms)."""
    out: dict[str, dict[str, float]] = {}
    for n in navigation:
        row = {k: spread(v)["median"] for k, v in (n.get("timeline_ms") or {}).items() if v}
        if n.get("futures_drawn_ms"):
            row["futures-drawn"] = spread(n["futures_drawn_ms"])["median"]
        if n.get("first_prediction_ms"):
            row["done"] = spread(n["first_prediction_ms"])["median"]
        out[n["model"]] = row
    return out


def longest_steps(row: dict[str, float], n: int = 3) -> list[tuple[str, str, float]]:
    """The n longest steps between consecutive stages of one view's timeline, up to the futures drawn."""
    end = row.get("futures-drawn")
    times = sorted((t, k) for k, t in row.items() if k in STARTUP_STAGES and (end is None or t <= end))
    steps = [(a, b, tb - ta) for (ta, a), (tb, b) in zip(times, times[1:])]
    return sorted(steps, key=lambda x: -x[2])[:n]


def _target(name: str, limit: str, items: list[tuple[str, float | None, bool | None]]) -> dict:
    """items: (what, measured, met); met None = not measured. The target is met when every item is."""
    measured = [m for _, _, m in items if m is not None]
    met = None if not measured else all(measured)
    return {"target": name, "limit": limit, "met": met,
            "items": [{"what": w, "value": v, "met": m} for w, v, m in items]}


def targets(native: dict, browser: dict, sizes: list[dict], dist: dict, cases: list[dict]) -> list[dict]:
    case_ms = {c["id"]: spread(c["round_trip_ms"])["median"] for c in browser["cases"]}
    out = []
    items = []
    for c in cases:
        if c["id"].endswith("/k10") or (c["k"] == 1 and f"{c['model']}/k10" not in {x["id"] for x in cases}):
            v = case_ms.get(c["id"])
            items.append((c["id"], v, None if v is None else v < STEP_K10_MS))
    out.append(_target("one predictor step at K=10 (K=1 for a model without K)", f"< {STEP_K10_MS:.0f} ms", items))
    items = [(c["id"], case_ms.get(c["id"]), None if c["id"] not in case_ms else case_ms[c["id"]] < ACTIONS3_K10_MS)
             for c in cases if c["actions"] >= 3 and c["k"] == 10]
    out.append(_target("WAT at K=10, 3-action sequence", f"< {ACTIONS3_K10_MS:.0f} ms", items))
    items = [(c["id"], case_ms.get(c["id"]), None if c["id"] not in case_ms else case_ms[c["id"]] < K50_MS)
             for c in cases if c["k"] == 50]
    out.append(_target("any model at K=50, one step", f"< {K50_MS:.0f} ms", items))
    nat = {g["id"]: g["native_ms"] for g in native["graphs"]}
    items = []
    for g in browser["graphs"]:
        r = ratio(g["ms"], nat[g["id"]]) if g.get("ms") else None
        items.append((g["id"], r, None if r is None else r <= MAX_RATIO))
    out.append(_target("browser/native ratio per graph", f"<= {MAX_RATIO:.0f}", items))
    drawn = [(n["model"], spread(n["futures_drawn_ms"])["median"] if n.get("futures_drawn_ms") else None)
             for n in browser["navigation"]]
    items = [(what, v, None if v is None else v < FUTURES_DRAWN_MS) for what, v in drawn]
    out.append(_target("navigation -> first frame with futures drawn (first view; each model by link)",
                       f"< {FUTURES_DRAWN_MS:.0f} ms", items))
    p95 = [(f"{f['model']} K={f['k']}", gap_percentile(f.get("gaps_ms"))) for f in browser["frames"]]
    items = [(what, v, None if v is None else v < FRAME_GAP_MS) for what, v in p95]
    out.append(_target(f"K=50 frame gaps during a prediction, {FRAME_GAP_PERCENTILE:.0f}th percentile",
                       f"< {FRAME_GAP_MS:.0f} ms", items))
    items = [(f"{f['model']} K={f['k']}", f.get("max_gap_ms"),
              None if f.get("max_gap_ms") is None else f["max_gap_ms"] < FRAME_GAP_MS) for f in browser["frames"]]
    out.append(_target("K=50 frame gaps during a prediction, longest", f"< {FRAME_GAP_MS:.0f} ms", items))
    items = [(s["model"], s["onnx_gzip_bytes"] / 1e6, s["within_cap"]) for s in sizes]
    total = sum(s["onnx_gzip_bytes"] for s in sizes)
    items.append(("all models together", total / 1e6, total < ONNX_TOTAL_GZ))
    for n in browser["navigation"]:
        own = set(n["own_files"])
        other = sorted({u.rsplit("/", 1)[-1] for u in n["onnx_requests"]["page"]} - own)
        items.append((f"lazy: opening {n['model']} fetched other models' files {other}", None, not other))
    out.append(_target("served ONNX files: each within its cap, together, lazily per model",
                       f"cap per model; < {ONNX_TOTAL_GZ / 1e6:.0f} MB gz together", items))
    other = dist.get("other_gzip_bytes", dist["gzip_bytes"])
    clips = dist.get("clips_gzip_bytes", 0)
    out.append(_target("dist/ gzipped", f"< {DIST_GZ / 1e6:.0f} MB without the clips; clips < {CLIPS_GZ / 1e6:.1f} MB",
                       [("dist/ without clips/", other / 1e6, other < DIST_GZ),
                        ("clips/", clips / 1e6, clips < CLIPS_GZ)]))
    return out


def _renderer(kind: str | None) -> str:
    """The stage's WebGL as the page reported it (web/src/viewer/stage.ts: no multisampling on a CPU renderer)."""
    return {"software": "software WebGL, drawn without multisampling", "gpu": "WebGL on a GPU, multisampled"}.get(
        kind or "", "WebGL renderer not reported")


def _met(m: bool | None) -> str:
    return {True: "met", False: "**missed**", None: "not measured"}[m]


def order_effect(graphs: list[dict]) -> str | None:
    """A line naming the graphs much slower in the shared worker than alone (bench/browser.ts: graphs())."""
    slow = sorted(((spread(g["shared_ms"])["median"] / spread(g["ms"])["median"], g["id"]) for g in graphs
                   if g.get("ms") and g.get("shared_ms")), reverse=True)
    slow = [(x, gid) for x, gid in slow if x >= ORDER_EFFECT]
    if not slow:
        return None
    return (f"Order effect: {len(slow)} graph(s) ran at least {ORDER_EFFECT}x slower in a worker that had run other "
            f"graphs first than alone ({', '.join(f'{gid} {x:.1f}x' for x, gid in slow[:4])}). V8 optimises "
            "onnxruntime's wasm with call feedback from the graphs before; a page where the user switches models "
            "can see these times.")


def analysis(doc: dict) -> list[str]:
    """Facts computed from the run that explain the misses (bullets for the markdown)."""
    nat, br = doc["native"], doc["browser"]
    sizes = {s["model"]: s for s in doc["sizes"]}
    nat_graphs = {g["id"]: g for g in nat["graphs"]}
    lines = []
    timed = [g for g in br["graphs"] if g.get("ms")]
    if timed:
        def nodes(g):
            n = nat_graphs[g["id"]]
            return sizes[n["model"]]["graphs"][n["role"]]["nodes"]
        floor = min(timed, key=lambda g: (nodes(g), spread(g["ms"])["median"]))
        fb, fn = spread(floor["ms"])["median"], spread(nat_graphs[floor["id"]]["native_ms"])["median"]
        lines.append(f"Per-call floor: the smallest graph ({floor['id']}, {nodes(floor)} nodes) takes {fb:.2f} ms per "
                     f"`session.run` in the browser against {fn:.3f} ms natively. A graph whose native time is near "
                     "this floor gets a large ratio from the fixed cost of a call (inputs copied into the wasm heap, "
                     "outputs copied out, an async hop), not from its arithmetic.")
        for g in timed:
            n = nat_graphs[g["id"]]
            k = nodes(g)
            b, nv = spread(g["ms"])["median"], spread(n["native_ms"])["median"]
            # per-node overhead shows where each node has little arithmetic natively (< 2 µs)
            if k >= 200 and 1e3 * nv / k < 2 and ratio(g["ms"], n["native_ms"]) > MAX_RATIO:
                lines.append(f"{g['id']}: {k} nodes; {1e3 * b / k:.1f} µs per node in the browser, "
                             f"{1e3 * nv / k:.1f} µs natively: per-node overhead (an unrolled recurrence; a fused "
                             "recurrent op or fewer, larger ops is the fix at export).")
    profiles = {p["graph"]: p for p in doc.get("profiles", [])}
    flags = doc["machine"].get("vector", [])
    vec = " + ".join(f.upper() for f in flags if f in ("avx2", "fma", "avx512f")) or "this CPU"
    lanes = 4 if "avx512f" in flags else 2 if "avx2" in flags else 1   # 512 / 256 / 128-bit against wasm's 128
    peak = lanes * (2 if "fma" in flags else 1)
    for g in timed:
        n = nat_graphs[g["id"]]
        nv = spread(n["native_ms"])["median"]
        prof = profiles.get(g["id"]) or next((p for gid, p in profiles.items()
                                              if gid.rsplit("/", 1)[0] == g["id"].rsplit("/", 1)[0]), None)
        if nodes(g) < 200 and nv >= 0.3 and ratio(g["ms"], n["native_ms"]) > MAX_RATIO and prof and prof["node_ms"] > 0:
            top = list(prof["op_ms"].items())[:3]
            share = sum(ms for _, ms in top) / prof["node_ms"]
            lines.append(f"{g['id']}: {nodes(g)} nodes and {nv:.1f} ms natively, so not per-node overhead; "
                         f"{', '.join(op for op, _ in top)} take {100 * share:.0f}% of the profiled node time: "
                         "arithmetic, where onnxruntime-web's wasm SIMD kernels (128-bit, no fused multiply-add) "
                         f"stand against native kernels on {vec}: {lanes}x the lanes"
                         f"{' and fused multiply-adds' if 'fma' in flags else ''}, so up to {peak}x the arithmetic "
                         "per instruction.")
    # A small graph (neither many nodes nor much native time) that still misses: split its time into a
    # fixed cost per call and a cost per batch row, from its smallest and largest batch.
    by_graph = defaultdict(list)
    for g in timed:
        by_graph[g["id"].rsplit("/", 1)[0]].append(g)
    for gid, gs in by_graph.items():
        missed = [g for g in gs if ratio(g["ms"], nat_graphs[g["id"]]["native_ms"]) > MAX_RATIO
                  and nodes(g) < 200 and spread(nat_graphs[g["id"]]["native_ms"])["median"] < 0.3]
        batch = {g["id"]: int(g["id"].rsplit("/b", 1)[1]) for g in gs if g["id"].rsplit("/b", 1)[-1].isdigit()}
        if not missed or len(batch) < 2:
            continue
        lo, hi = min(gs, key=lambda g: batch.get(g["id"], 0)), max(gs, key=lambda g: batch.get(g["id"], 0))
        rows = batch[hi["id"]] - batch[lo["id"]]
        b_lo, b_hi = spread(lo["ms"])["median"], spread(hi["ms"])["median"]
        n_lo, n_hi = (spread(nat_graphs[x["id"]]["native_ms"])["median"] for x in (lo, hi))
        per_b, per_n = 1e3 * (b_hi - b_lo) / rows, 1e3 * (n_hi - n_lo) / rows
        if per_n <= 0:
            continue
        x = per_b / per_n
        why = (f"within the up to {peak}x per instruction that {vec} gives over wasm's 128-bit SIMD" if x <= peak else
               f"more than the up to {peak}x per instruction that {vec} gives over wasm's 128-bit SIMD, so vector "
               "width alone does not explain it (compare the shared-worker column: V8's code for the graph also "
               "depends on what ran before)")
        lines.append(f"{gid}: {b_lo:.3f} ms at batch {batch[lo['id']]} and {b_hi:.3f} ms at batch {batch[hi['id']]} in the "
                     f"browser, {n_lo:.3f} and {n_hi:.3f} ms natively. Each further batch row (its arithmetic) costs "
                     f"{per_b:.1f} µs against {per_n:.1f} µs, {x:.1f}x: {why}. The fixed cost of a call does not set this ratio.")
    line = order_effect(br["graphs"])
    if line:
        lines.append(line)
    for c in br["cases"]:
        if not c["id"].endswith("/k10"):
            continue
        per_run = [sum(t["ms"] for t in run) for run in c["timings"]]
        if per_run:
            graphs_ms, total = spread(per_run)["median"], spread(c["worker_ms"])["median"]
            calls = len(c["timings"][0])
            lines.append(f"{c['id']}: {total:.1f} ms in the worker, of which {graphs_ms:.1f} ms in {calls} graph calls; "
                         f"the rest ({total - graphs_ms:.1f} ms) is the predictor's own TypeScript "
                         "(noise, stopping, smoothness, interpolation) and tensor wrapping.")
    for f in br.get("frames", []):
        gaps = f.get("gaps_ms") or []
        if not gaps or f.get("max_gap_ms") is None or f["max_gap_ms"] < FRAME_GAP_MS:
            continue
        # the last two intervals follow the result (recording stops two frames after it is shown)
        where = ("the first frames after the result, which build and first draw the new scene"
                 if gaps.index(max(gaps)) >= len(gaps) - 2 else "while the worker predicts")
        lines.append(f"{f['model']} K={f['k']}: the longest gap ({max(gaps):.0f} ms) falls in {where}; with the K=50 "
                     f"futures playing a frame takes {1000 / f['fps']:.0f} ms on average ({f['fps']:.1f} fps). Frames "
                     "start on 16.7 ms vsync steps, so every gap under 50 ms means every frame within two steps (33 ms).")
    for view, row in startup(br.get("navigation", [])).items():
        if row.get("futures-drawn", 0) < FUTURES_DRAWN_MS:
            continue
        steps = longest_steps(row)
        lines.append(f"{view}: futures drawn at {row['futures-drawn']:.0f} ms; the longest steps of its timeline: "
                     + ", ".join(f"{a} → {b} {ms:.0f} ms" for a, b, ms in steps) + ".")
    loads = {mid: spread(v["round_trip_ms"])["median"] for mid, v in br["load"].items()}
    warm_load = {}
    for g in br["graphs"]:
        n = nat_graphs[g["id"]]
        if g.get("load_ms") is not None:
            warm_load.setdefault(n["model"], {})[n["role"]] = g["load_ms"]
    for n in br["navigation"]:
        if n.get("first_prediction_ms") and n["model"] in loads:
            warm = warm_load.get(n["model"], {})
            lines.append(f"First prediction with {n['model']}: {spread(n['first_prediction_ms'])['median']:.0f} ms. Loading the "
                         f"model in a fresh bench-page worker (wasm start-up, fetch, every session) took "
                         f"{loads[n['model']]:.0f} ms; creating the largest session again in the warmed graph worker took "
                         f"{max(warm.values()):.0f} ms." if warm else "")
    return [line for line in lines if line]


def summary(doc: dict) -> dict:
    """Per model: the numbers a change to the served graphs is judged by (medians, ms)."""
    br, nat = doc["browser"], doc["native"]
    out: dict[str, dict] = defaultdict(dict)
    for s in doc["sizes"]:
        out[s["model"]].update(nodes=sum(g["nodes"] for g in s["graphs"].values()), gzip_bytes=s["onnx_gzip_bytes"])
    for mid, ms in nat["load_ms"].items():
        out[mid]["native_load_ms"] = ms
    for mid, v in br["load"].items():
        out[mid]["browser_load_ms"] = spread(v["round_trip_ms"])["median"]
    for c in br["cases"]:
        if c["id"].endswith("/k10"):
            out[c["id"].split("/")[0]]["k10_worker_ms"] = spread(c["worker_ms"])["median"]
    for n in br["navigation"]:
        if n.get("first_prediction_ms"):
            out[n["model"]]["first_prediction_ms"] = spread(n["first_prediction_ms"])["median"]
    return dict(out)


def changes(doc: dict) -> list[str]:
    """Each recorded change (bench/earlier.json) against this run: what it changed, in numbers."""
    now = summary(doc)
    # (summary key, column label, unit scale, digits)
    cols = [("nodes", "nodes", 1, 0), ("gzip_bytes", "ONNX gz (kB)", 1e-3, 0), ("native_load_ms", "native session (ms)", 1, 0),
            ("browser_load_ms", "browser load (ms)", 1, 0), ("k10_worker_ms", "K=10 in worker (ms)", 1, 1),
            ("first_prediction_ms", "first prediction (ms)", 1, 0)]

    def cell(a, b, scale, digits):
        return "—" if a is None or b is None else f"{a * scale:.{digits}f} → {b * scale:.{digits}f}"
    out = []
    for e in doc.get("earlier", []):
        out += [f"### {e['change']}", "", f"Earlier run: {e['date']}. {e['note']}", ""]
        rows = [[mid] + [cell(before.get(k), now.get(mid, {}).get(k), sc, d) for k, _, sc, d in cols]
                for mid, before in e["summary"].items()]
        out += [table(["model"] + [c[1] for c in cols], rows), ""]
    return out


def startup_table(rows: dict[str, dict[str, float]]) -> list[str]:
    """The first-futures timeline, one row per view, the stages any view has (STARTUP_STAGES' order)."""
    stages = [k for k in STARTUP_STAGES + ["done"] if any(k in r for r in rows.values())]
    return [table(["view"] + stages, [[view] + [f"{r[k]:.0f}" if k in r else "—" for k in stages]
                                      for view, r in rows.items()])]


def startup_changes(doc: dict) -> list[str]:
    """Each earlier run's first-futures timeline (bench/earlier.json entries with `startup`) against this run's."""
    now = startup(doc["browser"]["navigation"])
    keys = ["manifest-in", "clip-in", "wasm fetched", "model-loaded", "predict-asked", "prediction-received", "futures-drawn"]
    out = []
    for e in doc.get("earlier", []):
        if not e.get("startup"):
            continue
        rows = [[view] + [f"{before[k]:.0f} → {now[view][k]:.0f}" if k in before and k in now.get(view, {}) else "—"
                          for k in keys] for view, before in e["startup"].items()]
        out += [f"Before and after: {e['change']} (earlier run {e['date']}; {e['note']}) Earlier → this run, ms after "
                "navigation start, medians:", "", table(["view"] + keys, rows), ""]
        gaps = {f["model"]: gap_percentile(f.get("gaps_ms")) for f in doc["browser"].get("frames", [])}
        pairs = [f"{m} {b:.0f} → {gaps[m]:.0f}" for m, b in (e.get("frame_gap_p95_ms") or {}).items()
                 if b is not None and gaps.get(m) is not None]
        if pairs:
            out += [f"K=50 frame gaps during a prediction, {FRAME_GAP_PERCENTILE:.0f}th percentile (ms), earlier → this run: "
                    + "; ".join(pairs) + ".", ""]
    return out


def markdown(doc: dict) -> str:
    m, nat, br = doc["machine"], doc["native"], doc["browser"]
    sizes = {s["model"]: s for s in doc["sizes"]}
    nat_cases = {c["id"]: c for c in nat["cases"]}
    nat_graphs = {g["id"]: g for g in nat["graphs"]}
    out = ["# Performance", "",
           "Written by `make bench` (`python -m export bench`: native onnxruntime in Python, then bench/ drives "
           "headless Chromium on the built site). Numbers are milliseconds, median [interquartile range] over "
           f"{doc['runs']} runs after {doc['warmup']} warm-up runs, unless said otherwise. Raw numbers: "
           f"`{doc['json_path']}`.", "",
           "## Machine", "",
           f"- CPU: {m['cpu']}, {m['cores']} cores ({', '.join(m.get('vector') or ['vector extensions unknown'])}); {m['os']}",
           f"- Browser: {m['chromium']} (headless, {_renderer(m.get('renderer'))}), onnxruntime-web {m['onnxruntime_web']} "
           f"(wasm, 1 thread, session graph optimisation '{m.get('session_optimization', 'all')}')",
           f"- Node {m['node']}; Python {m['python']}, onnxruntime {m['onnxruntime']} (1 thread)",
           f"- Run: {doc['date']}, {doc['seconds']:.0f} s in all; load average (1 min) {m['load_start']:.1f} at the "
           f"start, {m['load_end']:.1f} at the end (the benchmark's own browser and server count)"
           + (" (other work shared the cores at the start: spreads are wider)" if m["load_start"] >= 1.0 else ""), "",
           "## Targets", ""]
    rows = []
    for t in doc["targets"]:
        shown = [f"{i['what']}: {i['value']:.2f}" if isinstance(i["value"], (int, float)) else i["what"]
                 for i in t["items"] if i["met"] is False]
        rows.append([t["target"], t["limit"], _met(t["met"]), "; ".join(shown) or "—"])
    out += [table(["target", "limit", "result", "misses"], rows), ""]

    out += ["## End-to-end prediction", "",
            "Round trip: from the page's request to the result on the page (the predictor worker's "
            "`predict`: noise, graphs, stopping, smoothness, interpolation, plus the messages). Worker: "
            "`predict` inside the worker. Native: the Python predictor on native onnxruntime.", ""]
    rows = []
    for c in br["cases"]:
        n = nat_cases[c["id"]]
        rt, wk, nv = spread(c["round_trip_ms"]), spread(c["worker_ms"]), spread(n["ms"])
        rows.append([c["id"], fmt_ms(rt), fmt_ms(wk), fmt_ms(nv), f"{wk['median'] / nv['median']:.1f}"])
    out += [table(["case", "browser round trip", "browser worker", "native", "worker/native"], rows), ""]
    rows = [[mid, fmt_ms(spread(v["round_trip_ms"])), f"{nat['load_ms'][mid]:.0f}"] for mid, v in br["load"].items()]
    out += ["Session load (fetch and create every graph's session, fresh page; native: session creation only):", "",
            table(["model", "browser", "native"], rows), ""]

    out += ["## Graphs alone", "",
            "Each graph the cases called, at each batch, on the inputs the predictor gave it "
            "(bench page's graph worker; native: one onnxruntime session, one thread). The browser's clock ticks in "
            "0.1 ms steps (no cross-origin isolation), so each browser sample is the mean of enough back-to-back runs "
            "to last 5 ms. `browser`: the graph alone in a fresh worker (after a 2-node opener session: Chromium "
            "runs a worker's first session slower for its life), warmed on itself for 1 s; the ratio uses it. "
            "`shared worker`: every graph in one worker in this table's order, as on a page where the user has "
            "switched models; V8 optimises onnxruntime's wasm with call feedback from the graphs run before, "
            "so this column depends on the order.", ""]
    rows = []
    for g in br["graphs"]:
        n = nat_graphs[g["id"]]
        facts = sizes[n["model"]]["graphs"][n["role"]]
        if g.get("ms"):
            b = spread(g["ms"])
            sh = g.get("shared_ms")
            rows.append([g["id"], str(facts["nodes"]), fmt_ms(b), fmt_ms(spread(sh)) if sh else "—",
                         fmt_ms(spread(n["native_ms"])), f"{ratio(g['ms'], n['native_ms']):.1f}",
                         f"{spread(sh)['median'] / b['median']:.2f}" if sh else "—"])
        else:
            rows.append([g["id"], str(facts["nodes"]), f"error: {g.get('error')}", "—", fmt_ms(spread(n["native_ms"])), "—", "—"])
    out += [table(["graph/batch", "nodes", "browser", "shared worker", "native", "ratio", "shared/fresh"], rows), ""]
    line = order_effect(br["graphs"])
    if line:
        out += [line, ""]

    out += ["### Attempts on the ratio", "",
            "At the K=10 batch: the served graph with lower session optimisation levels in the browser, "
            "and two rewritten graphs (onnxruntime's offline 'extended' optimisation saved as ONNX; "
            "dynamic int8 weights), each timed on both sides. `rel. diff`: largest output difference "
            "against the served graph, relative to the output's RMS (native).", ""]
    rows = []
    for g in br["graphs"]:
        n = nat_graphs[g["id"]]
        if not g.get("variants"):
            continue
        nodes = sizes[n["model"]]["graphs"][n["role"]]["nodes"]
        served = {"name": f"served graph, session optimisation '{m.get('session_optimization', 'all')}' (the site)", "ms": g.get("ms"), "load_ms": g.get("load_ms"),
                  "error": g.get("error")}
        nvar = {v["name"]: v for v in n["variants"]} | {served["name"]: {"native_ms": n["native_ms"], "nodes": nodes, "rel_diff": 0.0}}
        for v in [served] + g["variants"]:
            nv = nvar.get(v["name"], {})
            b = fmt_ms(spread(v["ms"])) if v.get("ms") else f"error: {v.get('error') or nv.get('error')}"
            nat_ms = nv.get("native_ms")
            rows.append([g["id"], v["name"], str(nv.get("nodes", "—")),
                         f"{v['load_ms']:.0f}" if v.get("load_ms") is not None else "—", b,
                         fmt_ms(spread(nat_ms)) if nat_ms else "—",
                         f"{ratio(v['ms'], nat_ms):.1f}" if nat_ms and v.get("ms") else "—",
                         f"{nv['rel_diff']:.1e}" if "rel_diff" in nv else "—"])
        shown = {v["name"] for v in g["variants"]}
        for v in n["variants"]:  # attempts that failed natively never reached the browser
            if v["name"] not in shown and "error" in v:
                rows.append([g["id"], v["name"], "—", "—", "—", f"error: {v['error'][:160]}", "—", "—"])
    out += [table(["graph/batch", "attempt", "nodes", "browser session load", "browser run", "native run", "ratio",
                   "rel. diff"], rows), ""]

    def num(v, digits=0):
        return "—" if v is None else f"{v:.{digits}f}"
    out += ["## Page", "",
            "Futures drawn: from navigation start to the first frame the stage drew with the first futures in it "
            "(the page's `mf:futures-drawn` mark, set once the stage has rendered the new tracks), what the user "
            "waits for. Done: `data-predict-status=done`, once the side panel's list, read-out and statuses have "
            "followed (two frames later). Each on the main page with a fresh profile (nothing cached; the browser "
            "open on about:blank for 2 s first, so its own start-up work is not timed): the first view (no query: "
            "the stage's model at the first view's K) and each model by link (`?model=ID`, its default controls). "
            "Frame gaps: intervals between `requestAnimationFrame` callbacks on the main page while a K=50 "
            "prediction runs (Predict pressed to result shown and drawn). Frame rate: `requestAnimationFrame` "
            f"callbacks per second over {br.get('fps_seconds', 0):.0f} s with the K=50 futures playing.", ""]
    rows = [[n["model"] + (f" ({n['shown_model']})" if n.get("shown_model") and n["shown_model"] != n["model"] else ""),
             fmt_ms(spread(n["futures_drawn_ms"])) if n.get("futures_drawn_ms") else f"error: {n.get('error')}",
             fmt_ms(spread(n["first_prediction_ms"])) if n.get("first_prediction_ms") else "—",
             ", ".join(sorted({u.rsplit('/', 1)[-1] for u in n["onnx_requests"]["page"]})) or "—",
             str(len(n["onnx_requests"]["service_worker"]))] for n in br["navigation"]]
    out += [table(["view", "futures drawn (ms)", "done (ms)", "ONNX fetched by the page",
                   "ONNX fetched by the service worker"], rows), "",
            "Requests are counted until the first prediction is shown. The page fetches only the chosen model's "
            "files; the offline service worker (web/src/embed/offline.ts registers it after the first prediction) "
            "then precaches the whole site, every model included, in the background.", ""]
    # Files: when their response ended; "model-loaded" and the rest: the page's performance marks.
    if any(n.get("timeline_ms") for n in br["navigation"]):
        out += ["Where the time to the first futures goes (ms after navigation start, medians; a file counts when its "
                "response has ended, whether the page or the predictor worker fetched it). app-start: the widget's "
                "code runs (the page's script is loaded and parsed); app-built: its synchronous start-up (stage, panels) is done; manifest-in, clip-in: the page has them; "
                "wasm fetched: onnxruntime's wasm, fetched by the worker when it starts onnxruntime; model-loaded: "
                "the worker has every session of the model; predict-asked: the page has the clip and the model and "
                "sends the prediction; prediction-received: the futures are back on the page; show-start, tracks-set: the "
                "page starts putting them on stage and has given the stage its tracks; futures-drawn: the "
                "stage has drawn them; prediction-shown: the panel has followed.", ""]
        out += startup_table(startup(br["navigation"])) + [""]
    out += startup_changes(doc)
    rows = [[f["model"], str(f["k"]), num(f.get("idle_max_gap_ms")),
             num(gap_percentile(f.get("gaps_ms"))) if f.get("error") is None else f"error: {f['error']}",
             num(f.get("max_gap_ms")) if f.get("error") is None else "—",
             num(f.get("prediction_ms")), num(f.get("fps"), 1), num(f.get("playing_idle_max_gap_ms")),
             num(f.get("playing_max_gap_ms")), num(f.get("playing_prediction_ms"))] for f in br["frames"]]
    out += [table(["model", "K", "still: longest gap idle (ms)", f"still: p{FRAME_GAP_PERCENTILE:.0f} gap, Predict to shown (ms)",
                   "still: longest gap, Predict to shown (ms)",
                   "still: Predict to shown (ms)", "fps, K=50 playing", "playing: longest gap idle (ms)",
                   "playing: longest gap, Predict to shown (ms)", "playing: Predict to shown (ms)"], rows), "",
            "\"Still\": playback paused before Predict (the target is checked on this: what the prediction costs the "
            "main thread). \"Playing\": the same with the previous K=50 futures playing; there the frames are long "
            "before Predict is pressed (see the frame rate).", ""]
    out += ["## Sizes", "", f"`dist/`: {doc['dist']['bytes'] / 1e6:.2f} MB raw, {doc['dist']['gzip_bytes'] / 1e6:.2f} MB "
            f"gzipped ({doc['dist']['files']} files; each file gzipped alone, level 9). Largest:", ""]
    out += [table(["file", "raw (MB)", "gzipped (MB)"], [[f["file"], f"{f['bytes'] / 1e6:.2f}", f"{f['gzip_bytes'] / 1e6:.2f}"]
                                                      for f in doc["dist"]["largest"]]), ""]
    rows = []
    for s in doc["sizes"]:
        for role, g in s["graphs"].items():
            rows.append([s["model"], g["file"], f"{g['bytes'] / 1e3:.0f}", f"{g['gzip_bytes'] / 1e3:.0f}", f"{g['params']:,}",
                         str(g["nodes"])])
        cap = f"cap {s['cap_mb']} MB" if s["cap_mb"] is not None else "no cap"
        rows.append([s["model"], f"**all ({cap})**", f"{s['onnx_bytes'] / 1e3:.0f}", f"{s['onnx_gzip_bytes'] / 1e3:.0f}",
                     f"{s['params']:,}", ""])
    out += [table(["model", "ONNX file", "kB", "kB gzipped", "parameters", "nodes"], rows), ""]

    if doc.get("earlier"):
        out += ["## Changes made from this benchmark", "",
                "Each change to the served graphs, measured: an earlier run's medians (bench/earlier.json) → this run's.", ""]
        out += changes(doc)

    missed = [t for t in doc["targets"] if t["met"] is False]
    if missed:
        out += ["## Missed targets: profile", ""]
        for t in missed:
            out += [f"### {t['target']} ({t['limit']})", ""]
            for i in t["items"]:
                if i["met"] is False:
                    v = f": {i['value']:.2f}" if isinstance(i["value"], (int, float)) else ""
                    out.append(f"- {i['what']}{v}")
            out.append("")
        out += ["What the numbers say:", ""] + [f"- {line}" for line in analysis(doc)] + [""]
    out += ["## Profile", ""]
    out += ["Node counts and op types of every served graph (what onnxruntime-web pays per node):", ""]
    rows = [[s["model"], role, str(g["nodes"]), ", ".join(f"{op} {n}" for op, n in list(g["ops"].items())[:8])]
            for s in doc["sizes"] for role, g in s["graphs"].items()]
    out += [table(["model", "graph", "nodes", "op types (most frequent first)"], rows), ""]
    if doc.get("profiles"):
        out += ["Browser profile (onnxruntime-web per-node events, mean of 3 runs per graph at the K=10 batch; time per op "
                "type). Profiling adds a cost to every node, so the run times here are longer than above; the "
                "split over op types is what it shows.", ""]
        rows = [[p["graph"], ", ".join(f"{op} {ms:.2f} ms" for op, ms in list(p["op_ms"].items())[:6]),
                 f"{p['node_ms']:.2f}", f"{p['run_ms']:.2f}"] for p in doc["profiles"]]
        out += [table(["graph/batch", "op types by time", "sum of node times (ms)", "run (ms)"], rows), ""]
    if doc.get("notes"):
        out += ["## Notes", ""] + [f"- {n}" for n in doc["notes"]] + [""]
    return "\n".join(out)
