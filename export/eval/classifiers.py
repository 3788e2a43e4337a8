"""The two action classifiers the metrics use, trained on the training split only.

- PoseGru (WAT supplement sec. 10): a GRU over the poses of a snippet, then a 3-layer MLP with
  ReLU after the first two layers and a sigmoid after the last; its penultimate layer gives the
  features for FID (Eq. 9).
- Moac (Keyposes sec. 4.3, appendix 6.6, Fig. 8b): the motion stream of HCN [25] on
  frame-to-frame velocities only, so a static prediction cannot score by its pose.

Both classify fixed snippets of SNIPPET frames (1 s here: the clips are 24-133 frames and the
test tails 37-53, so the paper's 125-frame inputs do not exist on this data). A longer motion is
classified by averaging the outputs of its sliding snippets. Every snippet is turned to face +z
at its first frame, like the training windows (data/windows.py with history=1).

Both have one class more than there are actions: NO_MOTION, trained on training poses held
still. Without it a frozen pose must be called some action (MOAC called every still snippet
"walk"), so a zero-velocity future scored as if it performed the action; the papers' classifiers
see real and predicted motion, never a requested action that is not performed. A prediction
classified as NO_MOTION counts as wrong for every action.
"""
from __future__ import annotations

import hashlib
import inspect
import json
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import torch
from torch import nn

from ..data.clip import Clip
from ..data.skeleton import SKELETON
from ..data.windows import windows
from ..ops.facing import canonicalise

J = SKELETON.num_joints
NO_MOTION = "(no motion)"


def snippets(motion: np.ndarray, frames: int, stride: int) -> np.ndarray:
    """Sliding snippets [n, frames, J, 3] of a motion [T, J, 3], each facing +z at its first frame.
    The last snippet always ends at the motion's last frame; a motion shorter than `frames` gives none."""
    motion = np.asarray(motion, dtype=np.float64)
    if len(motion) < frames:
        return np.zeros((0, frames, *motion.shape[1:]))
    starts = list(range(0, len(motion) - frames + 1, stride))
    if starts[-1] != len(motion) - frames:
        starts.append(len(motion) - frames)
    return np.stack([canonicalise(motion[s:s + frames], 0, SKELETON)[0] for s in starts])


class PoseGru(nn.Module):
    """WAT supplement sec. 10: GRU, then Linear-ReLU, Linear-ReLU (features), Linear-sigmoid."""

    def __init__(self, classes: int, hidden: int):
        super().__init__()
        self.gru = nn.GRU(J * 3, hidden, batch_first=True)
        self.body = nn.Sequential(nn.Linear(hidden, hidden), nn.ReLU(), nn.Linear(hidden, hidden), nn.ReLU())
        self.head = nn.Linear(hidden, classes)

    def features(self, x: torch.Tensor) -> torch.Tensor:     # x [B, T, J*3], normalised poses
        _, h = self.gru(x)
        return self.body(h[-1])

    def forward(self, x: torch.Tensor) -> torch.Tensor:
        return torch.sigmoid(self.head(self.features(x)))


