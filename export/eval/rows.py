"""What the results compare: rows (what predicts) and the papers' claims (which rows should win).

Adding a method row is one line: a Row naming its config (configs/<name>.json when served,
configs/ablations/<name>.json when not), the controls it predicts with, and optionally the
tables it belongs to. Rows whose config, method or predictor does not exist yet, or whose
model has not been trained, are skipped by the harness with a note saying which.

Training seed 0 of a served config is the model in public/models; the other seeds (and every
seed of an ablation) are trained by `make results` into runs/seeds/<model id>/seed<s>/.
"""
from __future__ import annotations

from dataclasses import dataclass, field


@dataclass(frozen=True)
class Row:
    id: str
    label: str
    kind: str = "model"                  # "model", "oracle" (the ground truth) or "noise" (sanity)
    config: str | None = None            # a file in configs/ (models only)
    controls: dict = field(default_factory=dict)
    tables: tuple[str, ...] | None = None  # None: every table the row can run in
    group: str = "baselines"
    note: str = ""


ROWS: list[Row] = [
    Row("oracle", "Ground truth (oracle)", kind="oracle", note="the test frames themselves"),
    Row("noise", "Ground truth + Gaussian noise (sanity)", kind="noise", group="sanity", tables=("test_1s",),
        note="K samples of truth + N(0, sigma^2) per coordinate; its diversity is known in closed form"),
    Row("zero-velocity", "Zero-velocity", config="zero_velocity.json"),
    Row("regression-gru", "Regression GRU", config="regression.json"),
    # WAT (issue 5): served model and the two ablations of its Table 5.
    Row("wat-rnn", "WAT (RNN)", config="wat_rnn.json", group="wat"),
    Row("wat-rnn-no-weak", "WAT (RNN) w/o weak supervision", config="ablations/wat_rnn_no_weak.json", group="wat"),
    Row("wat-rnn-no-padding", "WAT (RNN) w/o padding", config="ablations/wat_rnn_no_padding.json", group="wat"),
    # WAT (Transformer, issue 6): the served model and its Table 5 row without weak supervision.
    Row("wat-transformer", "WAT (Transformer)", config="wat_transformer.json", group="wat"),
    Row("wat-transformer-no-weak", "WAT (Transformer) w/o weak supervision",
        config="ablations/wat_transformer_no_weak.json", group="wat"),
    # LCP-VAE (issue 7): the served model (Table 4 row 4) and rows 2 and 3.
    Row("lcp-vae", "LCP-VAE (row 4: h_t / reparam z_c)", config="lcp_vae.json", group="lcp_vae"),
    Row("lcp-row2", "CVAE (row 2: h_t / concat h_t)", config="ablations/lcp_cvae_h.json", group="lcp_vae"),
    Row("lcp-row3", "CVAE (row 3: z_c / concat z_c)", config="ablations/lcp_cvae_zc.json", group="lcp_vae"),
    # Keyposes (issue 8): one trained model sampled at four temperatures (Table 3).
    *[Row(f"keyposes-t{t}", f"Keyposes (T = {t})", config="keyposes.json", controls={"temperature": t},
          group="keyposes") for t in (0.1, 0.3, 0.5, 1.0)],
]


@dataclass(frozen=True)
class Part:
    """One comparison: (row a, metric a) against (row b, metric b) in a table, in a direction
    ("greater", "less", "not_less" = similar or better, "not_greater")."""
    table: str
    a: str
    b: str
    metric: str
    direction: str
    metric_b: str | None = None          # another column of row b (default: the same metric)


@dataclass(frozen=True)
class Claim:
    id: str
    paper: str
    text: str
    parts: tuple[Part, ...]


def chain(table: str, rows: list[str], metric: str, direction: str) -> tuple[Part, ...]:
    """A monotone trend over rows in order: each consecutive pair compared."""
    return tuple(Part(table, b, a, metric, direction) for a, b in zip(rows, rows[1:]))


KP = [f"keyposes-t{t}" for t in (0.1, 0.3, 0.5, 1.0)]

