"""Keyposes (Kiciroglu et al.): long-term prediction as keypose classification.

prepare: extract keyposes (section 3.1), cluster them with k-means, pick the label temperature,
and cut training sequences of observed and future keyposes from windows of the split's train part
(each history's keyposes from its own frames only, as at prediction time). The model is KP-GRU
(3.2.1) plus the refinement GCN (appendix 6.4), trained together (their parameters are disjoint).
"""
from __future__ import annotations

import numpy as np
import torch
from sklearn.cluster import KMeans
from torch import nn
from torch.nn import functional as F

from ..data.clip import Clip
from ..data.skeleton import SKELETON
from ..data.sources import FPS
from ..data.windows import Window, window_weights, windows
from ..models.kp_gru import KPGRU, KPGRUStep
from ..models.kp_refine import RefineGCN
from ..ops import keyposes as kp
from ..ops.keypose_interpolation import interpolate
from ..ops.facing import root_relative, split_root
from ..ops.floor import floor_penalty
from ..ops.keypose_travel import facing_velocities, velocity_table
from ..ops.mirror import mirror_positions
from ..ops.proximity import NOISE_PER_TEMPERATURE, choose_temperature, face_forward, proximity, softmax
from .base import GraphDef, Method, TensorSpec, TrainingData

J = SKELETON.num_joints
D = len(kp.DURATION_BOUNDS)


def train_motions(clips: list[Clip], mirror: bool) -> list[np.ndarray]:
    """Every train range as a motion carrying the root channel (export/ops/facing.py), and its mirror image."""
    parts = [part for clip in clips for part in clip.part("train") if len(part)]
    parts += [mirror_positions(part, SKELETON) for part in parts] if mirror else []
    return [split_root(part) for part in parts]


def cluster_keyposes(clips: list[Clip], threshold: float, mirror: bool) -> np.ndarray:
    """Every keypose of every train range (extracted per range, as the paper per training motion, from
    its root-relative poses), each turned to face +z, plus their mirror images: [n, J, 3]."""
    poses = []
    for clip in clips:
        for part in clip.part("train"):
            if len(part):
                part = root_relative(split_root(part))
                poses.append(part[kp.extract(part, threshold)])
    poses = np.concatenate(poses) if poses else np.zeros((0, J, 3))
    out = face_forward(poses)
    if mirror:
        out = np.concatenate([out, face_forward(mirror_positions(poses, SKELETON))])
    return out


def centre_distances(values: np.ndarray, centres: np.ndarray) -> dict:
    """Mean distance of each keypose to its centre: L2 over the pose (the extraction's error) and
    mean per joint."""
    labels, _ = kp.nearest_centre(values, centres)
    d = values - centres[labels]
    return {"l2": float(np.sqrt((d ** 2).sum((-1, -2))).mean()),
            "per_joint": float(np.linalg.norm(d, axis=-1).mean())}


_BONES = np.zeros((J, len(SKELETON.bones)), np.float32)
for _b, (_parent, _child) in enumerate(SKELETON.bones):
    _BONES[_child, _b], _BONES[_parent, _b] = 1.0, -1.0


def bone_lengths(positions: torch.Tensor) -> torch.Tensor:
    """[..., J, 3] -> [..., bones]; a product with a fixed +-1 matrix, because gathering joints is
    slow to differentiate under deterministic algorithms."""
    bones = torch.einsum("...jc,jb->...bc", positions, torch.from_numpy(_BONES))
    return (bones * bones).sum(-1).clamp_min(1e-12).sqrt()


def accuracy(labels, durations, target_l, target_d, mask) -> tuple[torch.Tensor, torch.Tensor]:
    """Top-1 accuracy of the label and duration predictions over the masked targets."""
    n = mask.sum().clamp_min(1)
    return (((labels.argmax(-1) == target_l).float() * mask).sum() / n,
            ((durations.argmax(-1) == target_d).float() * mask).sum() / n)


def targets(batch: dict) -> tuple[torch.Tensor, torch.Tensor, torch.Tensor]:
    """Output s predicts keypose s + 1: observed ones (past supervision, Table 11), then the future."""
    target_l = torch.cat([batch["obs_label"][:, 1:], batch["fut_label"]], 1)
    target_d = torch.cat([batch["obs_duration"][:, 1:].argmax(-1), batch["fut_duration"]], 1)
    mask = torch.cat([batch["obs_mask"][:, :-1], batch["fut_mask"]], 1)
    return target_l, target_d, mask


