"""One end-to-end case as the vector stores it: the inputs a replay needs (model, history, request)
and what the prediction gave. Every method's case adds its own exact fields (segments, labels)."""
from __future__ import annotations

import numpy as np


def float32_list(values: np.ndarray) -> list:
    """Values as float32 (what the predictors return), written exactly: no decimal rounding that a
    last-bit difference between machines could flip."""
    return np.asarray(values, dtype=np.float32).astype(np.float64).tolist()


def record(entry: dict, clip: str, start: int, history: np.ndarray, req, pred, **extra) -> dict:
    return {"model": entry["id"], "model_hash": entry["hash"], "clip": clip, "start": start,
            "history": float32_list(history), "request": req.to_json(), "lengths": pred.lengths.tolist(),
            "warnings": [w["quantity"] for w in pred.warnings],
            "cuts": [s["cut"]["frame"] if "cut" in s else None for s in pred.samples],
            **extra, "futures": float32_list(pred.futures)}
