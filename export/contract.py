"""The shared contract: JSON schemas in contract/, checked here and by web/src/contract/.

Errors name the file and the field, so a user sees which file is broken and why.
"""
from __future__ import annotations

import json
import math
from functools import lru_cache
from pathlib import Path
from typing import Any

from jsonschema import Draft202012Validator
from referencing import Registry, Resource

from .paths import CONTRACT_DIR

SCHEMAS = ("defs", "clip", "clip-index", "manifest")


class ContractError(ValueError):
    """A file that breaks the contract; the message names the file and the problem."""


@lru_cache(maxsize=None)
def _registry() -> Registry:
    resources = []
    for name in SCHEMAS:
        doc = json.loads((CONTRACT_DIR / f"{name}.schema.json").read_text())
        resources.append((doc["$id"], Resource.from_contents(doc)))
    return Registry().with_resources(resources)


@lru_cache(maxsize=None)
def _validator(name: str) -> Draft202012Validator:
    schema = json.loads((CONTRACT_DIR / f"{name}.schema.json").read_text())
    return Draft202012Validator(schema, registry=_registry())


def _path(parts) -> str:
    return "/".join(str(p) for p in parts) or "(top level)"


def validate(doc: Any, schema: str, where: str | Path) -> None:
    """Raise ContractError naming `where` and the first offending field."""
    errors = sorted(_validator(schema).iter_errors(doc), key=lambda e: list(e.absolute_path))
    if errors:
        e = errors[0]
        more = f" (and {len(errors) - 1} more problems)" if len(errors) > 1 else ""
        raise ContractError(f"{where}: field {_path(e.absolute_path)}: {e.message}{more}")
    if schema in ("clip", "clip-index", "manifest"):
        _check_skeleton(doc["skeleton"], where)
    if schema == "clip":
        _check_clip(doc, where)
    if schema == "manifest":
        _check_manifest(doc, where)


def _check_skeleton(skel: dict, where) -> None:
    joints, parents = skel["joints"], skel["parents"]
    if len(parents) != len(joints):
        raise ContractError(f"{where}: field skeleton/parents: {len(parents)} parents for {len(joints)} joints")
    for j, p in enumerate(parents):
        if p >= j or (p < 0 and j != 0):
            raise ContractError(f"{where}: field skeleton/parents/{j}: parent {p} must precede joint {j} "
                                "(only joint 0 is the root)")
    if "offsets" in skel and len(skel["offsets"]) != len(joints):
        raise ContractError(f"{where}: field skeleton/offsets: {len(skel['offsets'])} offsets for {len(joints)} joints")


def _check_ranges(ranges, frames: int, field: str, where) -> None:
    for i, (a, b) in enumerate(ranges):
        if not 0 <= a < b <= frames:
            raise ContractError(f"{where}: field {field}/{i}: range [{a}, {b}) is empty or outside 0..{frames}")


def _check_clip(doc: dict, where) -> None:
    joints = len(doc["skeleton"]["joints"])
    frames = len(doc["positions"])
    for f, frame in enumerate(doc["positions"]):
        if len(frame) != joints:
            raise ContractError(f"{where}: field positions/{f}: {len(frame)} joints, the skeleton has {joints}")
        for j, xyz in enumerate(frame):
            if not all(math.isfinite(v) for v in xyz):
                raise ContractError(f"{where}: field positions/{f}/{j}: not a finite number (NaN or infinity)")
    _check_ranges(doc["split"]["train"], frames, "split/train", where)
    _check_ranges(doc["split"]["test"], frames, "split/test", where)


def _check_manifest(doc: dict, where) -> None:
    for i, model in enumerate(doc["models"]):
        p = model["params"]
        for key in ("stop",):
            if key in p and p[key]["min_frames"] > p["future_frames"]:
                raise ContractError(f"{where}: field models/{i}/params/stop/min_frames: larger than future_frames")


def load_json(path: Path, schema: str) -> dict:
    """Read and validate a contract file; every failure is a ContractError naming the file."""
    path = Path(path)
    try:
        text = path.read_text()
    except OSError as e:
        raise ContractError(f"{path}: cannot be read ({e.strerror or e})") from e
    try:
        # NaN and Infinity are not JSON; refuse them here rather than let them reach a model.
        doc = json.loads(text, parse_constant=_reject_constant)
    except (json.JSONDecodeError, ValueError) as e:
        raise ContractError(f"{path}: not valid JSON ({e})") from e
    validate(doc, schema, path)
    return doc


def _reject_constant(name: str):
    raise ValueError(f"{name} is not a number JSON allows")