CLAIMS: list[Claim] = [
    Claim("lcp-context-bounds", "LCP-VAE Table 2",
          "A zero-velocity future keeps less context (action recognisability) than the ground truth.",
          (Part("test_1s", "oracle", "zero-velocity", "acc_pose", "greater"),)),
    Claim("moac-static", "Keyposes sec. 4.3",
          "The motion-only classifier does not reward a static prediction: zero-velocity scores below the ground truth on MOAC.",
          (Part("test_1s", "oracle", "zero-velocity", "acc_moac", "greater"),)),
    Claim("fac-static", "Keyposes appendix 6.6, Table 16",
          "A pose-based classifier rewards a static prediction more than the motion-only one does.",
          (Part("test_1s", "zero-velocity", "zero-velocity", "acc_pose", "greater", metric_b="acc_moac"),)),
    Claim("wat-ade", "WAT Table 3 (issue 5)",
          "WAT's best-of-10 ADE beats zero-velocity and the regression GRU on the test split.",
          (Part("test_1s", "wat-rnn", "zero-velocity", "ade", "less"),
           Part("test_1s", "wat-rnn", "regression-gru", "ade", "less"))),
    Claim("wat-weak-supervision", "WAT Table 5",
          "Weak supervision raises recognition accuracy and diversity of action-conditioned futures.",
          (Part("transitions", "wat-rnn", "wat-rnn-no-weak", "acc_pose", "greater"),
           Part("transitions", "wat-rnn", "wat-rnn-no-weak", "div", "greater"))),
    Claim("wat-transformer-mode-collapse", "WAT Table 5",
          "Without weak supervision the Transformer model suffers from mode collapse: its diversity falls below "
          "the weakly-supervised Transformer's (the paper reports Div 0.01 vs 1.08 on GRAB).",
          (Part("transitions", "wat-transformer", "wat-transformer-no-weak", "div", "greater"),)),
    Claim("wat-padding", "WAT Table 5",
          "Padding raises recognition accuracy of action-conditioned futures.",
          (Part("transitions", "wat-rnn", "wat-rnn-no-padding", "acc_pose", "greater"),)),
    Claim("lcp-table4", "LCP-VAE Table 4",
          "The learned conditional prior (row 4) gives more diversity than the standard CVAE (row 2) at similar or better context.",
          (Part("walker_5s", "lcp-vae", "lcp-row2", "div", "greater"),
           Part("walker_5s", "lcp-vae", "lcp-row2", "acc_pose", "not_less"))),
    Claim("kp-diversity-temperature", "Keyposes Table 3",
          "Diversity increases with the sampling temperature.",
          chain("walker_5s", KP, "div", "greater")),
    Claim("kp-mpjpe-temperature", "Keyposes Table 3",
          "The best-sample MPJPE at 5 s decreases as the temperature increases.",
          chain("walker_5s", KP, "mpjpe_h_best", "less")),
    Claim("kp-moac-temperature", "Keyposes Table 3",
          "MOAC accuracy decreases as the temperature increases.",
          chain("walker_5s", KP, "acc_moac", "less")),
    Claim("kp-moac-baselines", "Keyposes Table 1",
          "Keyposes (T = 0.3) futures are recognised by the motion-only classifier more often than the baselines'.",
          (Part("walker_5s", "keyposes-t0.3", "regression-gru", "acc_moac", "greater"),
           Part("walker_5s", "keyposes-t0.3", "zero-velocity", "acc_moac", "greater"))),
]


@dataclass(frozen=True)
class Comparison:
    """Rows side by side on chosen columns, where a paper compares variants without a directional claim."""
    id: str
    paper: str
    text: str
    rows: tuple[str, ...]
    metrics: tuple[str, ...]
    tables: tuple[str, ...]


COMPARISONS: list[Comparison] = [
    Comparison("wat-rnn-vs-transformer", "WAT sec. 4.3, Tables 2-5",
               "WAT's two temporal encoders on the same training strategy: transition smoothness, diversity, "
               "recognisability and stopping (WAT reports the Transformer smoother and more diverse).",
               ("wat-rnn", "wat-transformer", "wat-rnn-no-weak", "wat-transformer-no-weak"),
               ("smooth", "div", "div_w", "acc_pose", "acc_moac", "stopped", "length"),
               ("transitions", "in_sample")),
]
