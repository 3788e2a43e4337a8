"""The seam between a history and its future: the first predicted frames continue the history's last
velocity and hand over to the predicted motion within SEAM_FRAMES frames.

    y'_t = c_t + w_t (y_t - c_t),   c_t = x_N + (t + 1)(x_N - x_{N-1}),   w_t = min(t / SEAM_FRAMES, 1)

for future frames t = 0, 1, ...: the first frame moves exactly the history's last step, so a future
never starts with a jump (issue 17: no more than 1.5x that step), and from frame SEAM_FRAMES on the
prediction is the model's own. It acts on the models' canonical tensors (root-relative poses and the
root channel, export/ops/facing.py), so the root keeps its speed across the seam too; bones are given
their lengths afterwards (export/models/keep_bones.py). The graphs apply it in torch (models/finish.py);
Keyposes, whose future is interpolated outside any graph, applies this numpy form (TypeScript twin:
`continueHistory` in web/src/sampling/keyposes.ts).
"""
from __future__ import annotations

import numpy as np

SEAM_FRAMES = 5


def seam_weights(frames: int, seam: int = SEAM_FRAMES) -> np.ndarray:
    """w_t for t = 0..frames-1."""
    return np.minimum(np.arange(frames) / seam, 1.0)


def continue_history(future: np.ndarray, last_two: np.ndarray, seam: int = SEAM_FRAMES) -> np.ndarray:
    """future [..., T, J, 3] and the history's last two frames [..., 2, J, 3] (same frame) -> the future
    with its seam blended."""
    f = np.array(future, dtype=np.float64)
    x1, x0 = np.asarray(last_two, dtype=np.float64)[..., 1, :, :], np.asarray(last_two, dtype=np.float64)[..., 0, :, :]
    n = min(f.shape[-3], seam)                     # frames from `seam` on are the prediction's own, untouched
    t = np.arange(n)
    c = x1[..., None, :, :] + (t + 1)[:, None, None] * (x1 - x0)[..., None, :, :]
    w = seam_weights(n, seam)[:, None, None]
    f[..., :n, :, :] = c + w * (f[..., :n, :, :] - c)
    return f
