"""What the results compare: rows (what predicts) and the papers' claims (which rows should win).

Adding a method row is one line: a Row naming its config (configs/<name>.json when served,
configs/ablations/<name>.json when not), the controls it predicts with, and optionally the
tables it belongs to. Rows whose config, method or predictor does not exist yet, or whose
model has not been trained, are skipped by the harness with a note saying which.

Training seed 0 of a served config is the model in public/models; the other seeds (and every
seed of an ablation) are trained by `make results` into runs/seeds/<model id>/seed<s>/.

Row kinds:
- "model": a trained model through the Python predictor (the browser's code path);
- "baseline": a pure function of export/eval/baselines.py on the world-frame history ("constant_velocity",
  "repeat_cycle" with `history` frames, "nearest_window" over the training people's windows);
- "projected": the futures of row `parent`, bone-projected onto the history's bone lengths
  (ops/bones.project_lengths): an extra row after the raw outputs (issue 19);
- "oracle" (the ground truth) and "noise" (the ground truth + Gaussian noise, a sanity row).
"""
from __future__ import annotations

from dataclasses import dataclass, field

from ..config import load_config


@dataclass(frozen=True)
class Row:
    id: str
    label: str
    kind: str = "model"                  # "model", "baseline", "projected", "oracle" or "noise"
    config: str | None = None            # a file in configs/ (models only)
    controls: dict = field(default_factory=dict)
    tables: tuple[str, ...] | None = None  # None: every table the row can run in
    group: str = "baselines"
    note: str = ""
    baseline: str | None = None          # baselines: the function
    history: int | None = None           # baselines: history frames it reads (at most, for the long variant)
    parent: str | None = None            # projected rows: the raw row
    extract: str = "mean"                # Keyposes: the keypose extraction rule at prediction (ops/keyposes.py)
    plant_feet: bool = True              # models: the feet on the floor carry the root (ops/foot_plant.py)


HELD_OUT = ("heldout_1s", "heldout_2s")
LONG = "heldout_5s"
TRANSITIONS = "transitions"
IN_SAMPLE = "in_sample"
KP_TEMPERATURES = (0.1, 0.3, 0.5, 1.0)
KP_SERVED = load_config("keyposes.json")["sampling"]["temperature"]   # export/methods/keyposes.py says why
SERVED_ONLY = (*HELD_OUT, LONG, IN_SAMPLE)

