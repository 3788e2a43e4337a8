"""WAT's shared test vectors: DCT smoothness (Eq. 4) and variance stopping (Eq. 8), Python -> vitest, floats within
each file's derived tolerance (export/tolerance.py)."""
from __future__ import annotations

import numpy as np

from .ops.dct import dct_basis
from .ops.dct_smoothness import smoothness
from .ops.variance_stop import first_stop, variance_curve


def _clip(name: str) -> np.ndarray:
    from .data.clip_json import read_clip
    from .paths import CLIPS_DIR
    return read_clip(CLIPS_DIR / f"{name}.json").positions.astype(np.float64).round(6)


def dct_smoothness_vector() -> dict:
    rng = np.random.default_rng(5)
    walk, backflip, punch = _clip("deepmimic_walk"), _clip("deepmimic_backflip"), _clip("deepmimic_punch")
    cases = [
        ("walk, real motion", walk[0:10], walk[10:20], 5),
        ("backflip, real motion", backflip[20:30], backflip[30:40], 5),
        ("hard cut walk -> punch", walk[0:10], punch[30:40], 5),
        ("held pose", walk[5:6].repeat(10, 0), walk[5:6].repeat(10, 0), 5),
        ("noise, L = 4, M = 3", rng.normal(size=(4, 18, 3)).round(6), rng.normal(size=(4, 18, 3)).round(6), 3),
    ]
    return {"about": "Eq. 4 over the last L history and first L predicted poses with the first M orthonormal "
                     "DCT-II bases (square metres); also the basis itself.",
            "basis": {"frames": 20, "bases": 5, "d": dct_basis(20, 5).tolist()},
            "cases": [{"name": name, "l": len(tail), "m": m, "tail": tail.tolist(), "head": head.tolist(),
                       "smoothness": smoothness(tail, head, m)} for name, tail, head, m in cases]}


def variance_stop_vector() -> dict:
    walk, kick = _clip("deepmimic_walk"), _clip("deepmimic_kick")
    held = np.concatenate([walk[:30], walk[29:30].repeat(20, 0)])           # moves 30 frames, then holds
    settles = np.concatenate([kick[:40], kick[39:40].repeat(10, 0)])
    cases = [
        ("walk then hold", held, 5, 0.01, 10),
        ("walk then hold, T_min after the hold starts", held, 5, 0.01, 35),
        ("never stops (threshold too low)", walk[:38], 5, 1e-4, 10),
        ("stops at T_min (threshold high)", walk[:38], 5, 10.0, 10),
        ("kick settling, Q = 3", settles, 3, 0.02, 8),
    ]
    out = []
    for name, frames, q, delta, t_min in cases:
        curve = variance_curve(frames, q)
        stop = first_stop(curve, delta, t_min, len(frames))
        out.append({"name": name, "q": q, "delta": delta, "min_frames": t_min, "max_frames": len(frames),
                    "frames": frames.tolist(), "curve": curve.tolist(), "length": stop.length,
                    "stopped": stop.stopped, "margin": stop.margin})
    return {"about": "Eq. 8 curve and the stop rule: length and stopped exactly, the curve and the margin as floats.",
            "cases": out}


# (clip, first history frame, action sequence): a held-out walk into three actions, and a held-out
# ballet take continued as its own action.
E2E_CASES = [("cmu_10_04", 3, ["walk", "punch", "jump"]), ("cmu_49_09", 90, ["dance"])]


def wat_e2e_cases(entry: dict, predictor, keeps, sequences=None) -> list[dict]:
    """End-to-end cases for a served WAT model: K = 2 samples whose every stop test keeps its margin
    (`keeps(prediction, history, request)`: the first such seed from 7 on), with their segments for the
    TypeScript check. (K = 2: every segment of every sample must keep the margin, and the curves of
    Eq. 8 approach delta slowly, so larger K leaves few seeds.)"""
    from .data.clip_json import read_clip
    from .paths import CLIPS_DIR
    from .sample.request import Request
    n = entry["params"]["history_frames"]
    cases = []
    for clip, start, actions in sequences or E2E_CASES:
        history = read_clip(CLIPS_DIR / f"{clip}.json").positions[start:start + n].astype(np.float32)
        for seed in range(7, 3000):
            req = Request(k=2, seed=seed, actions=list(actions))
            pred = predictor.predict(history, req)
            if keeps(pred, history, req):
                break
        else:
            raise ValueError(f"no seed in 7..2999 gives {clip}@{start} stop decisions that keep their margins")
        cases.append(wat_record(entry, clip, start, history, req, pred))
    return cases


def wat_record(entry: dict, clip: str, start: int, history: np.ndarray, req, pred) -> dict:
    """What a WAT case stores of one prediction (also what a replay of the case is compared on)."""
    from .vectors_record import record
    return record(entry, clip, start, history, req, pred,
                  segments=[[{k: sg[k] for k in ("start", "length", "action", "stopped")} for sg in s["segments"]]
                            for s in pred.samples],
                  min_margin=min(pred.margins))
