"""Samples that nest (issue 30 item 6): with the same seed, the first k samples of a prediction with
K > k are exactly the k samples of a prediction with K = k, for every stochastic served model; so
best-of-K never rises with K. The sub-streams that make it so (export/rng.py) are checked here too.
Twin: tests/web/nesting.test.ts."""
from dataclasses import replace

import numpy as np
import pytest

from export.data.clip_json import read_clip
from export.eval.metrics import ade
from export.manifest import read_manifest
from export.paths import CLIPS_DIR, MODELS_DIR
from export.rng import Prng, row_normals, streams
from export.sample.predictor import load_predictor
from export.sample.request import Request
from export.vectors_keyposes import first_accepted_start

MANIFEST = read_manifest(MODELS_DIR / "manifest.json")
# The stochastic models are the ones with a K control.
STOCHASTIC = [m for m in MANIFEST["models"] if any(c["id"] == "k" for c in m["controls"])]
KS = (1, 5, 10, 50)
HELD_OUT_WALKS = ["cmu_10_04", "cmu_07_05", "cmu_08_04"]


def test_the_stochastic_models_are_the_four_served_samplers():
    assert sorted(m["method"] for m in STOCHASTIC) == ["keyposes", "lcp_vae", "wat", "wat_transformer"]


# --- the streams -----------------------------------------------------------------------------------

def _bits(state: list[int]) -> np.ndarray:
    return np.array([(state[w] >> b) & 1 for w in range(4) for b in range(32)], np.int64)


def _state(bits: np.ndarray) -> list[int]:
    return [sum(int(bits[w * 32 + b]) << b for b in range(32)) for w in range(4)]


def test_jump_moves_the_state_2_to_the_64_draws_ahead():
    # xoshiro128**'s state transition is linear over GF(2): its 128 x 128 matrix squared 64 times is
    # 2^64 draws, computed here independently of the JUMP constants.
    def step(state):
        g = Prng(0)
        g.s = list(state)
        g.next_u32()
        return g.s
    t = np.zeros((128, 128), np.int64)
    for j in range(128):
        unit = [0, 0, 0, 0]
        unit[j // 32] = 1 << (j % 32)
        t[:, j] = _bits(step(unit))
    for _ in range(64):
        t = (t @ t) % 2
    for seed in (0, 42, 4294967295):
        g = Prng(seed)
        want = _state((t @ _bits(g.s)) % 2)
        g.jump()
        assert g.s == want


def test_streams_nest_and_stream_0_is_the_seed_itself():
    big = [[g.next_u32() for _ in range(5)] for g in streams(7, 12)]
    for k in (0, 1, 5, 12):
        assert [[g.next_u32() for _ in range(5)] for g in streams(7, k)] == big[:k]
    g = Prng(7)
    assert big[0] == [g.next_u32() for _ in range(5)]
    assert len({tuple(x) for x in big}) == 12
    with pytest.raises(ValueError, match="stream count"):
        streams(7, -1)


def test_row_normals_from_one_generator_or_one_stream_per_row():
    assert np.array_equal(row_normals(Prng(3), 4, 6), Prng(3).normals((4, 6)))
    rows = row_normals(streams(3, 4), 4, 6)
    assert rows.shape == (4, 6)
    assert np.array_equal(rows[2], streams(3, 3)[2].normals((6,)))
    with pytest.raises(ValueError, match="3 streams for 4 samples"):
        row_normals(streams(3, 3), 4, 6)


# --- the predictors --------------------------------------------------------------------------------

def _case(entry: dict, predictor) -> tuple[np.ndarray, Request]:
    """A held-out walk and a request that exercises every draw: three actions (WAT), a recursive call
    (LCP-VAE, 75 > 60 frames), refine on and the longest horizon (Keyposes)."""
    n = entry["params"]["history_frames"]
    pos = read_clip(CLIPS_DIR / "cmu_10_04.json").positions
    if entry["method"] == "keyposes":
        start = first_accepted_start(predictor, pos, n, 15)
        return pos[start:start + n].astype(np.float32), Request(k=1, seed=11, controls={"refine": True})
    history = pos[3:3 + n].astype(np.float32)
    if entry["method"] == "lcp_vae":
        return history, Request(k=1, seed=11, horizon_frames=75)
    return history, Request(k=1, seed=11, actions=["walk", "punch", "jump"])


def _assert_nested(big, small, k: int) -> None:
    """small (K = k) is big's (K > k) first k samples, exactly. WAT pads every sample to the longest
    one's length, so only the frames both hold are compared (every sample's own frames are)."""
    f = small.futures.shape[1]
    assert f <= big.futures.shape[1]
    assert small.lengths.tolist() == big.lengths[:k].tolist()
    assert small.samples == big.samples[:k]
    assert np.array_equal(small.futures, big.futures[:k, :f])
    for cs, cb in zip(small.curves, big.curves):
        assert all(np.array_equal(a, b[:f]) for a, b in zip(cs["series"], cb["series"][:k]))
    if big.ghosts is not None:
        assert small.ghosts["frames"] == big.ghosts["frames"][:k]
        assert all(np.array_equal(a, b) for a, b in zip(small.ghosts["poses"], big.ghosts["poses"][:k]))
    assert small.warnings == big.warnings


@pytest.mark.parametrize("entry", STOCHASTIC, ids=[m["id"] for m in STOCHASTIC])
def test_the_first_k_samples_of_K_are_the_k_samples(entry):
    predictor = load_predictor(entry["id"])
    history, req = _case(entry, predictor)
    big = predictor.predict(history, replace(req, k=KS[-1]))
    assert len({big.futures[i].tobytes() for i in range(KS[-1])}) == KS[-1]   # 50 different futures
    for k in KS[:-1]:
        _assert_nested(big, predictor.predict(history, replace(req, k=k)), k)


@pytest.mark.parametrize("entry", STOCHASTIC, ids=[m["id"] for m in STOCHASTIC])
def test_best_of_k_never_rises_with_k_on_held_out_walks(entry):
    """Separate predictions at K = 1, 5, 10, 50 (what a user who raises K sees), 2 s after frame 40."""
    predictor = load_predictor(entry["id"])
    n, at, horizon = entry["params"]["history_frames"], 40, 60
    for clip in HELD_OUT_WALKS:
        pos = read_clip(CLIPS_DIR / f"{clip}.json").positions
        history, truth = pos[at - n:at].astype(np.float32), pos[at:at + horizon]
        actions = ["walk"] if entry["method"].startswith("wat") else []
        best = [ade(predictor.predict(history, Request(k=k, seed=3, actions=actions, horizon_frames=horizon)).futures, truth)
                for k in KS]
        assert all(a >= b for a, b in zip(best, best[1:])), (clip, best)
