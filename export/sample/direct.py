"""Predictor for the deterministic baselines: history -> one fixed-horizon graph call, recursively."""
from __future__ import annotations

import numpy as np

from .canonical import from_canonical, to_canonical
from .predictor import Predictor
from .request import Prediction, Request, horizon_frames


class DirectPredictor(Predictor):
    def _predict(self, history: np.ndarray, req: Request) -> Prediction:
        n = self.params["history_frames"]
        step = self.params["future_frames"]
        horizon = horizon_frames(req, self.entry, self.manifest["fps"])
        frames = history[-n:].astype(np.float32)
        out = []
        while sum(len(o) for o in out) < horizon:
            # Each call sees its own history facing +z (the recursion re-canonicalises).
            canon, placement = to_canonical(frames[-n:])
            future = self.runner.run("predict", {"history": canon[None]})["future"][0]
            future = from_canonical(future, placement)
            out.append(future)
            frames = np.concatenate([frames, future])
        future = np.concatenate(out)[:horizon]
        return Prediction(future[None].astype(np.float32), np.array([horizon]),
                          [{"length": horizon, "stopped": False, "segments": [{"start": 0, "length": horizon}]}])
