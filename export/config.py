"""Model configs (configs/*.json) and the model hash that detects stale committed models."""
from __future__ import annotations

import ast
import copy
import hashlib
import json
from pathlib import Path

from .paths import CONFIGS_DIR, ROOT

EXPORT_DIR = ROOT / "export"
# What a model computes depends on its method's module, the shared training/export path, and what
# those import inside export/. Hashing that import closure (not every file) keeps an edit to, say,
# the evaluation from marking every committed model stale; the data readers (data/bvh.py among them)
# are in the closure, since the pipeline converts the data. Each file is hashed as its syntax tree
# without docstrings (normalised_code), so comments, docstrings and formatting never stale a model.
_PIPELINE = "export.pipeline"
# The method registry maps names to classes; adding a method there changes no existing model.
_NOT_HASHED = {"export.methods"}

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
    if "extends" in cfg:
        # An ablation names the config it changes and only what it changes, so it follows the served
        # config (its data, budget and sizes) instead of drifting from a copy.
        unknown = set(cfg) - {"extends", "id", "label", "description", "changes"}
        if unknown:
            raise ValueError(f"{path}: a config that extends another has only id, label, description and "
                             f"changes, not {sorted(unknown)}")
        base = load_config(CONFIGS_DIR / cfg["extends"])
        own = {k: cfg[k] for k in ("id", "label", "description") if k in cfg}
        cfg = {**override(base, **cfg.get("changes", {})), **own}
    for key in ("id", "method", "history_frames", "future_frames"):
        if key not in cfg:
            raise ValueError(f"{path}: config is missing '{key}'")
    return cfg


def site_configs() -> list[dict]:
    site = json.loads((CONFIGS_DIR / "site.json").read_text())
    return [load_config(CONFIGS_DIR / name) for name in site["models"]]


def _module_file(module: str) -> Path | None:
    parts = module.split(".")[1:]
    if not parts:
        return EXPORT_DIR / "__init__.py"
    rel = Path(*parts)
    for cand in (EXPORT_DIR / rel.with_suffix(".py"), EXPORT_DIR / rel / "__init__.py"):
        if cand.is_file():
            return cand
    return None


def _imports(path: Path, module: str) -> set[str]:
    """export.* modules imported by one file (absolute or relative, top level or inside functions)."""
    package = module if path.name == "__init__.py" else module.rpartition(".")[0]
    found = set()
    for node in ast.walk(ast.parse(path.read_text(), str(path))):
        if isinstance(node, ast.Import):
            found |= {a.name for a in node.names if a.name.split(".")[0] == "export"}
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")[: len(package.split(".")) - node.level + 1]
                base = ".".join(base + ([node.module] if node.module else []))
            else:
                base = node.module or ""
            if base.split(".")[0] != "export":
                continue
            found.add(base)
            found |= {f"{base}.{a.name}" for a in node.names}   # `from . import x` may name a module
    return found


def code_files(method_module: str) -> list[Path]:
    """The files of export/ that the method's training and export path imports, transitively."""
    seen: dict[str, Path] = {}
    todo = ["export", _PIPELINE, method_module]
    while todo:
        mod = todo.pop()
        if mod in seen:
            continue
        path = _module_file(mod)
        if path is None:
            continue
        seen[mod] = path
        if mod in _NOT_HASHED:
            continue
        parts = mod.split(".")
        todo += [".".join(parts[:i]) for i in range(1, len(parts))]   # parent packages run too
        todo += sorted(_imports(path, mod))
    return sorted({p for m, p in seen.items() if m not in _NOT_HASHED})


def normalised_code(source: str, name: str = "<code>") -> str:
    """What a file runs: its syntax tree without docstrings or positions. Comments, docstrings, blank
    lines, line breaks and quote styles leave it unchanged; any change to what executes does not."""
    tree = ast.parse(source, name)
    for node in ast.walk(tree):
        body = getattr(node, "body", None)
        if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)) and body \
                and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant) \
                and isinstance(body[0].value.value, str):
            node.body = body[1:] or [ast.Pass()]
    return ast.dump(tree, annotate_fields=False, include_attributes=False)


def code_hash(method_module: str) -> str:
    h = hashlib.sha256()
    for path in code_files(method_module):
        code = normalised_code(path.read_text(), str(path))
        h.update(str(path.relative_to(EXPORT_DIR)).encode() + b"\0" + code.encode() + b"\0")
    return h.hexdigest()


def model_hash(cfg: dict, data_hash: str) -> str:
    h = hashlib.sha256()
    h.update(json.dumps(cfg, sort_keys=True).encode() + b"\0")
    h.update(data_hash.encode() + b"\0")
    from .methods import METHODS   # late: methods import this module's siblings
    if cfg["method"] not in METHODS:
        raise ValueError(f"unknown method {cfg['method']!r}; known: {sorted(METHODS)}")
    h.update(code_hash(METHODS[cfg["method"]].split(":")[0]).encode())
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
