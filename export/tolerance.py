"""Comparing a committed number with one computed on another machine: what is exact stays exact,
every float gets a tolerance derived from float32-vs-float64 error.

torch, onnxruntime and BLAS pick float32 kernels by CPU (plain, AVX2, AVX-512), so a float written
on one machine and recomputed on another may differ in its last bits, and a 90-step rollout grows
that difference. The rule, used by `python -m export vectors`, pytest and vitest alike:
- Exact things compare exactly: integers, booleans, strings, keys, lengths (so shapes), labels,
  stop frames.
- Each float family measures its largest float32-vs-float64 gap when it is written: the same
  model evaluated in float64 (the graphs converted to double, export/onnx/float64.py; never below
  half a float32 step at the largest value, since predictors return float32), or, for arithmetic
  already done in float64 (ops on committed clips), the gap between the result and its float32
  rounding, the smallest error any float32 evaluation has.
- The tolerance is TOLERANCE_FACTOR times that gap, rounded up to two significant digits: between
  10x and 100x the gap, as contract/README.md states. Cross-machine differences are of the order of
  the gap; a real change (a retrained or perturbed weight) is far above 100x it.
"""
from __future__ import annotations

import math

import numpy as np

TOLERANCE_FACTOR = 30.0
RULE = (f"exact: integers, booleans, strings, keys and lengths; floats: |committed - computed| <= tolerance, "
        f"where tolerance = {TOLERANCE_FACTOR:g} x the family's largest float32-vs-float64 gap (rounded up to 2 "
        "significant digits), measured when the file was written")


def derive(gap: float) -> float:
    """The tolerance for a measured gap: TOLERANCE_FACTOR x gap, rounded up to 2 significant digits."""
    if not (math.isfinite(gap) and gap >= 0):
        raise ValueError(f"a float32-vs-float64 gap must be finite and non-negative, got {gap}")
    if gap == 0:
        return 0.0
    raw = TOLERANCE_FACTOR * gap
    scale = 10.0 ** (math.floor(math.log10(raw)) - 1)
    return math.ceil(raw / scale - 1e-9) * scale


def first_difference(a, b, tol: float, where: str = "") -> str | None:
    """Where two JSON documents differ: structure, integers, booleans and strings exactly, floats
    beyond `tol` (absolute). None when they agree."""
    if isinstance(a, dict) and isinstance(b, dict):
        if a.keys() != b.keys():
            return f"{where}: keys {sorted(a.keys() ^ b.keys())}"
        return next((d for k in a if (d := first_difference(a[k], b[k], tol, f"{where}/{k}"))), None)
    if isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            return f"{where}: length {len(a)} != {len(b)}"
        return next((d for i, (x, y) in enumerate(zip(a, b)) if (d := first_difference(x, y, tol, f"{where}/{i}"))),
                    None)
    if isinstance(a, float) or isinstance(b, float):
        both = all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in (a, b))
        if both and math.isfinite(a) and math.isfinite(b) and abs(a - b) <= tol:
            return None
        if both and a == b:     # the same infinity
            return None
        return f"{where}: {a!r} != {b!r} (tolerance {tol:.3g})"
    return None if (a == b and type(a) is type(b)) else f"{where}: {a!r} != {b!r}"


def float_gap(a, b, where: str = "") -> float:
    """Largest |a - b| over the floats of two documents of the same structure (which must agree
    exactly everywhere else: a flipped decision is not a float gap)."""
    diff = first_difference(a, b, math.inf, where)
    if diff is not None:
        raise ValueError(f"the float64 evaluation made another decision than the float32 one: {diff}")
    return max((abs(x - y) for x, y in zip(_floats(a), _floats(b))), default=0.0)


def float32_floor(doc) -> float:
    """Half a float32 step at the document's largest magnitude: results returned as float32 (every
    predictor's) can differ by one rounding when the float64 arithmetic before it (a rotation)
    differs in its last bit, so no gap is taken below this."""
    return max((abs(v) for v in _floats(doc) if math.isfinite(v)), default=0.0) * 2.0 ** -24


def rounding_gap(doc) -> float:
    """Largest |v - float32(v)| over a document's floats: what a float32 evaluation of float64
    arithmetic at least loses."""
    values = np.asarray(list(_floats(doc)), dtype=np.float64)
    values = values[np.isfinite(values)]
    return float(np.abs(values - values.astype(np.float32).astype(np.float64)).max()) if len(values) else 0.0


def _floats(doc):
    if isinstance(doc, dict):
        for v in doc.values():
            yield from _floats(v)
    elif isinstance(doc, list):
        for v in doc:
            yield from _floats(v)
    elif isinstance(doc, float):
        yield doc


def about(text: str, gap, tolerance=None) -> dict:
    """A vector file's `about` field: what it pins, the measured gap and the derived tolerance
    (one number, or one per model)."""
    if tolerance is None:
        tolerance = {k: derive(g) for k, g in gap.items()} if isinstance(gap, dict) else derive(gap)
    return {"text": text, "float32_vs_float64_gap": gap, "tolerance": tolerance, "rule": RULE}


def curve_gap(single, wide) -> float:
    """Largest |v32 - v64| of Eq. 8's curves (Prediction.curves "variance") of two predictions of the same
    case, the served graphs and the graphs widened to float64; inf when their stops differ. The stop
    margin a case must keep is derive() of it: the tolerance rule applied to the quantity the stop
    decision compares with delta, so a difference within that tolerance cannot flip a stop."""
    a = next((c for c in single.curves if c["id"] == "variance"), None)
    b = next((c for c in wide.curves if c["id"] == "variance"), None)
    if a is None or b is None:
        return 0.0
    if list(single.lengths) != list(wide.lengths):
        return math.inf
    return max((float(np.abs(np.asarray(x, np.float64) - np.asarray(y, np.float64)).max())
                for x, y in zip(a["series"], b["series"])), default=0.0)


def keeps_its_stop_margin(pred, wide) -> bool:
    """A prediction whose every stop decision (its `margins`) keeps 1.5 x the tolerance of its own
    Eq. 8 curve (curve_gap against the same case in float64): a difference within that tolerance
    cannot flip one of its stops, so its lengths are the same on any machine."""
    if not pred.margins:
        return True
    return min(pred.margins) >= 1.5 * derive(min(curve_gap(pred, wide), 1e300))


def tolerance_of(doc: dict, model: str | None = None) -> float:
    """The tolerance a committed vector file states (per model where it has one per model)."""
    tol = doc["about"]["tolerance"]
    return float(tol[model]) if isinstance(tol, dict) else float(tol)
