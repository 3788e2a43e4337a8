"""Model configs (configs/*.json) and the model hash that detects stale committed models."""
from __future__ import annotations

import copy
import hashlib
import json
from pathlib import Path

from .paths import CONFIGS_DIR, ROOT

EXPORT_DIR = ROOT / "export"
# Evaluation does not change what a model computes, so editing it must not mark models stale.
_NOT_HASHED = ("eval",)


def load_config(path: str | Path) -> dict:
    path = Path(path)
    if not path.is_absolute() and not path.exists():
        path = CONFIGS_DIR / path
    try:
        cfg = json.loads(path.read_text())
    except OSError as e:
        raise FileNotFoundError(f"{path}: config not found") from e
    except json.JSONDecodeError as e:
        raise ValueError(f"{path}: not valid JSON ({e})") from e
    for key in ("id", "method", "history_frames", "future_frames"):
        if key not in cfg:
            raise ValueError(f"{path}: config is missing '{key}'")
    return cfg


def site_configs() -> list[dict]:
    site = json.loads((CONFIGS_DIR / "site.json").read_text())
    return [load_config(CONFIGS_DIR / name) for name in site["models"]]


def code_hash() -> str:
    h = hashlib.sha256()
    for path in sorted(EXPORT_DIR.rglob("*.py")):
        rel = path.relative_to(EXPORT_DIR)
        if rel.parts[0] in _NOT_HASHED:
            continue
        h.update(str(rel).encode() + b"\0" + path.read_bytes() + b"\0")
    return h.hexdigest()


def model_hash(cfg: dict, data_hash: str) -> str:
    h = hashlib.sha256()
    h.update(json.dumps(cfg, sort_keys=True).encode() + b"\0")
    h.update(data_hash.encode() + b"\0")
    h.update(code_hash().encode())
    return "sha256:" + h.hexdigest()


def override(cfg: dict, **changes) -> dict:
    """A copy with dotted keys replaced, e.g. override(cfg, **{"train.steps": 5})."""
    out = copy.deepcopy(cfg)
    for dotted, value in changes.items():
        node = out
        *parents, last = dotted.split(".")
        for p in parents:
            node = node.setdefault(p, {})
        node[last] = value
    return out
