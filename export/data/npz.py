"""Joint positions in an .npz file (AMASS-style, after the SMPL body model) to named source points.

What is read, first key found wins (a sidecar `<file>.json` beside it overrides the npz):
- positions [frames, joints, 3] (or [frames, joints * 3]): `joints`, `positions`, `joint_positions`, `Jtr`;
- frame rate in Hz: `mocap_framerate` (AMASS), `mocap_frame_rate`, `fps`, `frame_rate`;
- up axis "y" or "z": `up_axis`, `up` (default: the joint map's, z for SMPL);
- joint names: `joint_names`, `names` (default: the joint map's SMPL order for that joint count).
AMASS's own files hold body-model parameters (`poses`, `trans`, `betas`), not positions; those
get a message saying so, because turning them into positions needs the SMPL model files.
"""
from __future__ import annotations

import json
import zipfile
from dataclasses import dataclass
from pathlib import Path

import numpy as np

POSITION_KEYS = ("joints", "positions", "joint_positions", "Jtr")
FPS_KEYS = ("mocap_framerate", "mocap_frame_rate", "fps", "frame_rate")
UP_KEYS = ("up_axis", "up")
NAME_KEYS = ("joint_names", "names")
SIDECAR_KEYS = ("fps", "up", "names")


class NpzFormatError(ValueError):
    """The npz lacks what this loader needs; the message names the file and the missing arrays."""


@dataclass
class NpzMotion:
    points: np.ndarray       # [F, J, 3] in the file's units and axes
    fps: float
    up: str | None           # None: use the joint map's
    names: list[str] | None  # None: use the joint map's order for J joints


def _first(doc, keys):
    for k in keys:
        if k in doc:
            return k
    return None


def _scalar_text(value) -> str:
    arr = np.asarray(value)
    return str(arr.item() if arr.shape == () else arr.ravel()[0])


def read_sidecar(path: Path) -> dict:
    side = Path(path).with_suffix(".json")
    if not side.exists():
        return {}
    try:
        doc = json.loads(side.read_text())
    except (OSError, json.JSONDecodeError) as e:
        raise NpzFormatError(f"{side}: not readable JSON ({e})") from e
    if not isinstance(doc, dict) or set(doc) - set(SIDECAR_KEYS):
        raise NpzFormatError(f"{side}: a sidecar is a JSON object with any of {', '.join(SIDECAR_KEYS)}")
    return doc


def load_npz(path: Path) -> NpzMotion:
    path = Path(path)
    try:
        doc = np.load(path, allow_pickle=False)
    except (OSError, ValueError, EOFError, zipfile.BadZipFile) as e:
        raise NpzFormatError(f"{path}: not a readable .npz file ({e})") from e
    if not isinstance(doc, np.lib.npyio.NpzFile):
        raise NpzFormatError(f"{path}: a single .npy array, not an .npz archive of named arrays")
    with doc:
        arrays = {}
        for k in doc.files:
            try:
                arrays[k] = doc[k]
            except (ValueError, OSError, zipfile.BadZipFile):
                pass  # object arrays (pickles) are never loaded; the keys this loader reads are plain
    side = read_sidecar(path)

    key = _first(arrays, POSITION_KEYS)
    if key is None:
        found = ", ".join(sorted(arrays)) or "no arrays"
        hint = (" It holds SMPL body-model parameters (poses/trans), not joint positions: run the body model "
                "first and save the joints as 'joints' [frames, joints, 3]." if "poses" in arrays else "")
        raise NpzFormatError(f"{path}: no joint positions: expected an array named one of "
                             f"{', '.join(POSITION_KEYS)} [frames, joints, 3]; found {found}.{hint}")
    points = np.asarray(arrays[key])
    if points.ndim == 2 and points.shape[1] % 3 == 0:
        points = points.reshape(len(points), -1, 3)
    if points.ndim != 3 or points.shape[2] != 3 or points.shape[1] < 2 or not np.issubdtype(points.dtype, np.number):
        raise NpzFormatError(f"{path}: array '{key}' must be numbers of shape [frames, joints, 3], got "
                             f"{points.dtype} {points.shape}")
    points = points.astype(np.float64)
    if not np.all(np.isfinite(points)):
        raise NpzFormatError(f"{path}: array '{key}' contains NaN or infinite values")

    fps_key = _first(arrays, FPS_KEYS)
    fps = side.get("fps", arrays[fps_key] if fps_key else None)
    if fps is None:
        raise NpzFormatError(f"{path}: no frame rate: add one of {', '.join(FPS_KEYS)} to the npz, "
                             f"or a sidecar {path.with_suffix('.json').name} with {{\"fps\": 30}}")
    try:
        fps = float(np.asarray(fps, dtype=np.float64).ravel()[0])
    except (ValueError, TypeError, IndexError) as e:
        raise NpzFormatError(f"{path}: the frame rate is not a number ({e})") from e
    if not (np.isfinite(fps) and fps > 0):
        raise NpzFormatError(f"{path}: the frame rate must be positive, got {fps}")

    up_key = _first(arrays, UP_KEYS)
    up = side.get("up", _scalar_text(arrays[up_key]) if up_key else None)
    if up is not None and up not in ("y", "z"):
        raise NpzFormatError(f"{path}: the up axis must be \"y\" or \"z\", got {up!r}")

    name_key = _first(arrays, NAME_KEYS)
    names = side.get("names", [str(n) for n in np.asarray(arrays[name_key]).ravel()] if name_key else None)
    if names is not None and len(names) != points.shape[1]:
        raise NpzFormatError(f"{path}: {len(names)} joint names for {points.shape[1]} joints")
    return NpzMotion(points=points, fps=fps, up=up, names=names)
