"""DeepMimic humanoid motion files (pybullet_data/data/motions/*.txt) to rotation clips.

A frame is [dt, root pos(3), root quat(4), chest(4), neck(4), r_hip(4), r_knee(1), r_ankle(4),
r_shoulder(4), r_elbow(1), l_hip(4), l_knee(1), l_ankle(4), l_shoulder(4), l_elbow(1)];
quaternions are w, x, y, z and not always unit length; knees and elbows turn about local z.
"""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from .motion import RotationMotion
from .skeleton import SKELETON
from ..ops.rotations import from_wxyz

FRAME_WIDTH = 44
# (project joint, width) in file order after dt and the root position.
_CHANNELS = [
    ("root", 4), ("chest", 4), ("neck", 4),
    ("right_hip", 4), ("right_knee", 1), ("right_ankle", 4), ("right_shoulder", 4), ("right_elbow", 1),
    ("left_hip", 4), ("left_knee", 1), ("left_ankle", 4), ("left_shoulder", 4), ("left_elbow", 1),
]

LICENSE = ("Motion clips of the DeepMimic project (Peng et al., SIGGRAPH 2018, MIT licence), "
           "as shipped in the pybullet wheel (zlib licence)")


class DeepMimicFormatError(ValueError):
    pass


def pybullet_data_dir() -> Path:
    try:
        import pybullet_data
    except ImportError as e:  # pragma: no cover - depends on the environment
        raise RuntimeError("pybullet is not installed: run `make .venv` (it provides the default clips)") from e
    return Path(pybullet_data.getDataPath())


def parse_frames(path: Path) -> tuple[np.ndarray, bool]:
    """The raw [F, 44] frame table and whether the clip loops."""
    try:
        doc = json.loads(Path(path).read_text())
    except (OSError, json.JSONDecodeError) as e:
        raise DeepMimicFormatError(f"{path}: not a readable DeepMimic motion file ({e})") from e
    frames = np.asarray(doc.get("Frames", []), dtype=np.float64)
    if frames.ndim != 2 or frames.shape[1] != FRAME_WIDTH or len(frames) < 2:
        raise DeepMimicFormatError(f"{path}: expected at least 2 frames of {FRAME_WIDTH} values, got shape {frames.shape}")
    if not np.all(np.isfinite(frames)):
        raise DeepMimicFormatError(f"{path}: contains NaN or infinite values")
    return frames, doc.get("Loop") == "wrap"


def frames_to_motion(frames: np.ndarray) -> RotationMotion:
    # The last frame's dt is 0 (or unused): timestamps are the cumulative sum of the dts before each frame.
    times = np.concatenate([[0.0], np.cumsum(frames[:-1, 0])])
    root_pos = frames[:, 1:4]
    quats = np.tile(np.array([1.0, 0.0, 0.0, 0.0]), (len(frames), SKELETON.num_joints, 1))
    col = 4
    for joint, width in _CHANNELS:
        j = SKELETON.index(joint)
        if width == 4:
            quats[:, j] = frames[:, col:col + 4]
        else:  # revolute about local z
            angle = frames[:, col]
            quats[:, j] = np.stack([np.cos(angle / 2), 0 * angle, 0 * angle, np.sin(angle / 2)], axis=-1)
        col += width
    try:
        local = from_wxyz(quats)
    except ValueError as e:
        raise DeepMimicFormatError(str(e)) from e
    return RotationMotion(times=times, root_pos=root_pos, local=local)


def load(path: Path) -> tuple[RotationMotion, bool]:
    frames, loops = parse_frames(path)
    return frames_to_motion(frames), loops
