"""Keyposes' ghosts stand where the drawn figure stands: with planted feet (the default) each ghost moves
by the root shift planting gave its future at the ghost's frame; with plant_feet off it stays at the
method's own root."""
import numpy as np
import pytest

from export.data.clip_json import read_clip
from export.manifest import read_manifest
from export.paths import CLIPS_DIR, MODELS_DIR
from export.sample.ghosts import follow_roots
from export.sample.predictor import load_predictor
from export.sample.request import Request
from export.vectors_keyposes import E2E_CASES, first_accepted_start

ENTRY = next((m for m in read_manifest(MODELS_DIR / "manifest.json")["models"] if m["method"] == "keyposes"), None)
committed = pytest.mark.skipif(ENTRY is None, reason="no Keyposes model in public/models")


def _roots_at(pred, i: int) -> np.ndarray:
    """Future i's root x, z at its ghosts' frames [n, 2]."""
    return pred.futures[i, pred.ghosts["frames"][i], 0][:, [0, 2]].astype(np.float64)


@committed
@pytest.mark.parametrize("clip, earliest, horizon, controls", E2E_CASES)
def test_ghosts_stand_on_the_planted_root_and_on_the_methods_own_without_planting(clip, earliest, horizon, controls):
    p = load_predictor(ENTRY["id"])
    n = ENTRY["params"]["history_frames"]
    positions = read_clip(CLIPS_DIR / f"{clip}.json").positions
    start = first_accepted_start(p, positions, n, earliest)
    history = positions[start:start + n].astype(np.float32)
    on = p.predict(history, Request(k=4, seed=5, horizon_frames=horizon, controls=dict(controls)))
    off = p.predict(history, Request(k=4, seed=5, horizon_frames=horizon, controls=dict(controls), plant_feet=False))
    moved = 0.0
    for i in range(4):
        g_on, g_off = np.asarray(on.ghosts["poses"][i], np.float64), np.asarray(off.ghosts["poses"][i], np.float64)
        assert g_on.shape[0] == len(on.ghosts["frames"][i]) and g_off.shape[0] == len(off.ghosts["frames"][i])
        # each ghost's root is its future's root at its frame, planted or not
        np.testing.assert_allclose(g_on[:, 0, [0, 2]], _roots_at(on, i), atol=1e-5)
        np.testing.assert_allclose(g_off[:, 0, [0, 2]], _roots_at(off, i), atol=1e-5)
        # the whole pose moves by planting's shift at that frame, horizontally only (ghosts past a cut are gone)
        keep = min(len(g_on), len(g_off))
        assert on.ghosts["frames"][i][:keep] == off.ghosts["frames"][i][:keep]
        shift = _roots_at(on, i)[:keep] - _roots_at(off, i)[:keep]
        np.testing.assert_allclose((g_on - g_off)[:keep][..., [0, 2]], np.broadcast_to(shift[:, None], (keep, 18, 2)), atol=1e-5)
        np.testing.assert_array_equal(g_on[:keep, :, 1], g_off[:keep, :, 1])
        moved = max(moved, float(np.abs(shift).max(initial=0.0)))
    assert moved > 0.01            # planting moved these futures, so the test tells a placed ghost from a stale one


def test_a_ghost_outside_its_future_is_refused_by_name():
    futures = np.zeros((1, 5, 18, 3), np.float32)
    ghosts = {"frames": [[2, 5]], "poses": [np.zeros((2, 18, 3), np.float32)]}
    with pytest.raises(ValueError, match=r"future 0 has a ghost outside its 5 frames: \[2, 5\]"):
        follow_roots(ghosts, futures, futures + 1)
