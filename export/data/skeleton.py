"""The project's one skeleton: 18 joints of the DeepMimic humanoid, in metres, y-up.

Every source (DeepMimic clips, BVH, npz) ends up as positions of these joints,
so models, the manifest and the browser share one joint order.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

# The humanoid URDF is authored at 4x scale; DeepMimic loads it with globalScaling 0.25.
URDF_SCALE = 0.25


@dataclass(frozen=True)
class Skeleton:
    names: tuple[str, ...]
    parents: tuple[int, ...]
    offsets: np.ndarray  # [J, 3] rest offset of each joint from its parent, metres

    @property
    def num_joints(self) -> int:
        return len(self.names)

    def index(self, name: str) -> int:
        return self.names.index(name)

    @property
    def mirror_map(self) -> np.ndarray:
        """Joint index of each joint's left/right counterpart (itself on the midline)."""
        out = []
        for n in self.names:
            if n.startswith("right_"):
                out.append(self.names.index("left_" + n[6:]))
            elif n.startswith("left_"):
                out.append(self.names.index("right_" + n[5:]))
            else:
                out.append(self.names.index(n))
        return np.asarray(out)

    @property
    def bones(self) -> list[tuple[int, int]]:
        return [(p, j) for j, p in enumerate(self.parents) if p >= 0]

    def bone_lengths(self) -> np.ndarray:
        return np.linalg.norm(self.offsets[[j for _, j in self.bones]], axis=-1)

    def to_contract(self) -> dict:
        return {"joints": list(self.names), "parents": list(self.parents)}


def _u(*xyz: float) -> list[float]:
    return [URDF_SCALE * v for v in xyz]


# Offsets from pybullet_data/humanoid/humanoid.urdf (joint origins). The forward axis is +x
# and the right side is +z in the URDF. End points (head, toes, wrists) are added so the
# figure reads as a person: head = centre of the head sphere, toe = front-bottom edge of
# the foot box, wrist = the URDF's fixed wrist joint.
_JOINTS: list[tuple[str, str | None, list[float]]] = [
    ("root", None, [0.0, 0.0, 0.0]),
    ("chest", "root", _u(0, 0.944604, 0)),
    ("neck", "chest", _u(0, 0.895576, 0)),
    ("head", "neck", _u(0, 0.7, 0)),
    ("right_hip", "root", _u(0, 0, 0.339548)),
    ("right_knee", "right_hip", _u(0, -1.686184, 0)),
    ("right_ankle", "right_knee", _u(0, -1.639480, 0)),
    ("right_toe", "right_ankle", _u(0.18 + 0.354, -0.09 - 0.11, 0)),
    ("left_hip", "root", _u(0, 0, -0.339548)),
    ("left_knee", "left_hip", _u(0, -1.686184, 0)),
    ("left_ankle", "left_knee", _u(0, -1.639480, 0)),
    ("left_toe", "left_ankle", _u(0.18 + 0.354, -0.09 - 0.11, 0)),
    ("right_shoulder", "chest", _u(-0.0962, 0.974, 0.73244)),
    ("right_elbow", "right_shoulder", _u(0, -1.099152, 0)),
    ("right_wrist", "right_elbow", _u(0, -1.035788, 0)),
    ("left_shoulder", "chest", _u(-0.0962, 0.974, -0.73244)),
    ("left_elbow", "left_shoulder", _u(0, -1.099152, 0)),
    ("left_wrist", "left_elbow", _u(0, -1.035788, 0)),
]

_NAMES = tuple(n for n, _, _ in _JOINTS)
SKELETON = Skeleton(
    names=_NAMES,
    parents=tuple(-1 if p is None else _NAMES.index(p) for _, p, _ in _JOINTS),
    offsets=np.asarray([o for _, _, o in _JOINTS], dtype=np.float64),
)
