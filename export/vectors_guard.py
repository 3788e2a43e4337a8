"""Shared test vectors of the guards (issue 19): bone projection, the training envelope's measures and
warnings, and where a future breaks a bound. Independent of any trained model: inputs are served clips
and fixed perturbations of them, so TypeScript can reproduce every number from the same inputs."""
from __future__ import annotations

import numpy as np

from .data.skeleton import SKELETON
from .ops.bones import bone_lengths, project_lengths
from .ops.envelope import check, measure
from .ops.facing import canonicalise
from .sample.guard import first_bad_frame


def _served(frames: int, role: str = "test") -> list[tuple[str, int, np.ndarray]]:
    """(clip, start, world positions [frames, J, 3]) from two served clips of `role`, float32 values."""
    import json
    from .data.clip_json import read_clip
    from .paths import CLIPS_DIR
    index = json.loads((CLIPS_DIR / "index.json").read_text())
    names = sorted(c["name"] for c in index["clips"] if c["role"] == role and c["frames"] >= frames + 5)[:2]
    return [(n, 5, read_clip(CLIPS_DIR / f"{n}.json").positions[5:5 + frames].astype(np.float32).astype(np.float64))
            for n in names]


def bones_vector() -> dict:
    rng = np.random.default_rng(19)
    cases = []
    for clip, start, motion in _served(6):
        noisy = motion + rng.normal(scale=0.03, size=motion.shape)
        lengths = bone_lengths(motion).mean(0)
        cases.append({"clip": clip, "start": start, "motion": noisy.tolist(), "lengths": lengths.tolist(),
                      "bone_lengths": bone_lengths(noisy).tolist(), "projected": project_lengths(noisy, lengths).tolist()})
    return {"about": "bone lengths of a motion (skeleton.bones order) and its projection onto given lengths "
                     "along the kinematic tree (export/ops/bones.py)", "cases": cases}


def envelope_vector() -> dict:
    fps = 30.0
    env = {"root_height": [0.8, 1.0], "root_speed": [0.0, 2.0], "scale": [0.55, 0.7], "bone_error": [0.0, 0.05],
           "joint_speed": [0.0, 6.0]}
    cases = []
    for clip, start, motion in _served(10):
        for name, m in [("as captured", motion), ("raised 0.7 m", motion + np.array([0.0, 0.7, 0.0])),
                        ("scaled 1.25", motion * 1.25)]:
            canon, _ = canonicalise(m, len(m) - 1, SKELETON)
            cases.append({"clip": clip, "start": start, "change": name, "canonical": canon.tolist(),
                          "measure": measure(canon, fps), "warnings": [w["quantity"] for w in check(canon, env, fps)]})
    return {"about": "a canonical history's envelope quantities (export/ops/envelope.py) and which fall outside "
                     "a fixed envelope (quantities exactly, values as floats)", "fps": fps, "envelope": env,
            "cases": cases}


def guard_vector() -> dict:
    cases = []
    for clip, start, motion in _served(20):
        history, future = motion[:10], motion[10:20].copy()
        grow = future.copy()
        grow[4:, 7] += np.cumsum(np.full(6, 0.4))[:, None]           # a toe flying off: a bone breaks first
        drift = future.copy()
        drift[6:] += np.array([2.0, 0.0, 0.0])                         # the whole body teleports
        nan = future.copy()
        nan[8, 3, 1] = np.nan
        for name, f in [("as captured", future), ("a toe flies off", grow), ("the body jumps 2 m", drift), ("NaN", nan)]:
            bad = first_bad_frame(f, history)
            cases.append({"clip": clip, "start": start, "change": name, "history": history.tolist(),
                          "future": np.where(np.isfinite(f), f, 0.0).tolist(), "nan_at": [8, 3, 1] if name == "NaN" else None,
                          "first_bad": None if bad is None else bad[0]})
    return {"about": "where a future (world frame) first breaks a bound against its history (export/sample/guard.py): "
                     "the frame exactly (null: none)", "cases": cases}
