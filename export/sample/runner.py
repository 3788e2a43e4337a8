"""Runs a model's ONNX graphs with native onnxruntime (one thread), sessions created on first use."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from ..onnx.export import session


class GraphRunner:
    def __init__(self, entry: dict, models_dir: Path):
        self.entry, self.models_dir = entry, Path(models_dir)
        self._sessions = {}

    def run(self, role: str, feeds: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
        if role not in self._sessions:
            spec = self.entry["graphs"].get(role)
            if spec is None:
                raise ValueError(f"model {self.entry['id']} has no graph {role!r}")
            path = self.models_dir / spec["file"]
            if not path.exists():
                raise FileNotFoundError(f"{path}: model file missing; run `make models`")
            self._sessions[role] = (session(path), spec)
        sess, spec = self._sessions[role]
        out = sess.run([o["name"] for o in spec["outputs"]], feeds)
        return {o["name"]: v for o, v in zip(spec["outputs"], out)}