@torch.no_grad()
def keypose_accuracy(model: "KeyposesNet", data: TrainingData, max_observed: int) -> dict:
    """Greedy KP-GRU accuracy on keypose sequences (no noise, own predictions fed back, as
    the paper's ablations evaluate): past (observed) and future keyposes separately."""
    model.eval()
    t = data.tensors
    labels, durations = model.gru(t["obs_proximity"], t["obs_duration"], t["obs_mask"], t["fut_label"],
                                  t["fut_duration"], False)
    target_l, target_d, mask = targets(t)
    past = torch.zeros_like(mask)
    past[:, :max_observed - 1] = 1
    out = {}
    for name, m in [("past", mask * past), ("future", mask * (1 - past))]:
        acc_l, acc_d = accuracy(labels, durations, target_l, target_d, m)
        out[name] = {"label": float(acc_l), "duration": float(acc_d), "targets": int(m.sum())}
    return out


class KeyposesNet(nn.Module):
    """KP-GRU and the refinement GCN, with the centres they were trained for."""

    def __init__(self, gru: KPGRU, refine: RefineGCN, centres: torch.Tensor):
        super().__init__()
        self.gru, self.refine = gru, refine
        self.register_buffer("centres", centres.float())

    def forward(self, obs_proximity, obs_duration, obs_mask, fut_label, fut_duration, refine_input, teacher: bool):
        labels, durations = self.gru(obs_proximity, obs_duration, obs_mask, fut_label, fut_duration, teacher)
        return labels, durations, self.refine(refine_input)


