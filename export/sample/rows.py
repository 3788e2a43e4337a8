"""Graph calls whose every row is what it would be at any other batch size (issue 30 item 6).

A sample's future must not depend on how many samples run beside it. Native onnxruntime takes
another path for a batch of one in WAT Transformer's prior: its history_features output comes out
up to 2.4e-7 off the batched rows (the means and log-variances the predictor reads were equal on
every held-out window tried; every graph gave equal rows at batch 2..50). Nesting should not rest
on which outputs such a path touches, so a batch of one runs as two equal rows and keeps the first. onnxruntime-web's wasm kernels
give the same rows at batch 1..50 for every served graph, so web/src/predictor has no twin of this
(tests/web/nesting.test.ts checks the samples nest there).
"""
from __future__ import annotations

import numpy as np


def run_rows(runner, role: str, feeds: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
    """runner.run(role, feeds) for feeds that share a leading batch axis."""
    if any(len(v) != 1 for v in feeds.values()):
        return runner.run(role, feeds)
    out = runner.run(role, {n: np.concatenate([v, v]) for n, v in feeds.items()})
    return {n: v[:1] for n, v in out.items()}
