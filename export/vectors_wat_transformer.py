"""WAT (Transformer)'s end-to-end vector cases: the RNN's case format (vectors_wat.wat_e2e_cases) with
its own action sequences. Its variance curves cross delta gently for walk, run and jump (median
distance to delta at the decision 3e-4 on the walker history vs 1.1e-3 for the RNN), so no seed
keeps E2E_MARGIN = 1e-3 there; these sequences keep the margin and still stop inside T_max."""
from __future__ import annotations

from .vectors_wat import wat_e2e_cases

# (clip, first history frame, action sequence)
E2E_CASES = [("cmu_10_04", 3, ["kick", "punch", "cartwheel"]), ("cmu_49_09", 90, ["dance"])]


def wat_transformer_e2e_cases(entry: dict, predictor, keeps) -> list[dict]:
    return wat_e2e_cases(entry, predictor, keeps, E2E_CASES)