class KeyposesMethod(Method):
    name = "keyposes"

    def __init__(self, cfg: dict):
        super().__init__(cfg)
        k = cfg.get("keyposes", {})
        # The served config (issue "Futures that move like people", measured on held-out people, 2 s):
        # - threshold 0.2 m (whole-pose L2, 4.7 cm per joint): the paper's CMU setting, 250 mm on 38
        #   joints, is 4.1 cm per joint; 0.3 m found 3.5 keyposes per 1 s history, 0.2 finds 4.5;
        # - min_observed 2 (the paper sets none; its histories are 2 s): a history's first and last
        #   frames are keyposes, so every history can be read. 3 refused 34% of held-out 1 s windows,
        #   every ballet and salsa clip at its default start;
        # - 192 clusters (the paper: 100 on CMU, 1000 on Human3.6M): data v2 gives 12,798 training
        #   keyposes at 0.2 m; 128 centres lay 0.42 m from their members, 256 lie 0.37 m, but 256 put
        #   the step and refinement graphs at 320 KB gzipped, past Keyposes' 0.3 MB cap.
        self.threshold = float(k.get("threshold", kp.THRESHOLD))
        # The served sampling temperature (sec. 3.3 sets 0.3; its Table 3 shows diversity and best-of-K
        # MPJPE improving as it rises, at some cost in action accuracy). Chosen on the training people's
        # 2 s windows (in-sample table, K = 10), never on held-out ones: best-of-10 ADE 0.781 / 0.764 /
        # 0.800 m at 0.3 / 0.6 / 1.0, truth outside every sample 77% / 60% / 37%: 0.6.
        # Issue 28 (configs/keyposes.json sampling.temperature 1.2, was 0.6): after split_holds and 4000 steps
        # the truth lay outside every sample in 38% of those windows at 0.6 (held out: 42% at 1 s, 45% at 2 s).
        # The rule WAT and LCP-VAE's spreads were chosen by (the first value whose truth-outside is within twice
        # the calibrated 9%) is not reached inside the control's range: best-of-10 ADE / zero-velocity's, truth
        # outside, pose spread of 10 at the last frame, at 0.6 / 0.8 / 1.0 / 1.2 / 1.4: 0.676 / 0.695 / 0.700 /
        # 0.718 / 0.740, 38 / 38 / 31 / 21 / 20%, 13.9 / 15.0 / 16.3 / 17.0 / 18.6 cm. 1.2 is where the
        # truth-outside curve flattens; 1.4 buys one point for 0.022 of ADE ratio.
        self.sampling_temperature = float(cfg.get("sampling", {}).get("temperature", 0.3))
        self.clusters = int(k.get("clusters", 128))
        self.mirror = bool(k.get("mirror", True))
        self.target_top = float(k.get("target_top_probability", 0.6))
        self.min_observed = int(k.get("min_observed", 3))
        self.max_observed = int(k.get("max_observed", 10))
        self.predicted = int(k.get("predicted", 12))
        self.min_future = int(k.get("min_future_frames", 20))
        # Labelled variant `split_holds` (the paper prunes, sec. 3.2, and bounds no gap): training futures
        # get a keypose every 30 frames (the longest duration class, 3.2.1) inside a longer gap, so a held
        # pose is learnt as its own label again; off, a 3 s hold is one "very long" step, played as 30
        # frames before the next keypose. Served on, with 4000 steps (see `train.steps` below).
        self.split_holds = bool(k.get("split_holds", False))
        # train.steps 4000 (was 800, about 5 epochs of the ~20k windows; the paper trains 100 epochs, 3.2.1).
        # Chosen on the training people's 2 s windows (K = 10, best-of-10 ADE / zero-velocity's, truth
        # outside every sample, follow rho): 800 steps 0.781 / 52% / 0.37; 4000 steps without split_holds
        # 0.700 / 54% / 0.11; 4000 with it 0.676 / 38% / 0.21 (label accuracy 0.33 -> 0.52). Looked at on
        # held-out people afterwards (issue 28's note): 2 s 0.971 -> 0.982 (4000, off) -> 0.939 (served).
        self.refine_frames = self.future_frames       # the refinement graph's length = the longest horizon
        self.notes: dict = {}

    # --- data -------------------------------------------------------------------------------
    def prepare(self, clips: list[Clip]) -> TrainingData:
        values = cluster_keyposes(clips, self.threshold, self.mirror)
        if len(values) < self.clusters:
            raise ValueError(f"only {len(values)} training keyposes for {self.clusters} clusters")
        seed = int(self.cfg.get("train", {}).get("seed", 0))
        km = KMeans(self.clusters, n_init=10, random_state=seed).fit(values.reshape(len(values), -1))
        # Rounded once here, so training, the JSON file and both predictors use the same numbers.
        self.centres = np.round(km.cluster_centers_.reshape(self.clusters, J, 3), 5)
        self.temperature = choose_temperature(values, self.centres, self.target_top)
        # Table 7's noise, scaled to our units (see NOISE_PER_TEMPERATURE); configurable for ablations.
        self.noise = float(self.cfg.get("loss", {}).get("label_noise", NOISE_PER_TEMPERATURE)) * self.temperature
        self.root_velocity = self.travel_table(clips)
        top = softmax(proximity(values, self.centres), self.temperature).max(-1)
        self.notes = {"cluster_keyposes": len(values), "centre_distance": centre_distances(values, self.centres),
                      "label_temperature": self.temperature, "mean_top_probability": float(top.mean())}

        data = self.sequences(clips, "train")
        self.notes.update(data.notes)
        self.examples = len(data)
        return TrainingData(data.tensors, {}, self.notes, data.weights)

    def travel_table(self, clips: list[Clip]) -> np.ndarray:
        """The root channel's velocity per cluster (export/ops/keypose_travel.py) from every train range."""
        segments = []
        for motion in train_motions(clips, self.mirror):
            poses = root_relative(motion)
            keys = kp.extract(poses, self.threshold)
            labels, _ = kp.nearest_centre(face_forward(poses[keys]), self.centres)
            steps = facing_velocities(motion)
            segments += [(int(labels[i + 1]), steps[keys[i]:keys[i + 1]]) for i in range(len(keys) - 1)]
        return velocity_table(segments, self.clusters)

    def sequences(self, clips: list[Clip], part: str) -> TrainingData:
        """Observed and future keypose sequences (and refinement pairs) of every window of `part`;
        windows whose history yields fewer than min_observed keyposes are left out, as the
        predictors reject them."""
        rows, kept, observed_counts, future_counts = [], [], [], []
        for w in self._windows(clips, part):
            row = self._sequence(w)
            observed_counts.append(row.pop("observed_count"))
            future_counts.append(row.pop("future_count"))
            if observed_counts[-1] >= self.min_observed:
                rows.append(row)
                kept.append(w)
        if not rows:
            raise ValueError(f"no {part} window yields {self.min_observed} keyposes")
        tensors = {k: torch.from_numpy(np.stack([r[k] for r in rows])) for k in rows[0]}
        return TrainingData(tensors, {}, {"windows": len(rows), "skipped_few_keyposes": len(observed_counts) - len(rows),
                                          "observed_histogram": np.bincount(observed_counts).tolist(),
                                          "future_histogram": np.bincount(future_counts).tolist()},
                            window_weights(kept))

    def _windows(self, clips: list[Clip], part: str = "train") -> list[Window]:
        """Windows of history + refine_frames from `part` (loops wrap); where a range ends sooner,
        the windows whose future runs to the end of the range, down to min_future frames."""
        n, r = self.history_frames, self.refine_frames
        stride = int(self.cfg.get("train", {}).get("stride", 1))
        out = []
        for clip in clips:
            ranges = clip.split.train if part == "train" else clip.split.test
            full = windows([clip], part, n + r, n, stride=stride, mirror=self.mirror)
            covered = {int(w.frames[n - 1]) for w in full}
            out += full
            ends = {b - 1 for _, b in ranges}
            if all(p in covered for a, b in ranges for p in range(a + n - 1, b - self.min_future)):
                continue
            for f in range(r - 1, self.min_future - 1, -1):
                for w in windows([clip], part, n + f, n, stride=stride, mirror=self.mirror, wrap=False):
                    if int(w.frames[-1]) in ends and int(w.frames[n - 1]) not in covered:
                        out.append(w)
        return out

    def _sequence(self, w: Window) -> dict:
        n, r = self.history_frames, self.refine_frames
        poses = root_relative(w.positions)                             # keyposes act on root-relative poses
        hist, future = poses[:n], poses[n - 1:]                        # the present is in both
        # Observed keyposes: from the history's own frames, labelled, pruned (as the predictors do).
        obs = kp.extract(hist, self.threshold)
        obs_values = face_forward(hist[obs])
        obs_labels, _ = kp.nearest_centre(obs_values, self.centres)
        keep = kp.prune(obs_labels)
        obs = [obs[i] for i in keep]
        obs_values, obs_labels = obs_values[keep], obs_labels[keep]
        observed_count = len(obs)
        obs, obs_values, obs_labels = obs[-self.max_observed:], obs_values[-self.max_observed:], obs_labels[-self.max_observed:]

        # Future keyposes: extracted from the present on; the present leads the pruning.
        fut = kp.extract(future, self.threshold)
        fut_values = face_forward(future[fut])
        fut_labels, _ = kp.nearest_centre(fut_values, self.centres)
        keep = kp.prune(fut_labels)
        fut = [fut[i] for i in keep]
        if self.split_holds:
            # Pruning (sec. 3.2) turns a 3 s hold into one "very long" step, which the predictors play
            # as 30 frames (Eq. 3) and then move on; split, the hold is a run of its own label.
            fut = kp.bound_gaps(fut, max(kp.DURATION_LENGTHS))
        fut_labels, _ = kp.nearest_centre(face_forward(future[fut]), self.centres)
        fut, fut_labels = fut[1:], fut_labels[1:]
        durations = np.diff([0] + fut)

        i1, i2 = self.max_observed, self.predicted
        pad = i1 - len(obs)
        obs_prox = np.zeros((i1, self.clusters), np.float32)
        obs_prox[pad:] = proximity(obs_values, self.centres)
        obs_dur = np.zeros((i1, D), np.float32)
        for i in range(1, len(obs)):                                 # the first fed keypose: no duration
            obs_dur[pad + i, kp.duration_class(obs[i] - obs[i - 1])] = 1
        obs_mask = np.zeros(i1, np.float32)
        obs_mask[pad:] = 1
        obs_label = np.zeros(i1, np.int64)
        obs_label[pad:] = obs_labels
        # The window's last frame is a keypose only because the window ends there: not a target.
        targets = len(fut) - 1
        fut_label = np.zeros(i2, np.int64)
        fut_dur = np.zeros(i2, np.int64)
        fut_mask = np.zeros(i2, np.float32)
        m = min(targets, i2)
        fut_label[:m] = fut_labels[:m]
        fut_dur[:m] = [kp.duration_class(int(d)) for d in durations[:m]]
        fut_mask[:m] = 1

        # Refinement: the centres of the true labels at the true keypose frames, from the present
        # pose (what the predictors feed it), against the true future; frames past the window's
        # end hold the last pose and carry no loss.
        valid = len(future) - 1
        ref_in = interpolate(future[0], self.centres[fut_labels], durations, r)
        target = np.concatenate([future[1:r + 1], np.repeat(future[-1:], max(0, r - valid), axis=0)])
        return {"obs_proximity": obs_prox, "obs_duration": obs_dur, "obs_mask": obs_mask, "obs_label": obs_label,
                "fut_label": fut_label, "fut_duration": fut_dur, "fut_mask": fut_mask,
                "refine_input": np.concatenate([future[:1], ref_in]).astype(np.float32),
                "refine_target": target.astype(np.float32),
                "refine_mask": (np.arange(r) < valid).astype(np.float32),
                "observed_count": observed_count, "future_count": targets}

    # --- model and loss ---------------------------------------------------------------------
    def build(self, data: TrainingData) -> nn.Module:
        m = self.cfg.get("model", {})
        rf = m.get("refine", {})
        centres = torch.from_numpy(self.centres)
        centre_prox = torch.from_numpy(proximity(self.centres, self.centres))
        gru = KPGRU(self.clusters, D, int(m.get("hidden", 48)), int(m.get("layers", 3)), centre_prox,
                    self.temperature, self.noise)
        refine = RefineGCN(J, self.refine_frames + 1, int(rf.get("bases", 20)), int(rf.get("hidden", 32)),
                           int(rf.get("blocks", 1)), int(rf.get("ramp_frames", 10)), bool(m.get("keep_bones", True)))
        return KeyposesNet(gru, refine, centres)

    def teacher_probability(self, step: int) -> float:
        """Scheduled sampling, Eq. 2: eps_i = k / (k + exp(i / k)) with i the epoch (as in the paper's
        100-epoch schedule; k = 10)."""
        k = float(self.cfg.get("loss", {}).get("scheduled_sampling_k", 10))
        batch = int(self.cfg.get("train", {}).get("batch_size", 64))
        epoch = step * batch / max(1, self.examples)
        return k / (k + float(np.exp(min(epoch / k, 50.0))))

    def loss(self, model, batch, step):
        w = self.cfg.get("loss", {})
        teacher = bool(torch.rand(()) < self.teacher_probability(step))
        labels, durations, refined = model(batch["obs_proximity"], batch["obs_duration"], batch["obs_mask"],
                                           batch["fut_label"], batch["fut_duration"], batch["refine_input"], teacher)
        target_l, target_d, mask = targets(batch)
        n = mask.sum().clamp_min(1)
        ce_l = (F.cross_entropy(labels.transpose(1, 2), target_l, reduction="none") * mask).sum() / n
        ce_d = (F.cross_entropy(durations.transpose(1, 2), target_d, reduction="none") * mask).sum() / n
        acc_l, acc_d = accuracy(labels, durations, target_l, target_d, mask)

        # Refinement, Eq. 4: pose, velocity and bone-length MSE over the frames the window has.
        target, fm = batch["refine_target"], batch["refine_mask"]
        present = batch["refine_input"][:, :1]
        frames = fm.sum().clamp_min(1)
        e_pose = (((refined - target) ** 2).mean((-1, -2)) * fm).sum() / frames
        vel = torch.diff(torch.cat([present, refined], 1), dim=1) - torch.diff(torch.cat([present, target], 1), dim=1)
        e_vel = ((vel ** 2).mean((-1, -2)) * fm).sum() / frames
        e_bone = (((bone_lengths(refined) - bone_lengths(target)) ** 2).mean(-1) * fm).sum() / frames
        # Eq. 4's weights (paper: 0.1, 100, 1e-6) leave bone length out; measured here, bone = 1
        # lets the GCN memorise training motions (train MPJPE 0.20 -> 0.10 m) while bone errors grow
        # (1.4 -> 1.8 cm); bone = 100 halves them on train and quarters them on test windows.
        floor = floor_penalty(refined)        # feet may not sink (ops/floor.py): issue 17's shape terms
        refine = (float(w.get("pose", 1.0)) * e_pose + float(w.get("velocity", 10.0)) * e_vel
                  + float(w.get("bone", 100.0)) * e_bone + float(w.get("floor", 100.0)) * floor)
        total = float(w.get("labels", 1.0)) * ce_l + float(w.get("duration", 0.1)) * ce_d + refine
        logs = {"ce_label": ce_l, "ce_dur": ce_d, "acc_label": acc_l, "acc_dur": acc_d, "pose": e_pose, "bone": e_bone}
        return total, {k: float(v.detach()) for k, v in logs.items()}

    # --- export -----------------------------------------------------------------------------
    def graphs(self, model: nn.Module) -> dict[str, GraphDef]:
        g = model.gru
        k, h, layers, r = g.clusters, g.hidden, g.layers, self.refine_frames
        dist = torch.softmax(torch.randn(2, k), -1)
        dur = torch.eye(D)[[1, 2]]
        return {
            "step": GraphDef(
                module=KPGRUStep(g), example_inputs=(dist, dur, torch.zeros(2, layers, h)),
                inputs=[TensorSpec("label_dist", ["batch", k]), TensorSpec("duration", ["batch", D]),
                        TensorSpec("hidden", ["batch", layers, h])],
                outputs=[TensorSpec("label_logits", ["batch", k]), TensorSpec("duration_logits", ["batch", D]),
                         TensorSpec("next_hidden", ["batch", layers, h])]),
            "refine": GraphDef(
                module=model.refine, example_inputs=(torch.randn(2, r + 1, J, 3) * 0.3,),
                inputs=[TensorSpec("sequence", ["batch", r + 1, J, 3])],
                outputs=[TensorSpec("refined", ["batch", r, J, 3])]),
        }

    def params(self, model: nn.Module) -> dict:
        g = model.gru
        return {**super().params(model),
                "keyposes": {"threshold": self.threshold, "error": "l2_pose", "clusters": g.clusters,
                             "min_observed": self.min_observed, "max_observed": self.max_observed,
                             "predicted": self.predicted, "layers": g.layers, "hidden": g.hidden},
                "label_temperature": g.temperature, "label_noise": g.noise,
                "duration_classes": {"bounds": list(kp.DURATION_BOUNDS), "lengths": list(kp.DURATION_LENGTHS)},
                "refine_frames": self.refine_frames,
                # the predictors' seam with the history and fixed bone lengths (issue 17's shape terms);
                # false only in the ablation that measures what they cost
                "finish": bool(self.cfg.get("finish", True))}

    def controls(self, actions: list[str]) -> list[dict]:
        return [
            {"id": "k", "type": "int", "label": "Samples (K)", "min": 1, "max": 50, "step": 1, "default": 10,
             "help": "How many futures to sample."},
            {"id": "temperature", "type": "number", "label": "Temperature", "min": 0.05, "max": 1.5, "step": 0.05,
             "default": self.sampling_temperature,
             "help": "Labels and durations are drawn from softmax(logits / temperature): "
                                     "low keeps the most likely keyposes, high gives more varied futures."},
            {"id": "refine", "type": "bool", "label": "Refine", "default": True,
             "help": "Smooth the interpolated keyposes with the refinement network."},
            {"id": "horizon", "type": "number", "label": "Horizon (s)", "min": 1, "max": self.refine_frames / FPS,
             "step": 0.5, "default": self.refine_frames / FPS, "help": "Keyposes are sampled until the horizon is covered."},
        ]

    def files(self, model: nn.Module) -> dict[str, dict]:
        c = model.centres.double().numpy().round(5)
        return {"centres": {"format": "motion-futures/keypose-centres", "version": 1,
                            "about": "k-means centres of the training keyposes, each facing +z, metres [K][J][3]; "
                                     "duration classes: half-open frame intervals [bounds[c], bounds[c+1]) "
                                     "and the length each stands for; root_velocity [K][2]: metres per frame "
                                     "(x sideways, z forward) a segment leading to a keypose of that "
                                     "cluster moves the root (export/ops/keypose_travel.py)",
                            "clusters": int(c.shape[0]), "joints": int(c.shape[1]),
                            "centres": c.tolist(),
                            "root_velocity": self.root_velocity.tolist(),
                            "duration_classes": {"bounds": list(kp.DURATION_BOUNDS),
                                                 "lengths": list(kp.DURATION_LENGTHS)}}}