class Moac(nn.Module):
    """Keyposes Fig. 8b: HCN's motion stream. Point-level convolutions per joint, then a transpose that
    makes joints the channels, two 3x3 convolutions with max pooling, and two fully connected layers."""

    # HCN's widths (64, 32, 32, 64) halved: the full ones cost ~0.7 s per training step on this CPU.
    WIDTHS = (32, 16, 16, 32)

    def __init__(self, classes: int, frames: int, hidden: int):
        super().__init__()
        a, b, c, d = self.WIDTHS
        self.point = nn.Sequential(nn.Conv2d(3, a, 1), nn.ReLU(), nn.Conv2d(a, b, (3, 1), padding=(1, 0)))
        self.cooccur = nn.Sequential(
            nn.Conv2d(J, c, 3, padding=1), nn.ReLU(), nn.MaxPool2d(2),
            nn.Conv2d(c, d, 3, padding=1), nn.ReLU(), nn.MaxPool2d(2))
        flat = d * ((frames - 1) // 4) * (b // 4)
        self.body = nn.Sequential(nn.Flatten(), nn.Linear(flat, hidden), nn.ReLU())
        self.head = nn.Linear(hidden, classes)

    def features(self, v: torch.Tensor) -> torch.Tensor:     # v [B, T-1, J, 3], normalised velocities
        x = self.point(v.permute(0, 3, 1, 2))                  # [B, b, T-1, J]
        return self.body(self.cooccur(x.permute(0, 3, 1, 2)))  # joints as channels: [B, J, T-1, b]

    def forward(self, v: torch.Tensor) -> torch.Tensor:
        return self.head(self.features(v))


@dataclass
class Classifier:
    """A trained classifier with its input normalisation; classifies snippets or whole motions."""
    kind: str                   # "pose_gru" or "moac"
    model: nn.Module
    actions: list[str]
    classes: list[str]          # actions + [NO_MOTION]: the output order
    mean: np.ndarray
    std: np.ndarray
    frames: int

    def _inputs(self, snips: np.ndarray) -> torch.Tensor:
        x = np.asarray(snips, dtype=np.float64)
        x = np.diff(x, axis=1) if self.kind == "moac" else x.reshape(len(x), x.shape[1], -1)
        return torch.from_numpy(((x - self.mean) / self.std).astype(np.float32))

    @torch.no_grad()
    def snippet_outputs(self, snips: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(class scores [n, C] as probabilities, features [n, F]) for snippets [n, frames, J, 3]."""
        self.model.eval()
        scores, feats = [], []
        for i in range(0, len(snips), 512):
            x = self._inputs(snips[i:i + 512])
            f = self.model.features(x)
            out = self.model.head(f)
            # PoseGru's sigmoid scores are kept as they are (argmax is what counts); Moac uses softmax.
            scores.append((torch.sigmoid(out) if self.kind == "pose_gru" else torch.softmax(out, -1)).numpy())
            feats.append(f.numpy())
        if not scores:
            return np.zeros((0, len(self.classes))), np.zeros((0, 0))
        return np.concatenate(scores), np.concatenate(feats)

    def classify(self, motions: list[np.ndarray], stride: int) -> tuple[np.ndarray, list[np.ndarray]]:
        """Class index per motion (scores averaged over its sliding snippets) and each motion's
        snippet features."""
        return self.classify_snippets([snippets(m, self.frames, stride) for m in motions])

    def classify_snippets(self, cut: list[np.ndarray]) -> tuple[np.ndarray, list[np.ndarray]]:
        """classify() on motions already cut into snippets (one array per motion), so two classifiers
        can share the cutting."""
        if any(len(c) == 0 for c in cut):
            raise ValueError(f"a motion is shorter than the classifier's {self.frames} frames")
        if not cut:
            return np.zeros(0, dtype=int), []
        scores, feats = self.snippet_outputs(np.concatenate(cut))
        bounds = np.cumsum([0] + [len(c) for c in cut])
        labels = np.array([scores[a:b].mean(0).argmax() for a, b in zip(bounds[:-1], bounds[1:])])
        return labels, [feats[a:b] for a, b in zip(bounds[:-1], bounds[1:])]


def split_snippets(clips: list[Clip], part: str, frames: int, stride: int, mirror: bool = False
                   ) -> tuple[np.ndarray, list[str], list[str]]:
    """Snippets of the train or test part of the split (facing +z at their first frame), their actions
    and their clip names. Loop-repeatable clips wrap around their loop, as data/windows.py allows."""
    ws = windows(clips, part, frames, history=1, stride=stride, mirror=mirror)
    if not ws:
        return np.zeros((0, frames, J, 3)), [], []
    return np.stack([w.positions for w in ws]), [w.action for w in ws], [w.clip for w in ws]


def _fingerprint(kind: str, cfg: dict, clips: list[Clip], seed: int, shuffled: bool) -> str:
    h = hashlib.sha256(json.dumps([kind, cfg, seed, shuffled], sort_keys=True).encode())
    # The code that decides the weights (not the whole module, so editing a report helper keeps the cache).
    for part in (snippets, PoseGru, Moac, Classifier._inputs, split_snippets, train_classifier, _fit):
        h.update(inspect.getsource(part).encode())
    for c in clips:
        h.update(c.name.encode() + json.dumps([c.split.train, c.split.test]).encode() + c.positions.tobytes())
    return h.hexdigest()[:16]


def train_classifier(kind: str, clips: list[Clip], cfg: dict, seed: int, shuffled: bool = False,
                     cache_dir: Path | None = None) -> Classifier:
    """Train on the training split's snippets (mirrors included). `shuffled` permutes the labels over
    snippets, for the sanity row that must then score at chance. Cached by a fingerprint of
    everything that decides the weights."""
    if kind not in ("pose_gru", "moac"):
        raise ValueError(f"unknown classifier {kind!r}; known: pose_gru, moac")
    actions = sorted({c.action for c in clips})
    frames, stride = int(cfg["snippet_frames"]), int(cfg["stride"])
    path = None
    if cache_dir is not None:
        path = Path(cache_dir) / f"{kind}{'-shuffled' if shuffled else ''}-{_fingerprint(kind, cfg, clips, seed, shuffled)}.pt"
    x, names, _ = split_snippets(clips, "train", frames, stride, mirror=True)
    if len(x) == 0:
        raise ValueError(f"no training snippets of {frames} frames")
    labels = np.array([actions.index(a) for a in names])
    # NO_MOTION examples: a random training pose held for the whole snippet, as many as an average action has.
    rng = np.random.default_rng(seed + 7919)
    still = x[rng.integers(0, len(x), len(x) // len(actions)), :1].repeat(frames, axis=1)
    x, labels = np.concatenate([x, still]), np.concatenate([labels, np.full(len(still), len(actions))])
    classes = [*actions, NO_MOTION]
    if shuffled:
        labels = np.random.default_rng(seed).permutation(labels)
    raw = np.diff(x, axis=1) if kind == "moac" else x.reshape(len(x), frames, -1)
    mean = raw.mean(axis=(0, 1)) if kind == "pose_gru" else np.zeros(raw.shape[2:])
    std = np.maximum(raw.std(axis=(0, 1)), 1e-3)
    torch.manual_seed(seed)
    model = PoseGru(len(classes), int(cfg["hidden"])) if kind == "pose_gru" else \
        Moac(len(classes), frames, int(cfg["hidden"]))
    clf = Classifier(kind, model, actions, classes, mean, std, frames)
    if path is not None and path.exists():
        model.load_state_dict(torch.load(path, weights_only=True))
        model.eval()
        return clf
    _fit(clf, x, labels, cfg, seed)
    if path is not None:
        path.parent.mkdir(parents=True, exist_ok=True)
        torch.save(model.state_dict(), path)
    return clf


def _fit(clf: Classifier, x: np.ndarray, labels: np.ndarray, cfg: dict, seed: int) -> None:
    rng = np.random.default_rng(seed)
    torch.set_num_threads(1)   # the machine is shared; one thread is also the deterministic choice
    opt = torch.optim.Adam(clf.model.parameters(), lr=float(cfg["lr"]))
    # Input noise with probability 1/2 per snippet (Keyposes appendix 6.6), sigma in metres.
    sigma = float(cfg["noise"])
    target = torch.from_numpy(labels)
    onehot = torch.nn.functional.one_hot(target, len(clf.classes)).float()
    clf.model.train()
    for _ in range(int(cfg["steps"])):
        idx = rng.integers(0, len(x), int(cfg["batch_size"]))
        batch = x[idx] + rng.normal(0.0, sigma, x[idx].shape) * (rng.random((len(idx), 1, 1, 1)) < 0.5)
        out = clf.model(clf._inputs(batch))
        if clf.kind == "pose_gru":   # sigmoid outputs (supplement sec. 10): binary cross-entropy per class
            loss = nn.functional.binary_cross_entropy(out, onehot[idx])
        else:
            loss = nn.functional.cross_entropy(out, target[idx])
        opt.zero_grad(set_to_none=True)
        loss.backward()
        opt.step()
    clf.model.eval()


def snippet_accuracy(clf: Classifier, snips: np.ndarray, actions: list[str], balanced: bool = False) -> float:
    """Accuracy on snippets whose true actions are given (balanced: the mean over actions)."""
    if len(snips) == 0:
        return float("nan")
    scores, _ = clf.snippet_outputs(snips)
    pred, truth = scores.argmax(1), np.array([clf.actions.index(a) for a in actions])
    if balanced:
        return float(np.mean([(pred[truth == c] == c).mean() for c in np.unique(truth)]))
    return float((pred == truth).mean())


# --- choosing the classifier honestly (issue 18, item 5) ---------------------------------------------


def action_accuracy(clf: Classifier, snips: np.ndarray, actions: list[str]) -> dict[str, dict]:
    """Per true action: {"accuracy" (% of its snippets), "snippets"}; a snippet called NO_MOTION is wrong."""
    if len(snips) == 0:
        return {}
    pred = clf.snippet_outputs(snips)[0].argmax(1)
    out = {}
    for a in sorted(set(actions)):
        idx = [i for i, b in enumerate(actions) if b == a]
        hit = [pred[i] < len(clf.actions) and clf.actions[pred[i]] == a for i in idx]
        out[a] = {"accuracy": 100.0 * float(np.mean(hit)), "snippets": len(idx)}
    return out


def person_folds(clips: list[Clip]) -> list[tuple[str, list[Clip], list[Clip]]]:
    """Leave-one-person-out inside the training people: (person, the others' clips, that person's clips).
    A person is a fold only when another training person performs one of their actions: the score is on
    those shared actions, since a classifier cannot know an action nobody else performs."""
    train = [c for c in clips if c.split.role != "test"]
    out = []
    for person in sorted({str(c.subject) for c in train}):
        others = [c for c in train if str(c.subject) != person]
        known = {c.action for c in others}
        mine = [c for c in train if str(c.subject) == person and c.action in known]
        if mine:
            out.append((person, others, mine))
    return out


def select_classifier(kind: str, clips: list[Clip], cfg: dict, cache_dir: Path | None = None) -> tuple[dict, dict]:
    """The classifier config to train on all training people: the candidate of cfg["selection"] with the best
    mean balanced accuracy over the person folds (ties: the first). Returns (config, report)."""
    sel = cfg["selection"]
    base = {k: v for k, v in cfg.items() if k != "selection"}
    frames = int(base["snippet_frames"])
    folds = person_folds(clips)
    if not folds:
        raise ValueError("no training person shares an action with another: leave-one-person-out cannot choose")
    report = []
    for cand in sel["candidates"]:
        trial = dict(base, steps=int(sel["steps"]), **{k: v for k, v in cand.items() if k != "name"})
        scores = {}
        for person, others, mine in folds:
            clf = train_classifier(kind, others, trial, int(base["seed"]), cache_dir=cache_dir)
            x, acts, _ = split_snippets(mine, "train", frames, int(sel["stride"]))
            scores[person] = 100.0 * snippet_accuracy(clf, x, acts, balanced=True)
        report.append({"name": cand.get("name", str(cand)), "changes": {k: v for k, v in cand.items() if k != "name"},
                       "score": float(np.mean(list(scores.values()))), "folds": scores})
    best = max(range(len(report)), key=lambda i: (report[i]["score"], -i))
    chosen = dict(base, **report[best]["changes"])
    return chosen, {"candidates": report, "chosen": report[best]["name"], "people": [p for p, _, _ in folds],
                    "steps": int(sel["steps"])}