ROWS: list[Row] = [
    Row("oracle", "Ground truth (oracle)", kind="oracle", note="the captured frames themselves"),
    Row("noise", "Ground truth + Gaussian noise (sanity)", kind="noise", group="sanity", tables=("heldout_1s",),
        note="K samples of truth + N(0, sigma^2) per coordinate; its diversity is known in closed form"),
    # Baselines that expose copying and memorising (issue 18, item 2).
    Row("zero-velocity", "Zero-velocity", config="zero_velocity.json"),
    Row("constant-velocity", "Constant velocity", kind="baseline", baseline="constant_velocity", history=2,
        tables=(*HELD_OUT, LONG), note="every joint keeps its last velocity"),
    *[Row(f"repeat-cycle-{h}", f"Repeat last cycle ({h}-frame history)", kind="baseline", baseline="repeat_cycle",
          history=h, tables=(*HELD_OUT, LONG),
          note=f"the best period (8 to {h // 2} frames) of the last {h} frames, continued; the history of "
               + {10: "WAT and the regression GRU", 19: "LCP-VAE", 30: "Keyposes"}[h]
               + ("; too short for a period, so it holds the last pose" if h < 16 else ""))
      for h in (10, 19, 30)],
    Row("repeat-cycle-60", "Repeat last cycle (longer history, up to 60 frames)", kind="baseline",
        baseline="repeat_cycle", history=60, tables=(*HELD_OUT, LONG),
        note="labelled variant: 10 frames cannot hold a gait cycle, so this one reads up to 60 frames (as many "
             "as the take holds before the present, at least the table's history)"),
    Row("nearest-window", "Nearest training window", kind="baseline", baseline="nearest_window", history=10,
        tables=(*HELD_OUT, LONG), note="the future of the training window whose 10-frame history is closest "
                                      "(L2 over the root-relative poses, both canonical at their last frame), among every "
                                      "window of the training people (configs/eval.json \"nearest\"), mirrors included as the models train; "
                                      "the bank is searched clip by clip with one matrix product each, so it stays small "
                                      "and fast, and the chosen future is turned and moved onto the held-out history"),
    Row("regression-gru", "Regression GRU", config="regression.json"),
    # WAT (issue 5): served model and the ablations of its Table 5; the shape-term ablation (issue 17).
    Row("wat-rnn", "WAT (RNN)", config="wat_rnn.json", group="wat", tables=(*HELD_OUT, TRANSITIONS, IN_SAMPLE)),
    Row("wat-rnn-no-weak", "WAT (RNN) w/o weak supervision", config="ablations/wat_rnn_no_weak.json", group="wat",
        tables=(TRANSITIONS,)),
    Row("wat-rnn-no-padding", "WAT (RNN) w/o padding", config="ablations/wat_rnn_no_padding.json", group="wat",
        tables=(TRANSITIONS,)),
    Row("wat-rnn-no-shape", "WAT (RNN) w/o shape terms", config="ablations/wat_rnn_no_shape.json", group="wat",
        tables=HELD_OUT),
    Row("wat-rnn-paper-loss", "WAT (RNN) with the paper's Eq. 6 (no speed and skate terms)",
        config="ablations/wat_rnn_paper_loss.json", group="wat", tables=HELD_OUT,
        note="the served model's labelled variant terms (export/ops/speed_term.py, skate_term.py) off"),
    Row("wat-transformer", "WAT (Transformer)", config="wat_transformer.json", group="wat",
        tables=(*HELD_OUT, TRANSITIONS, IN_SAMPLE)),
    Row("wat-transformer-no-weak", "WAT (Transformer) w/o weak supervision",
        config="ablations/wat_transformer_no_weak.json", group="wat", tables=(TRANSITIONS,)),
    Row("wat-transformer-no-shape", "WAT (Transformer) w/o shape terms",
        config="ablations/wat_transformer_no_shape.json", group="wat", tables=HELD_OUT),
    Row("wat-transformer-paper-loss", "WAT (Transformer) with the paper's Eq. 6 (no speed and skate terms)",
        config="ablations/wat_transformer_paper_loss.json", group="wat", tables=HELD_OUT,
        note="the served model's labelled variant terms (export/ops/speed_term.py, skate_term.py) off"),
    # LCP-VAE (issue 7): the served model (Table 4 row 4), rows 2 and 3, and the shape-term ablation.
    Row("lcp-vae", "LCP-VAE (row 4: h_t / reparam z_c)", config="lcp_vae.json", group="lcp_vae"),
    Row("lcp-row2", "CVAE (row 2: h_t / concat h_t)", config="ablations/lcp_cvae_h.json", group="lcp_vae",
        tables=("heldout_2s",)),
    Row("lcp-row3", "CVAE (row 3: z_c / concat z_c)", config="ablations/lcp_cvae_zc.json", group="lcp_vae",
        tables=("heldout_2s",)),
    Row("lcp-vae-no-shape", "LCP-VAE w/o shape terms", config="ablations/lcp_no_shape.json", group="lcp_vae",
        tables=HELD_OUT),
    Row("lcp-vae-paper-loss", "LCP-VAE with the paper's Eq. 9 (no speed and skate terms)",
        config="ablations/lcp_paper_loss.json", group="lcp_vae", tables=HELD_OUT,
        note="the served model's labelled variant terms (export/ops/speed_term.py, skate_term.py) off"),
    # Issue 28: the served models sample wider than the papers (WAT's prior temperature, LCP-VAE's sigma scale,
    # export/methods/wat.py and lcp_vae.py); these rows draw as the papers do, on the same windows and seeds.
    *[Row(f"{p}-paper-draw", f"{label}, {what} (the paper's draw)", config=cfg, controls=ctl, group=g,
          tables=HELD_OUT, note=f"the served model sampled at {what}; the served row samples at the config's value")
      for p, label, cfg, ctl, what, g in (
          ("wat-rnn", "WAT (RNN)", "wat_rnn.json", {"temperature": 1.0}, "prior temperature 1", "wat"),
          ("wat-transformer", "WAT (Transformer)", "wat_transformer.json", {"temperature": 1.0}, "prior temperature 1",
           "wat"),
          ("lcp-vae", "LCP-VAE", "lcp_vae.json", {"sigma_scale": 1.0}, "sigma scale 1", "lcp_vae"))],
    # Keyposes (issue 8). The paper's tables interpolate linearly (refine off); the site serves the refinement.
    # The served temperature is 1.2 (configs/keyposes.json "sampling", chosen on training people; the
    # paper's 0.3 stays in the linear rows its tables compare; 0.6 was served before issue 28's spread).
    Row("keyposes", f"Keyposes (T = {KP_SERVED}, refined: served)", config="keyposes.json",
        controls={"temperature": KP_SERVED, "refine": True}, group="keyposes"),
    Row("keyposes-t0.6-refined", "Keyposes (T = 0.6, refined), served before", config="keyposes.json",
        controls={"temperature": 0.6, "refine": True}, group="keyposes", tables=(*HELD_OUT, LONG),
        note="the served model sampled at 0.6, the temperature served before issue 28; the served row samples "
             "at the config's value"),
    *[Row(f"keyposes-t{t}", f"Keyposes (T = {t}, linear)", config="keyposes.json",
          controls={"temperature": t, "refine": False}, group="keyposes",
          tables=(*HELD_OUT, LONG) if t == 0.3 else (LONG,)) for t in KP_TEMPERATURES],
    Row("keyposes-max-rule", f"Keyposes (T = {KP_SERVED}, refined), max-error extraction", config="keyposes.json",
        controls={"temperature": KP_SERVED, "refine": True}, group="keyposes", extract="max", tables=(*HELD_OUT, LONG),
        note="evaluation variant: the history's keyposes by the authors' code's rule (a segment splits until its "
             "largest error is below the threshold), the served model otherwise"),
    Row("keyposes-no-shape", f"Keyposes w/o shape terms (T = {KP_SERVED}, refined)",
        config="ablations/keyposes_no_shape.json", controls={"temperature": KP_SERVED, "refine": True},
        group="keyposes", tables=(*HELD_OUT, LONG)),
    Row("keyposes-32-clusters", "Keyposes, 32 clusters (T = 0.3, linear)", config="ablations/keyposes_32_clusters.json",
        controls={"temperature": 0.3, "refine": False}, group="keyposes", tables=(LONG,)),
    Row("keyposes-noise-1x", "Keyposes, lighter label noise (T = 0.3, linear)",
        config="ablations/keyposes_noise_1x.json", controls={"temperature": 0.3, "refine": False}, group="keyposes",
        tables=(LONG,)),
    # Issue 28: the served rows plant their feet as the site does (ops/foot_plant.py, a post-process of ours);
    # these rows keep each method's own root travel, on the same windows.
    *[Row(f"{p}-own-root", f"{label}, own root (feet not planted)", config=cfg, controls=ctl, group=g,
          plant_feet=False, tables=("heldout_2s",),
          note="the served model with ops/foot_plant.py off: the root travels as the method predicts it")
      for p, label, cfg, ctl, g in (
          ("regression-gru", "Regression GRU", "regression.json", {}, "baselines"),
          ("wat-rnn", "WAT (RNN)", "wat_rnn.json", {}, "wat"),
          ("wat-transformer", "WAT (Transformer)", "wat_transformer.json", {}, "wat"),
          ("lcp-vae", "LCP-VAE", "lcp_vae.json", {}, "lcp_vae"),
          ("keyposes", f"Keyposes (T = {KP_SERVED}, refined)", "keyposes.json",
           {"temperature": KP_SERVED, "refine": True}, "keyposes"))],
    # Issue 19: raw outputs first, then the served models' futures bone-projected, labelled as such.
    *[Row(f"{p}-projected", f"{label}, bone-projected (extra)", kind="projected", parent=p, group=g,
          tables=("heldout_2s",), note="the raw row's futures with every bone set to its mean length in the "
                                       "model's history (ops/bones.project_lengths), directions kept")
      for p, label, g in (("regression-gru", "Regression GRU", "baselines"), ("wat-rnn", "WAT (RNN)", "wat"),
                          ("wat-transformer", "WAT (Transformer)", "wat"), ("lcp-vae", "LCP-VAE", "lcp_vae"),
                          ("keyposes", "Keyposes (served)", "keyposes"))],
]


