"""Runs a model's ONNX graphs with native onnxruntime (one thread), sessions created on first use.

precision="float64" runs the same graphs widened to float64 (export/onnx/float64.py): the
reference against which `python -m export vectors` measures float32 error.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from ..onnx.export import session

PRECISIONS = ("float32", "float64")


class GraphRunner:
    def __init__(self, entry: dict, models_dir: Path, precision: str = "float32"):
        if precision not in PRECISIONS:
            raise ValueError(f"precision must be one of {PRECISIONS}, got {precision!r}")
        self.entry, self.models_dir, self.precision = entry, Path(models_dir), precision
        self._sessions = {}

    def run(self, role: str, feeds: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
        if role not in self._sessions:
            spec = self.entry["graphs"].get(role)
            if spec is None:
                raise ValueError(f"model {self.entry['id']} has no graph {role!r}")
            path = self.models_dir / spec["file"]
            if not path.exists():
                raise FileNotFoundError(f"{path}: model file missing; run `make models`")
            if self.precision == "float64":
                from ..onnx.float64 import Float64Session
                self._sessions[role] = (Float64Session(path), spec)
            else:
                self._sessions[role] = (session(path), spec)
        sess, spec = self._sessions[role]
        out = sess.run([o["name"] for o in spec["outputs"]], feeds)
        return {o["name"]: v for o, v in zip(spec["outputs"], out)}
