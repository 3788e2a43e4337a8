"""LCP-VAE and the Table 4 baselines: training terms, frozen CS-VAE in Eq. 6, export parity, predictor."""
import json

import numpy as np
import pytest
import torch

from export.config import load_config, override
from export.manifest import manifest_document, write_manifest
from export.methods.lcp_vae import components
from export.onnx.export import check_parity
from export.paths import CONFIGS_DIR, MODELS_DIR
from export.pipeline import export, train
from export.rng import Prng, streams
from export.sample.lcp_vae import diversity, sample_latents
from export.sample.predictor import load_predictor
from export.sample.request import PredictError, Request


@pytest.fixture(scope="module")
def clips(deepmimic):
    """Tiny models train on the DeepMimic clips (small, named, with their own test tails)."""
    return deepmimic

# Small enough that training and export of all three variants take seconds.
TINY = {"history_frames": 10, "future_frames": 8, "model.hidden": 16, "model.embed": 16, "model.latent": 4,
        "train.steps": 16, "train.batch_size": 16, "train.stride": 4, "train.checkpoint_every": 100}
VARIANTS = ["lcp", "cvae_h", "cvae_zc"]


@pytest.fixture(scope="module")
def trained(clips):
    out = {}
    for variant in VARIANTS:
        cfg = override(load_config("lcp_vae.json"), **TINY, **{"model.variant": variant, "id": f"tiny-{variant}"})
        out[variant] = (cfg, *train(cfg, list(clips.values()), progress=False))
    return out


@pytest.fixture(scope="module")
def models_dir(trained, tmp_path_factory, clips):
    """The three tiny models exported with a manifest, so the real predictor runs on them."""
    d = tmp_path_factory.mktemp("lcp_models")
    actions = sorted({c.action for c in clips.values()})
    entries = [export(method, model, cfg, d, actions, "sha256:" + "0" * 64) for cfg, method, model in trained.values()]
    write_manifest(manifest_document(entries, actions, "sha256:" + "0" * 64), d / "manifest.json")
    return d


def history(clips, frames=10, start=2):
    return clips["walker_walk_forward"].positions[start:start + frames]


def test_every_variant_trains_with_finite_terms_and_the_full_model_has_all_four(trained):
    for variant, (cfg, method, model) in trained.items():
        data = {"history": torch.zeros(4, 10, 18, 3) + model.pose_mean.reshape(1, 1, 18, 3),
                "future": torch.zeros(4, 8, 18, 3) + model.pose_mean.reshape(1, 1, 18, 3)}
        loss, logs = method.loss(model, data, step=3)
        assert torch.isfinite(loss)
        assert set(logs) >= {"rec_future", "rec_history", "kl_c", "kl", "lam", "tf"}
        if variant == "cvae_h":   # row 2 is a standard CVAE: no CS-VAE terms, so no z_c to draw a future from
            assert logs["rec_history"] == 0 and logs["kl_c"] == 0 and not hasattr(model, "cs_encode")
            assert "prior_speed" not in logs
        else:
            assert logs["rec_history"] > 0 and logs["kl_c"] > 0
            assert np.isfinite(logs["prior_speed"])


