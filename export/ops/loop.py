"""Repeating a looping clip with its seam blended in rotation space.

The DeepMimic loops do not close: the pose at the end of a cycle differs from the first
pose (0.07-0.65 m in joint positions). Each seam's jump is spread over `blend` frames on
either side by rotating every joint part of the way (slerp); forward kinematics afterwards
keeps bone lengths exact. Cycle r of a repeat covers frames [r*m, (r+1)*m), m the cycle
length. Each next cycle is turned about the vertical by the cycle's heading change, so a
turning loop keeps turning instead of snapping back.
"""
from __future__ import annotations

import numpy as np

from ..data.motion import RotationMotion
from .rotations import about_y, inv, mul, slerp, yaw


def _smoothstep(x: np.ndarray) -> np.ndarray:
    x = np.clip(x, 0.0, 1.0)
    return x * x * (3 - 2 * x)


def _turn_xz(xz: np.ndarray, angle: float) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    return np.stack([c * xz[..., 0] + s * xz[..., 1], -s * xz[..., 0] + c * xz[..., 1]], axis=-1)


def seam_blend_frames(cycle_length: int) -> int:
    """Frames blended on each side of a seam: a third of the cycle, 4 to 12 frames.

    Measured on the DeepMimic loops: with this width every seam step is at most the clip's own
    largest frame-to-frame step, and no step grows by more than 10% (walker turns, the worst).
    """
    return int(np.clip(cycle_length // 3, 4, 12))


def repeat_cycles(cycle: RotationMotion, end: RotationMotion, count: int, blend: int | None = None) -> RotationMotion:
    """`count` cycles of a loop; `end` is the one-frame pose that closes the cycle."""
    m = len(cycle)
    blend = seam_blend_frames(m) if blend is None else blend
    if count < 1:
        raise ValueError("count must be at least 1")
    if 2 * blend > m:
        raise ValueError(f"a blend of {blend} frames per side does not fit a {m}-frame cycle")
    dyaw = float(yaw(end.local[0, 0]) - yaw(cycle.local[0, 0]))
    start_xz = cycle.root_pos[0, [0, 2]]
    step_xz = end.root_pos[0, [0, 2]] - start_xz

    quats, roots, origin = [], [], np.zeros(2)
    for r in range(count):
        local = cycle.local.copy()
        local[:, 0] = mul(about_y(r * dyaw), cycle.local[:, 0])
        pos = cycle.root_pos.copy()
        pos[:, [0, 2]] = _turn_xz(pos[:, [0, 2]] - start_xz, r * dyaw) + origin
        origin = origin + _turn_xz(step_xz, r * dyaw)
        quats.append(local)
        roots.append(pos)
    quats = np.concatenate(quats)
    roots = np.concatenate(roots)

    identity = np.tile([0.0, 0.0, 0.0, 1.0], (quats.shape[1], 1))
    for r in range(count - 1):
        seam = (r + 1) * m
        natural = end.local[0].copy()                       # what would follow cycle r
        natural[0] = mul(about_y(r * dyaw), end.local[0, 0])
        delta = mul(quats[seam], inv(natural))              # the jump, left-multiplied, per joint
        dh = roots[seam, 1] - end.root_pos[0, 1]
        for f in range(seam - blend, seam + blend):
            w = float(_smoothstep(np.asarray((f - (seam - blend) + 0.5) / (2 * blend))))
            if f < seam:   # pull the end of cycle r toward the next start...
                quats[f] = mul(slerp(identity, delta, w), quats[f])
                roots[f, 1] += dh * w
            else:          # ...and start cycle r+1 from where cycle r was heading
                quats[f] = mul(slerp(identity, inv(delta), 1 - w), quats[f])
                roots[f, 1] -= dh * (1 - w)
    dt = cycle.times[1] - cycle.times[0]
    return RotationMotion(cycle.times[0] + dt * np.arange(len(roots)), roots, quats)