@dataclass(frozen=True)
class Part:
    """One comparison: (row a, metric a) against (row b, metric b) in a table, in a direction
    ("greater", "less", "not_less" = similar or better within `margin`, "not_greater").
    `construction`: why this part is true by construction (reported, never counted)."""
    table: str
    a: str
    b: str
    metric: str
    direction: str
    metric_b: str | None = None          # another column of row b (default: the same metric)
    margin: float = 0.0                  # "similar": how far the wrong way still counts as similar
    construction: str = ""


@dataclass(frozen=True)
class Claim:
    id: str
    paper: str
    text: str
    parts: tuple[Part | Trend, ...]
    construction: str = ""               # the whole claim holds by construction: labelled, not counted


@dataclass(frozen=True)
class Trend:
    """A monotone trend of one metric over rows that differ in one setting (a control, read from ROWS), listed in
    the setting's increasing order; direction "greater" (rises with the setting) or "less" (falls). Tested as one
    trend (stats.trend: the bootstrapped least-squares slope against the settings' rank), not as consecutive pairs,
    which can each be inconclusive while the whole runs the other way."""
    table: str
    rows: tuple[str, ...]
    metric: str
    direction: str
    setting: str = "temperature"

    def __post_init__(self):
        values = self.settings()
        if len(values) < 2 or any(x >= y for x, y in zip(values, values[1:])):
            raise ValueError(f"a trend's rows must have increasing {self.setting}s, got {values}")

    def settings(self) -> list:
        by_id = {r.id: r for r in ROWS}
        return [by_id[r].controls[self.setting] for r in self.rows]


