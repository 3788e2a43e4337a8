"""The `lcp` family of shared test vectors: latent sampling (all three Table 4 rows), the per-sample
streams it draws from, and diversity.

These pin the predictor's own arithmetic independently of any ONNX file: TypeScript must
reproduce z and c from (condition outputs, K, sigma scale, seed; one stream per sample, as the
predictor draws), the streams' first draws exactly, and the diversity of given futures, within the
file's derived tolerance.
"""
from __future__ import annotations

import numpy as np

from .rng import streams

# (prior, decoder condition) of Table 4 rows 4, 2 and 3.
ROWS = [("conditional", None), ("standard_normal", {"name": "h_t", "size": 6}),
        ("standard_normal", {"name": "z_c", "size": 4})]


def lcp_vector() -> dict:
    from .sample.lcp_vae import diversity, sample_latents  # imports onnxruntime: only when written
    rng = np.random.default_rng(7)
    d = 4
    sampling = []
    for prior, c_spec in ROWS:
        params = {"latent_size": d, "prior": prior, "decoder_condition": c_spec}
        for seed, k, scale, rows in [(0, 1, 1.0, 1), (11, 5, 0.0, 1), (42, 5, 0.55, 1), (4294967295, 3, 2.0, 3)]:
            # rows 1: the first call of a prediction (one shared history); rows k: a recursive call.
            cond = {"mu_c": rng.normal(size=(rows, d)).astype(np.float32),
                    "sigma_c": rng.uniform(0.05, 1.5, size=(rows, d)).astype(np.float32),
                    "h_t": rng.uniform(-1, 1, size=(rows, 6)).astype(np.float32)}
            z, c = sample_latents(streams(seed, k), cond, k, scale, params)
            sampling.append({"params": params, "seed": seed, "k": k, "sigma_scale": scale,
                             "condition": {n: v.tolist() for n, v in cond.items()},
                             "z": z.astype(np.float64).tolist(), "c": None if c is None else c.astype(np.float64).tolist()})
    div = []
    for k, frames in [(1, 3), (2, 4), (5, 7)]:
        futures = rng.normal(scale=0.3, size=(k, frames, 18, 3)).astype(np.float32)
        div.append({"futures": futures.astype(np.float64).tolist(), "diversity": diversity(futures)})
    # Sample i's stream is Prng(seed) jumped i x 2^64 draws (export/rng.py): its first draws, exactly.
    first = [{"seed": seed, "count": count, "u32": [[g.next_u32() for _ in range(4)] for g in streams(seed, count)]}
             for seed, count in [(0, 3), (42, 50), (4294967295, 5)]]
    return {"about": "LCP-VAE predictor arithmetic: condition outputs + K + sigma scale + seed -> z and c, "
                     "sample i drawing from streams(seed, K)[i] (draw order in export/sample/lcp_vae.py); "
                     "seed + count -> each stream's first 4 u32 draws (exact); futures -> diversity (WAT Eq. 10 on root-relative poses)",
            "sampling": sampling, "streams": first, "diversity": div}


# (clip, start, K, seed, horizon frames or None for the control's default, controls)
E2E_CASES = [("cmu_10_04", 3, 4, 7, 75, {"sigma_scale": 1.5}),   # 75 > 60: one recursive call
             ("cmu_49_09", 90, 4, 7, 75, {}),
             ("cmu_61_13", 5, 10, 3, None, {"sigma_scale": 0.5})]


def lcp_e2e_cases(entry: dict, predictor) -> list[dict]:
    """End-to-end cases for a served LCP-VAE model. LCP samples make no thresholded decisions
    (Prediction.margins is empty), so no case needs filtering by margin."""
    from .data.clip_json import read_clip
    from .paths import CLIPS_DIR
    from .sample.request import Request
    n = entry["params"]["history_frames"]
    cases = []
    for clip, start, k, seed, horizon, controls in E2E_CASES:
        history = read_clip(CLIPS_DIR / f"{clip}.json").positions[start:start + n].astype(np.float32)
        req = Request(k=k, seed=seed, horizon_frames=horizon, controls=dict(controls))
        cases.append(lcp_record(entry, clip, start, history, req, predictor.predict(history, req)))
    return cases


def lcp_record(entry: dict, clip: str, start: int, history: np.ndarray, req, pred) -> dict:
    """What an LCP-VAE case stores of one prediction (also what a replay of the case is compared on)."""
    from .vectors_record import record
    return record(entry, clip, start, history, req, pred, readouts=pred.readouts)
