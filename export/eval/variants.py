"""Evaluation variants that the served code does not run (issue 18, item 6; issue 19):

- Keyposes with the history's keyposes extracted by the max-error rule of the authors' code (ops/keyposes.py
  `rule="max"`), the served model otherwise;
- futures bone-projected onto the history's bone lengths (ops/bones.project_lengths), as an extra row after
  the raw outputs.
"""
from __future__ import annotations

import contextlib
import types

import numpy as np

from ..ops import keyposes as kp
from ..ops.bones import bone_lengths, project_lengths
from ..sample import keyposes as keyposes_predictor


@contextlib.contextmanager
def extraction_rule(rule: str):
    """Within the block, the Keyposes predictor extracts keyposes by `rule`. The served predictor reads
    ops.keyposes through its module attribute `kp`; a namespace with extract's rule bound stands in for it,
    so the served code and its default stay untouched."""
    if rule == "mean":
        yield
        return
    shim = types.SimpleNamespace(**{k: getattr(kp, k) for k in dir(kp) if not k.startswith("__")})
    shim.extract = lambda positions, threshold=kp.THRESHOLD: kp.extract(positions, threshold, rule=rule)
    saved = keyposes_predictor.kp
    keyposes_predictor.kp = shim
    try:
        yield
    finally:
        keyposes_predictor.kp = saved


class RuleKeyposes(keyposes_predictor.KeyposesPredictor):
    """The served Keyposes predictor whose history keyposes follow another extraction rule."""
    rule = "max"

    def observe(self, history: np.ndarray) -> dict:
        with extraction_rule(self.rule):
            return super().observe(history)


def with_rule(predictor, rule: str):
    """The same model's predictor with another extraction rule ("mean": the predictor itself)."""
    if rule == "mean":
        return predictor
    if not isinstance(predictor, keyposes_predictor.KeyposesPredictor):
        raise ValueError(f"the keypose extraction rule applies to Keyposes only, not {type(predictor).__name__}")
    out = RuleKeyposes(predictor.entry, predictor.manifest, predictor.models_dir)
    out.rule = rule
    return out


def project_onto_history(futures: np.ndarray, history: np.ndarray) -> np.ndarray:
    """World futures [K, T, J, 3] with every bone set to its mean length over the history [N, J, 3]."""
    return project_lengths(futures, bone_lengths(history).mean(0))


def keypose_counts(histories: list[np.ndarray], threshold: float = kp.THRESHOLD) -> dict[str, float]:
    """Mean keyposes per history under each rule (root-relative poses, as the predictor extracts them)."""
    from ..ops.facing import root_relative, split_root
    out = {}
    for rule in kp.RULES:
        out[rule] = float(np.mean([len(kp.extract(root_relative(split_root(h)), threshold, rule=rule))
                                   for h in histories])) if histories else float("nan")
    return out
