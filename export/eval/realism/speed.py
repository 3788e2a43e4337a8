"""Per-second speeds: does a future keep moving like the person, or freeze?

Mean joint speed (m/s) in second s: the mean over joints j and steps t of |p_{t+1,j} - p_{t,j}| * fps on
root-relative poses (each frame's root x and z subtracted, heights kept: metrics.root_relative), over the
steps of that second. The sequence is the future, with the history's last frame prepended when a history
is given; its frames are numbered from 0 (the present when prepended, else the first predicted frame), and
second s covers the steps from frame fps*s to frame fps*(s+1). So with the present prepended, 90 predicted
frames make three whole seconds and the first one includes the step from the present into the future; a
last second with fewer than fps steps is kept, averaged over the steps it has.

Horizontal root speed (m/s): the same windows on the root joint's world x and z: |xz_{t+1} - xz_t| * fps.

TypeScript twin: none (the stage does not show these).
"""
from __future__ import annotations

import numpy as np

from ..metrics import root_relative

FPS = 30


def _with_present(future: np.ndarray, history: np.ndarray | None) -> np.ndarray:
    """[..., T, J, 3] with the history's last frame [..., 1, J, 3] before it (broadcast over samples)."""
    future = np.asarray(future, dtype=np.float64)
    if history is None:
        return future
    last = np.asarray(history, dtype=np.float64)[..., -1:, :, :]
    last = np.broadcast_to(last, future.shape[:-3] + last.shape[-3:])
    return np.concatenate([last, future], axis=-3)


def _per_second(steps: np.ndarray, fps: int) -> np.ndarray:
    """[..., n] step speeds -> [..., ceil(n / fps)] means over consecutive fps steps."""
    n = steps.shape[-1]
    if n < 1:
        raise ValueError("a speed needs at least two frames")
    return np.stack([steps[..., s:s + fps].mean(-1) for s in range(0, n, fps)], axis=-1)


def joint_speed_per_second(future: np.ndarray, history: np.ndarray | None = None, fps: int = FPS) -> np.ndarray:
    """Mean joint speed, root-relative, per second (m/s): [..., T, J, 3] -> [..., S]."""
    poses = root_relative(_with_present(future, history))
    steps = np.linalg.norm(np.diff(poses, axis=-3), axis=-1).mean(-1) * fps
    return _per_second(steps, fps)


def root_speed_per_second(future: np.ndarray, history: np.ndarray | None = None, fps: int = FPS) -> np.ndarray:
    """Horizontal speed of the root joint (world x, z) per second (m/s): [..., T, J, 3] -> [..., S]."""
    xz = _with_present(future, history)[..., 0, :][..., [0, 2]]
    steps = np.linalg.norm(np.diff(xz, axis=-2), axis=-1) * fps
    return _per_second(steps, fps)


def ratio_to_truth(predicted: np.ndarray, truth: np.ndarray) -> np.ndarray:
    """Per second: the mean predicted speed over all windows (and samples) divided by the mean true speed
    over the windows, [..., S] and [..., S] -> [S]; NaN where the truth's mean is 0.

    A ratio of means, not a mean of per-window ratios: a window whose truth stands still (speed ~ 0)
    would make its own ratio explode and swamp the rest.
    """
    p = np.asarray(predicted, dtype=np.float64)
    t = np.asarray(truth, dtype=np.float64)
    num = p.reshape(-1, p.shape[-1]).mean(0)
    den = t.reshape(-1, t.shape[-1]).mean(0)
    if num.shape != den.shape:
        raise ValueError(f"predicted and true speeds cover {num.shape[0]} and {den.shape[0]} seconds")
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(den > 0, num / np.where(den > 0, den, 1.0), np.nan)