def test_schedules_teacher_forcing_decays_to_autoregressive_and_lambda_rises_to_one(trained):
    _, method, _ = trained["lcp"]
    steps = 16
    tf0, lam0 = method.schedule(0)
    assert (tf0, lam0) == (1.0, 0.0)
    assert method.schedule(steps // 2)[0] == 0.0            # teacher_forcing_fraction 0.5
    assert method.schedule(steps - 1)[1] == 1.0
    assert 0 < method.schedule(3)[1] < 1


def test_eq6_leaves_the_cs_vae_frozen_but_trains_the_lcp_encoder(trained, clips):
    cfg, method, model = trained["lcp"]
    data = method.prepare(list(clips.values()))
    batch = {k: v[:8] for k, v in data.tensors.items()}
    model.zero_grad()
    out = model(batch["history"], batch["future"], 0.0)
    components("lcp", out, method.rec_weight)["kl"].backward()
    cs = [p.grad for p in model.cs_encode.parameters()]
    assert all(g is None or float(g.abs().max()) == 0 for g in cs)
    assert max(float(p.grad.abs().max()) for p in model.lcp_encode.parameters()) > 0
    # while the reconstruction through z = mu + sigma*z_c (Eq. 4) does reach the CS-VAE encoder
    model.zero_grad()
    out = model(batch["history"], batch["future"], 0.0)
    components("lcp", out, method.rec_weight)["rec_future"].backward()
    assert max(float(p.grad.abs().max()) for p in model.cs_encode.parameters()) > 0
    model.zero_grad()


def test_graphs_match_torch_in_onnx_and_name_the_decoder_condition(trained, models_dir):
    for variant, (cfg, method, model) in trained.items():
        graphs = method.graphs(model)
        assert set(graphs) == {"condition", "decoder"}
        for role, graph in graphs.items():
            blob = (models_dir / f"tiny-{variant}.{role}.onnx").read_bytes()   # written by the fixture
            assert check_parity(graph, blob) < 1e-4, (variant, role)
        names = [s.name for s in graphs["decoder"].inputs]
        cond = [s.name for s in graphs["condition"].outputs]
        p = method.params(model)
        if variant == "lcp":
            assert names == ["z", "last_poses"] and cond == ["mu_c", "sigma_c"] and p["decoder_condition"] is None
            assert p["prior"] == "conditional" and p["table4_row"] == 4
        else:
            assert names == ["z", "last_poses", "c"] and p["prior"] == "standard_normal"
            assert p["decoder_condition"]["name"] == {"cvae_h": "h_t", "cvae_zc": "z_c"}[variant]
            assert cond == (["h_t"] if variant == "cvae_h" else ["mu_c", "sigma_c"])


def test_the_decoder_starts_at_the_last_pose_and_uses_z(trained):
    _, method, model = trained["lcp"]
    last = model.pose_mean.reshape(1, 1, 18, 3).repeat(2, 2, 1, 1)   # the last two poses, held still
    z = torch.stack([torch.zeros(4), 3 * torch.ones(4)])
    with torch.no_grad():
        fut = method.graphs(model)["decoder"].module(z, last)
    assert fut.shape == (2, 8, 18, 3)
    assert float((fut[:, 0] - last[:, -1]).abs().max()) < 0.5         # residual decoder and seam: no jump
    assert float((fut[0] - fut[1]).abs().max()) > 1e-4               # different z, different future


def test_sampling_follows_the_documented_draw_order():
    d, k, s = 3, 4, 0.7
    mu_c, sigma_c = np.float32([[0.1, -0.2, 0.3]]), np.float32([[0.5, 1.0, 2.0]])
    z, c = sample_latents(Prng(9), {"mu_c": mu_c, "sigma_c": sigma_c}, k, s,
                          {"latent_size": d, "prior": "conditional", "decoder_condition": None})
    eps = Prng(9).normals((k, d))
    np.testing.assert_array_equal(z, (mu_c.astype(np.float64) + s * sigma_c.astype(np.float64) * eps).astype(np.float32))
    assert c is None
    # row 3: eps_c for z_c first, then eps for z
    z, c = sample_latents(Prng(9), {"mu_c": mu_c, "sigma_c": sigma_c}, k, s,
                          {"latent_size": 2, "prior": "standard_normal", "decoder_condition": {"name": "z_c", "size": 3}})
    r = Prng(9)
    eps_c, eps = r.normals((k, 3)), r.normals((k, 2))
    np.testing.assert_array_equal(c, (mu_c.astype(np.float64) + s * sigma_c.astype(np.float64) * eps_c).astype(np.float32))
    np.testing.assert_array_equal(z, (s * eps).astype(np.float32))
    # the predictor's way: one stream per sample, each drawing eps_c then eps
    z, c = sample_latents(streams(9, k), {"mu_c": mu_c, "sigma_c": sigma_c}, k, s,
                          {"latent_size": 2, "prior": "standard_normal", "decoder_condition": {"name": "z_c", "size": 3}})
    for i, g in enumerate(streams(9, k)):
        eps_c, eps = g.normals((3,)), g.normals((2,))
        np.testing.assert_array_equal(c[i], (mu_c[0].astype(np.float64) + s * sigma_c[0].astype(np.float64) * eps_c).astype(np.float32))
        np.testing.assert_array_equal(z[i], (s * eps).astype(np.float32))


def test_diversity_is_eq10_of_wat_on_root_relative_poses():
    rng = np.random.default_rng(0)
    f = rng.normal(size=(4, 5, 18, 3)).astype(np.float32)
    rr = f.astype(np.float64) - f[:, :, :1].astype(np.float64) * np.array([1.0, 0.0, 1.0])
    pairs = [np.linalg.norm((rr[i] - rr[j]).reshape(5, -1), axis=1).mean() for i in range(4) for j in range(4) if i != j]
    assert diversity(f) == pytest.approx(np.mean(pairs), rel=1e-9)
    moved = f.copy()
    moved[..., [0, 2]] += rng.normal(size=(4, 5, 1, 2)).astype(np.float32)   # root paths apart, same poses
    assert diversity(moved) == pytest.approx(diversity(f), rel=1e-5)
    assert diversity(f[:1]) == 0.0
    assert diversity(np.repeat(f[:1], 3, 0)) == 0.0


def test_predictor_gives_k_futures_recurses_past_one_call_and_is_seeded(models_dir, clips):
    for variant in VARIANTS:
        p = load_predictor(f"tiny-{variant}", models_dir)
        h = history(clips)
        pred = p.predict(h, Request(k=5, seed=3, horizon_frames=20, controls={"sigma_scale": 1.0}))
        assert pred.futures.shape == (5, 20, 18, 3) and pred.futures.dtype == np.float32
        assert list(pred.lengths) == [20] * 5 and len(pred.samples) == 5 and pred.margins == []
        [readout] = pred.readouts
        assert readout["label"] == "diversity" and readout["unit"] == "m"
        assert readout["value"] == pytest.approx(diversity(pred.futures)) and readout["value"] > 0
        again = p.predict(h, Request(k=5, seed=3, horizon_frames=20, controls={"sigma_scale": 1.0}))
        np.testing.assert_array_equal(pred.futures, again.futures)
        other = p.predict(h, Request(k=5, seed=4, horizon_frames=20, controls={"sigma_scale": 1.0}))
        assert not np.array_equal(pred.futures, other.futures)


def test_sigma_scale_zero_decodes_the_mode_for_every_sample(models_dir, clips):
    for variant in VARIANTS:
        p = load_predictor(f"tiny-{variant}", models_dir)
        pred = p.predict(history(clips), Request(k=4, seed=1, controls={"sigma_scale": 0}))
        assert pred.readouts[0]["value"] == 0.0 and pred.notes
        assert all(np.array_equal(pred.futures[0], f) for f in pred.futures[1:])
    # the full model's mode is the decoder at z = mu_c, whatever the seed
    p = load_predictor("tiny-lcp", models_dir)
    a = p.predict(history(clips), Request(k=1, seed=1, controls={"sigma_scale": 0}))
    b = p.predict(history(clips), Request(k=1, seed=2, controls={"sigma_scale": 0}))
    np.testing.assert_array_equal(a.futures, b.futures)


@pytest.mark.parametrize("frames, controls, message", [
    (9, {}, "history has 9 frames; this model needs at least 10"),
    (10, {"sigma_scale": 8.5}, "Sigma scale must be between 0 and 8, got 8.5"),
    (10, {"sigma_scale": -0.1}, "Sigma scale must be between 0 and 8"),
    (10, {"sigma_scale": "wide"}, "Sigma scale must be a number"),
])
def test_bad_input_gives_a_clear_message(models_dir, clips, frames, controls, message):
    p = load_predictor("tiny-lcp", models_dir)
    with pytest.raises(PredictError, match=message):
        p.predict(history(clips, frames), Request(k=3, controls=controls))


def test_nan_history_and_k_out_of_range_are_rejected(models_dir, clips):
    p = load_predictor("tiny-lcp", models_dir)
    h = history(clips).copy()
    h[4, 2, 1] = np.nan
    with pytest.raises(PredictError, match="NaN or infinite values \\(first at frame 4\\)"):
        p.predict(h, Request(k=3))
    with pytest.raises(PredictError, match="K must be an integer from 1 to 50, got 51"):
        p.predict(history(clips), Request(k=51))


def test_served_config_records_the_issue_settings_and_ablations_share_its_budget():
    served = load_config("lcp_vae.json")
    assert (served["history_frames"], served["future_frames"]) == (19, 60)
    for name, variant in [("lcp_cvae_h.json", "cvae_h"), ("lcp_cvae_zc.json", "cvae_zc")]:
        # an ablation extends the served config and changes only the variant (config.py "extends")
        assert json.loads((CONFIGS_DIR / "ablations" / name).read_text())["changes"] == {"model.variant": variant}
        ab = load_config(CONFIGS_DIR / "ablations" / name)
        assert ab["model"]["variant"] == variant
        assert ab["train"] == served["train"] and ab["history_frames"] == 19 and ab["future_frames"] == 60
        assert {k: v for k, v in ab["model"].items() if k != "variant"} == \
            {k: v for k, v in served["model"].items() if k != "variant"}
