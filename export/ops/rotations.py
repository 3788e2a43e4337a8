"""Quaternion arrays [..., 4] in scipy's x, y, z, w order, with scipy's Rotation doing the algebra."""
from __future__ import annotations

import numpy as np
from scipy.spatial.transform import Rotation


def from_wxyz(q: np.ndarray) -> np.ndarray:
    """Unit x,y,z,w quaternions from w,x,y,z ones (the clips' quaternions are not always unit)."""
    q = np.asarray(q, dtype=np.float64)
    norms = np.linalg.norm(q, axis=-1, keepdims=True)
    if not np.all(np.isfinite(q)) or np.any(norms < 1e-8):
        raise ValueError("quaternion with zero length or non-finite values")
    return (q / norms)[..., [1, 2, 3, 0]]


def mul(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return (Rotation.from_quat(a) * Rotation.from_quat(b)).as_quat()


def inv(a: np.ndarray) -> np.ndarray:
    return Rotation.from_quat(a).inv().as_quat()


def apply(a: np.ndarray, v: np.ndarray) -> np.ndarray:
    return Rotation.from_quat(a).apply(v)


def slerp(a: np.ndarray, b: np.ndarray, t: np.ndarray | float) -> np.ndarray:
    """Geodesic interpolation a -> b, elementwise; t broadcasts over the leading axes."""
    ra = Rotation.from_quat(a)
    delta = (ra.inv() * Rotation.from_quat(b)).as_rotvec()
    t = np.asarray(t, dtype=np.float64)
    return (ra * Rotation.from_rotvec(delta * t[..., None])).as_quat()


def about_y(angle: np.ndarray | float) -> np.ndarray:
    angle = np.asarray(angle, dtype=np.float64)
    return np.stack([0 * angle, np.sin(angle / 2), 0 * angle, np.cos(angle / 2)], axis=-1)


def yaw(q: np.ndarray, forward: tuple[float, float, float] = (1.0, 0.0, 0.0)) -> np.ndarray:
    """Heading about +y of the rotated forward axis: 0 when it points along +x."""
    f = Rotation.from_quat(q).apply(np.tile(np.asarray(forward, dtype=np.float64), np.shape(q)[:-1] + (1,)))
    return np.arctan2(-f[..., 2], f[..., 0])