KP = [f"keyposes-t{t}" for t in KP_TEMPERATURES]
STILL = ("MOAC sees only velocities and has a 'no motion' class; a zero-velocity future is exactly motionless, "
         "so MOAC calls it 'no motion' and scores it 0 whatever the data")

CLAIMS: list[Claim] = [
    Claim("lcp-context-bounds", "LCP-VAE Table 2",
          "A zero-velocity future keeps less context (action recognisability) than the ground truth.",
          (Part("heldout_2s", "oracle", "zero-velocity", "acc_pose", "greater"),)),
    Claim("moac-static", "Keyposes sec. 4.3",
          "The motion-only classifier does not reward a static prediction: zero-velocity scores below the ground truth on MOAC.",
          (Part("heldout_2s", "oracle", "zero-velocity", "acc_moac", "greater"),), construction=STILL),
    Claim("fac-static", "Keyposes appendix 6.6, Table 16",
          "A pose-based classifier rewards a static prediction more than the motion-only one does.",
          (Part("heldout_2s", "zero-velocity", "zero-velocity", "acc_pose", "greater", metric_b="acc_moac"),),
          construction=STILL),
    Claim("wat-ade", "WAT Table 3 (issue 5)",
          "WAT's best-of-K ADE beats zero-velocity and the regression GRU on held-out people, 1 s and 2 s ahead.",
          (Part("heldout_1s", "wat-rnn", "zero-velocity", "ade", "less"),
           Part("heldout_1s", "wat-rnn", "regression-gru", "ade", "less"),
           Part("heldout_2s", "wat-rnn", "zero-velocity", "ade", "less"),
           Part("heldout_2s", "wat-rnn", "regression-gru", "ade", "less"))),
    Claim("wat-weak-supervision", "WAT Table 5",
          "Weak supervision raises recognition accuracy and diversity of action-conditioned futures.",
          (Part(TRANSITIONS, "wat-rnn", "wat-rnn-no-weak", "acc_pose", "greater"),
           Part(TRANSITIONS, "wat-rnn", "wat-rnn-no-weak", "div", "greater"))),
    Claim("wat-transformer-mode-collapse", "WAT Table 5",
          "Without weak supervision the Transformer model suffers from mode collapse: its diversity falls below "
          "the weakly-supervised Transformer's (the paper reports Div 0.01 vs 1.08 on GRAB).",
          (Part(TRANSITIONS, "wat-transformer", "wat-transformer-no-weak", "div", "greater"),)),
    Claim("wat-padding", "WAT Table 5",
          "Padding raises recognition accuracy of action-conditioned futures.",
          (Part(TRANSITIONS, "wat-rnn", "wat-rnn-no-padding", "acc_pose", "greater"),)),
    Claim("lcp-table4", "LCP-VAE Table 4",
          "The learned conditional prior (row 4) gives more diversity than the standard CVAE (row 2) at similar "
          "or better context (pose-GRU accuracy at most 5 points lower).",
          (Part("heldout_2s", "lcp-vae", "lcp-row2", "apd", "greater"),
           Part("heldout_2s", "lcp-vae", "lcp-row2", "acc_pose", "not_less", margin=5.0))),
    Claim("kp-diversity-temperature", "Keyposes Table 3",
          "Diversity increases with the sampling temperature.",
          (Trend(LONG, tuple(KP), "apd", "greater"),)),
    Claim("kp-mpjpe-temperature", "Keyposes Table 3",
          "The best-sample MPJPE at 5 s decreases as the temperature increases.",
          (Trend(LONG, tuple(KP), "mpjpe_h_best", "less"),)),
    Claim("kp-moac-temperature", "Keyposes Table 3",
          "MOAC accuracy decreases as the temperature increases.",
          (Trend(LONG, tuple(KP), "acc_moac", "less"),)),
    Claim("kp-moac-baselines", "Keyposes Table 1",
          "Keyposes (T = 0.3) futures are recognised by the motion-only classifier more often than the baselines'.",
          (Part(LONG, "keyposes-t0.3", "regression-gru", "acc_moac", "greater"),
           Part(LONG, "keyposes-t0.3", "zero-velocity", "acc_moac", "greater", construction=STILL))),
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
               ("smooth", "smooth_unsq", "div", "div_w", "acc_pose", "acc_moac", "stopped", "length"),
               (TRANSITIONS,)),
    Comparison("keyposes-protocols", "Keyposes sec. 3.3 and 4 (issue 18, item 6)",
               "Keyposes as the paper's tables run it (linear interpolation) and as the site serves it (refinement), "
               "and with the history's keyposes extracted by the authors' code's max-error rule.",
               ("keyposes-t0.3", "keyposes", "keyposes-max-rule"),
               ("ade", "fde", "mpjpe_h_best", "apd", "acc_moac", "smooth", "smooth_unsq", "foot"),
               (*HELD_OUT, LONG)),
]

# Issue 17's shape terms: each stochastic model with and without them (APD and best-of-K ADE, within 10%?).
SHAPE_PAIRS: list[tuple[str, str]] = [
    ("wat-rnn", "wat-rnn-no-shape"), ("wat-transformer", "wat-transformer-no-shape"),
    ("lcp-vae", "lcp-vae-no-shape"), ("keyposes", "keyposes-no-shape")]
SHAPE_METRICS = ("apd", "ade")
SHAPE_TOLERANCE = 0.10
