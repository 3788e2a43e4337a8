"""The two KL terms of LCP-VAE in closed form (paper Eqs. 5 and 6), per example.

Both take standard deviations (not log-variances), as the encoders output sigma directly.
"""
from __future__ import annotations

import torch


def kl_standard_normal(mu: torch.Tensor, sigma: torch.Tensor) -> torch.Tensor:
    """Eq. 5: KL(N(mu, diag(sigma)^2) || N(0, I)), summed over the latent dimension -> [batch]."""
    return 0.5 * (mu.square() + sigma.square() - 1.0 - 2.0 * torch.log(sigma)).sum(-1)


def kl_lcp(mu: torch.Tensor, sigma: torch.Tensor, mu_c: torch.Tensor, sigma_c: torch.Tensor) -> torch.Tensor:
    """Eq. 6: KL(N(mu + sigma*mu_c, diag(sigma*sigma_c)^2) || N(mu_c, diag(sigma_c)^2)) -> [batch].

    Derived from the Gaussian KL of Eq. 12 with mu_1 = mu + sigma*mu_c, Sigma_1 = diag(sigma*sigma_c)^2,
    mu_2 = mu_c, Sigma_2 = diag(sigma_c)^2; sigma_c cancels in the log-determinant and trace:
        KL = 1/2 sum_j [ -log sigma_j^2 - 1 + sigma_j^2 + (mu_j + (sigma_j - 1) mu_c_j)^2 / sigma_c_j^2 ].
    The printed Eq. 7 (and Eqs. 13-14) differ: a leading minus sign (that would make training
    maximise the divergence) and Sigma*mu_c (sigma squared) where the mean of Eq. 4 has sigma*mu_c.
    The caller detaches mu_c and sigma_c: CS-VAE is frozen for this term (Section 4.2).
    """
    mean_gap = mu + (sigma - 1.0) * mu_c   # (mu + sigma*mu_c) - mu_c
    return 0.5 * (sigma.square() - 1.0 - 2.0 * torch.log(sigma) + mean_gap.square() / sigma_c.square()).sum(-1)
