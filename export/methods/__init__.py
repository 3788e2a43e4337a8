"""The registry of methods by the manifest's `method` name (imported on first use)."""
from __future__ import annotations

import importlib

from .base import Method

METHODS: dict[str, str] = {
    "zero_velocity": "export.methods.baselines:ZeroVelocityMethod",
    "regression": "export.methods.baselines:RegressionMethod",
    "wat": "export.methods.wat:WatMethod",
    "wat_transformer": "export.methods.wat_transformer:WatTransformerMethod",
    "lcp_vae": "export.methods.lcp_vae:LcpVaeMethod",
    "keyposes": "export.methods.keyposes:KeyposesMethod",
}


def _load(path: str):
    module, name = path.split(":")
    return getattr(importlib.import_module(module), name)


def method_for(cfg: dict) -> Method:
    if cfg["method"] not in METHODS:
        raise ValueError(f"unknown method {cfg['method']!r}; known: {sorted(METHODS)}")
    return _load(METHODS[cfg["method"]])(cfg)
