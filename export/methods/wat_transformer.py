"""WAT (Transformer): the RNN method's training strategy (weak supervision, padding, stopping, the
loss of Eq. 6, the delta fit) with the Transformer CVAE of Fig. 3b. Only the model differs, and the
exported graphs keep the RNN's signatures, so the browser runs it with the same WAT predictor."""
from __future__ import annotations

from torch import nn

from ..data.skeleton import SKELETON
from ..models.wat_transformer import WatTransformer
from .base import TrainingData
from .wat import WatMethod


class WatTransformerMethod(WatMethod):
    name = "wat_transformer"
    model_class = WatTransformer
    # configs/wat_transformer.json trains 8000 steps at the paper's lr 0.0005 (Table 5; was 4000 at 0.001),
    # as the RNN trains longer at its paper rate (methods/wat.py). Chosen on the training people's 2 s windows
    # (K = 10): best-of-10 ADE 0.650 -> 0.644 m, joint speed 0.55 / 0.35 -> 0.58 / 0.40 of the truth's in
    # seconds 1 / 2, truth outside 82 -> 76%, follow rho 0.72 -> 0.75 (foot skating with planted feet 0.050
    # -> 0.097 m/s, the captures' 0.088).
    # Issue 28, this pass: the RNN's input choices (models/inputs.py; in the Transformer the history's steps
    # enter the prior, the posterior and the decoder's padded sequence, the padding's steps being 0), its
    # slowed pairs and its prior-speed term (methods/wat.py), at this model's own speed weight (15), without
    # a grid. Measured as the RNN's table there (K = 10, 2 s): in 0.687, 0.57 / 0.42, follow 0.79, outside 87%;
    # out 0.799, 0.57 / 0.44, 0.72, 84%; the evaluation before this pass (docs/RESULTS.md of stop 37) had
    # out 0.922, 0.62 / 0.48, 0.39, 88%. On the held-out ballet and balance histories of person 49 (poses held
    # at 0.03 m/s) it gives 1.2-1.3x zero-velocity's ADE where the served RNN gives 1.8-2.1x: a decoder that
    # reads the padded history holds a pose more readily than one that feeds its own frames back.
    # Tried, not kept (stop 45): the RNN's KL weight 0.1 (Eq. 6's KL weight; methods/wat.py says why the RNN
    # serves it), alone and with the RNN's speed weight 15, 8000 steps each. The latent then carried ~25 nats.
    # In-sample 2 s windows (84, K = 10) at prior temperature 1.5 (ADE/ZV, joint speed / truth's in seconds 1 / 2,
    # truth outside, feet below the floor, hip vertical range / truth's in walks): served (t 2.5) 0.751, 0.61 /
    # 0.39, 21%, 1.6%, 1.8x; kl 0.1 0.884, 0.84 / 0.74, 27%, 18.9%, 2.5x; kl 0.1 + speed 15 0.916, 0.84 / 0.70,
    # 25%, 28.6%, 4.2x. At t 1 / 0.5 (kl 0.1): 0.934 / 1.072, feet below 18.9 / 18.6%. The futures move, but
    # the root bobs and sinks even at t 0.5: the floor term (3000 here) acts only on the posterior's
    # reconstructions, and with the prior 25 nats from the posterior its draws are futures that term never saw.
    # Also tried (stop 45), not kept: loss.prior_speed 30 (served 15) at kl 1, 8000 steps. In-sample at t 2.5:
    # ADE/ZV 0.751 -> 0.759, joint speed 0.61 / 0.39 -> 0.66 / 0.45, truth outside 21 -> 20%; held-out 2 s,
    # looked at afterwards: 0.849 -> 0.860, 0.59 / 0.41 -> 0.63 / 0.45. Twice the weight moves the speed a
    # tenth of the way to the truth's and no target crosses its limit.

    def build(self, data: TrainingData) -> nn.Module:
        # The decoder's padded sequence and positional encodings need N (the RNN does not).
        return self.model_class(SKELETON.num_joints, len(self.actions), self.future_frames,
                                history_frames=self.history_frames, **self.cfg.get("model", {}), **data.stats)
