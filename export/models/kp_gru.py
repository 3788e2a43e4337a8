"""KP-GRU (Keyposes paper, section 3.2.1, Fig. 3): a three-layer GRU cell stack and one fully
connected layer that, from the previous keypose's label distribution and duration class, predicts
the next keypose's label and duration class.

`step` is the exported graph (one keypose per call; the predictors run the loop). `forward` unrolls
the training sequence: observed keyposes (supervised too, Table 11), then predicted ones fed back
with scheduled sampling (Eq. 2).
"""
from __future__ import annotations

import torch
from torch import nn


class KPGRU(nn.Module):
    def __init__(self, clusters: int, durations: int, hidden: int, layers: int,
                 centre_proximity: torch.Tensor, temperature: float, noise: float):
        super().__init__()
        self.clusters, self.durations, self.hidden, self.layers = clusters, durations, hidden, layers
        self.cells = nn.ModuleList(nn.GRUCell(clusters + durations if i == 0 else hidden, hidden)
                                   for i in range(layers))
        self.head = nn.Linear(hidden, clusters + durations)
        # Proximity of every centre to every centre: a predicted label's distribution (3.2.1, case 2).
        self.register_buffer("centre_proximity", centre_proximity.float())
        self.temperature, self.noise = float(temperature), float(noise)

    def step(self, label_dist: torch.Tensor, duration: torch.Tensor, hidden: torch.Tensor):
        """[B, K], [B, D], [B, layers, H] -> label logits [B, K], duration logits [B, D], hidden."""
        x = torch.cat([label_dist, duration], dim=-1)
        states = []
        for i, cell in enumerate(self.cells):
            x = cell(x, hidden[:, i])
            states.append(x)
        out = self.head(x)
        return out[:, :self.clusters], out[:, self.clusters:], torch.stack(states, dim=1)

    def distribution(self, proximity: torch.Tensor) -> torch.Tensor:
        """softmax(proximity / T); in training with Gaussian noise on the proximities (Table 7)."""
        if self.training and self.noise > 0:
            proximity = proximity + self.noise * torch.randn_like(proximity)
        return torch.softmax(proximity / self.temperature, dim=-1)

    def forward(self, obs_proximity, obs_duration, obs_mask, fut_label, fut_duration, teacher: bool):
        """Observed keyposes [B, I1, ...] (left-padded, mask [B, I1]) then I2 future targets.

        Returns label and duration logits [B, I1 - 1 + I2, ...]: output s predicts keypose s + 1 of
        the concatenated sequence. Future inputs are the true label and duration when `teacher`,
        else the model's own most probable ones (as the paper trains, 3.2.1).
        """
        b, n_obs = obs_mask.shape
        h = obs_proximity.new_zeros(b, self.layers, self.hidden)
        labels, durs = [], []
        for s in range(n_obs):
            dist = self.distribution(obs_proximity[:, s])
            lo, do, h_new = self.step(dist, obs_duration[:, s], h)
            m = obs_mask[:, s, None, None]
            h = m * h_new + (1 - m) * h        # padding steps leave the state alone
            labels.append(lo)
            durs.append(do)
        eye_d = torch.eye(self.durations, device=h.device)
        for j in range(fut_label.shape[1] - 1):
            if teacher:
                lab, dur = fut_label[:, j], fut_duration[:, j]
            else:
                lab, dur = labels[-1].argmax(-1), durs[-1].argmax(-1)
            lo, do, h = self.step(self.distribution(self.centre_proximity[lab]), eye_d[dur], h)
            labels.append(lo)
            durs.append(do)
        return torch.stack(labels, 1), torch.stack(durs, 1)


class KPGRUStep(nn.Module):
    """The exported graph: one KP-GRU step."""

    def __init__(self, gru: KPGRU):
        super().__init__()
        self.gru = gru

    def forward(self, label_dist, duration, hidden):
        return self.gru.step(label_dist, duration, hidden)
