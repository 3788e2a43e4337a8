"""The closed-form KLs of LCP-VAE (Eqs. 5-6) against Monte Carlo and torch.distributions, and lambda."""
import math

import pytest
import torch
from torch.distributions import Normal, kl_divergence

from export.ops.kl import kl_lcp, kl_standard_normal
from export.ops.kl_annealing import kl_weight


def random_params(batch=3, d=5, seed=0):
    g = torch.Generator().manual_seed(seed)
    mu, mu_c = torch.randn(batch, d, generator=g, dtype=torch.float64), torch.randn(batch, d, generator=g, dtype=torch.float64)
    sigma = 0.3 + 1.5 * torch.rand(batch, d, generator=g, dtype=torch.float64)
    sigma_c = 0.3 + 1.5 * torch.rand(batch, d, generator=g, dtype=torch.float64)
    return mu, sigma, mu_c, sigma_c


def test_eq6_closed_form_matches_a_monte_carlo_estimate():
    mu, sigma, mu_c, sigma_c = random_params()
    p1 = Normal(mu + sigma * mu_c, sigma * sigma_c)      # the LCP-VAE posterior of Eq. 4
    p2 = Normal(mu_c, sigma_c)                           # the CS-VAE posterior
    n = 400_000
    x = p1.loc + p1.scale * torch.randn((n, *mu.shape), generator=torch.Generator().manual_seed(1), dtype=torch.float64)
    log_ratio = (p1.log_prob(x) - p2.log_prob(x)).sum(-1)          # [n, batch]
    mc, se = log_ratio.mean(0), log_ratio.std(0) / math.sqrt(n)
    closed = kl_lcp(mu, sigma, mu_c, sigma_c)
    assert closed.shape == (3,)
    assert torch.all((closed - mc).abs() < 5 * se), (closed, mc, se)
    assert torch.all(closed > 0.1)  # the random parameters are far from equal distributions


def test_eq6_matches_torch_distributions_exactly_and_eq5_too():
    mu, sigma, mu_c, sigma_c = random_params(batch=7, d=16, seed=3)
    want = kl_divergence(Normal(mu + sigma * mu_c, sigma * sigma_c), Normal(mu_c, sigma_c)).sum(-1)
    torch.testing.assert_close(kl_lcp(mu, sigma, mu_c, sigma_c), want, rtol=1e-10, atol=1e-12)
    want5 = kl_divergence(Normal(mu, sigma), Normal(torch.zeros_like(mu), torch.ones_like(sigma))).sum(-1)
    torch.testing.assert_close(kl_standard_normal(mu, sigma), want5, rtol=1e-10, atol=1e-12)


def test_eq6_is_zero_exactly_when_the_extended_reparameterisation_is_the_identity():
    _, _, mu_c, sigma_c = random_params()
    zero = kl_lcp(torch.zeros_like(mu_c), torch.ones_like(mu_c), mu_c, sigma_c)
    assert torch.all(zero.abs() < 1e-12)
    assert torch.all(kl_lcp(torch.full_like(mu_c, 0.1), torch.ones_like(mu_c), mu_c, sigma_c) > 0)


def test_the_printed_eq7_is_not_this_kl():
    # Eq. 7 as printed: -1/2 [log 1/|S| - d + tr S + (mu_c - (mu + S mu_c))^T S_c^-1 (...)], S = diag(sigma^2).
    mu, sigma, mu_c, sigma_c = random_params()
    s2 = sigma.square()
    gap = mu_c - (mu + s2 * mu_c)
    printed = -0.5 * (-torch.log(s2).sum(-1) - mu.shape[-1] + s2.sum(-1) + (gap.square() / sigma_c.square()).sum(-1))
    assert torch.all(printed < 0)                     # a KL is never negative
    assert not torch.allclose(-printed, kl_lcp(mu, sigma, mu_c, sigma_c))  # and Sigma*mu_c is not sigma*mu_c


def test_kl_weight_is_a_logistic_ramp_from_0_to_1():
    end = 400
    w = [kl_weight(s, end) for s in range(0, 600)]
    assert w[0] == 0.0 and w[end] == 1.0 and w[-1] == 1.0
    assert all(b >= a for a, b in zip(w, w[1:]))
    assert kl_weight(end // 2, end) == pytest.approx(0.5)
    assert kl_weight(end // 10, end) < 0.05 and kl_weight(9 * end // 10, end) > 0.95   # logistic, not linear
    assert kl_weight(5, 0) == 1.0                       # no annealing configured
