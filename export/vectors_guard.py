"""Shared test vectors of the guards (issue 19): bone projection, the training envelope's measures and
warnings, and where a future breaks a bound. Independent of any trained model: inputs are served clips
and fixed perturbations of them, so TypeScript can reproduce every number from the same inputs."""
from __future__ import annotations

import numpy as np

from .data.skeleton import SKELETON
from .ops.bones import bone_lengths, project_lengths
from .ops.envelope import check, measure, tempo_poses
from .ops.facing import canonicalise
from .ops.handedness import handedness, swap_left_right
from .sample.canonical import body_scale, rescale, scale_anchor
from .sample.guard import first_bad_frame
from .sample.history import warnings_for


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
    scales = []      # issue 30: a body at another size, and that body brought to the model's size
    for clip, start, motion in _served(6):
        for factor in (0.8, 1.25):
            m = motion * factor
            scale = body_scale(m)
            scales.append({"clip": clip, "start": start, "factor": factor, "motion": m.tolist(), "body_scale": scale,
                           "anchor": scale_anchor(m).tolist(), "model_size": rescale(m, 1 / scale, scale_anchor(m)).tolist()})
    return {"about": "bone lengths of a motion (skeleton.bones order) and its projection onto given lengths "
                     "along the kinematic tree (export/ops/bones.py); a scaled body's size against the skeleton "
                     "and the body brought to the model's size about its anchor (export/sample/canonical.py)",
            "cases": cases, "scales": scales}


def _tempo_reference() -> dict:
    """tempo's reference from every served clip's windows of 10 frames (held-out ones too: the vector's
    histories then match its poses, and tempo is measured)."""
    import json
    from .data.clip_json import read_clip
    from .data.windows import windows
    from .paths import CLIPS_DIR
    index = json.loads((CLIPS_DIR / "index.json").read_text())
    clips = [read_clip(CLIPS_DIR / f"{c['name']}.json") for c in index["clips"]]
    return tempo_poses([w.positions[:10] for part in ("train", "test") for w in windows(clips, part, 11, 10)], 30.0)


def envelope_vector() -> dict:
    """The envelope's measures and warnings, and the predictor's history warnings (issue 30: reflected,
    frozen, 2x speed, scaled), on served histories and a held-out walk."""
    from .eval.odd_table import held_out_walks
    fps = 30.0
    env = {"root_height": [0.8, 1.0], "root_speed": [0.0, 2.0], "scale": [0.55, 0.7], "bone_error": [0.0, 0.05],
           "joint_speed": [0.0, 6.0], "tempo": [0.75, 1.5], "tempo_poses": _tempo_reference()}
    walk = held_out_walks(1)[0].astype(np.float32).astype(np.float64)
    histories = _served(10) + [("held-out walk", 60, walk[60:70])]
    cases = []
    for clip, start, motion in histories:
        changes = [("as captured", motion), ("raised 0.7 m", motion + np.array([0.0, 0.7, 0.0])),
                   ("scaled 1.25", motion * 1.25), ("reflected", motion * np.array([-1.0, 1.0, 1.0])),
                   ("frozen", np.repeat(motion[-1:], len(motion), axis=0))]
        if clip == "held-out walk":
            changes.append(("speed 2x", walk[start:start + 20:2]))
        for name, m in changes:
            canon, _ = canonicalise(m, len(m) - 1, SKELETON)
            score = handedness(m)[1]
            cases.append({"clip": clip, "start": start, "change": name, "world": m.tolist(), "canonical": canon.tolist(),
                          "measure": measure(canon, fps, SKELETON, env["tempo_poses"]),
                          "warnings": [w["quantity"] for w in check(canon, env, fps)],
                          "handedness": score, "swapped_handedness": handedness(swap_left_right(m))[1],
                          "history_warnings": [w["quantity"] for w in warnings_for(m, env, fps)]})
    return {"about": "a canonical history's envelope quantities (export/ops/envelope.py, tempo against the "
                     "reference tempo_poses; null: not measured) and which fall outside a fixed envelope; the "
                     "handedness score of the world history and of it with left and right swapped "
                     "(export/ops/handedness.py); and the predictor's history warnings in order "
                     "(export/sample/history.py warnings_for). Quantities and orders exactly, values as floats",
            "fps": fps, "envelope": env, "cases": cases}


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
