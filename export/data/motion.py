"""A motion as a root trajectory plus local joint rotations, before forward kinematics."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from .skeleton import SKELETON, Skeleton
from ..ops.fk import forward_kinematics
from ..ops.resample import resample


@dataclass
class RotationMotion:
    times: np.ndarray      # [F] seconds
    root_pos: np.ndarray   # [F, 3] metres, y-up
    local: np.ndarray      # [F, J, 4] x, y, z, w; the root's entry is its world rotation

    def __len__(self) -> int:
        return len(self.times)

    @property
    def duration(self) -> float:
        return float(self.times[-1] - self.times[0])

    def sample(self, new_times: np.ndarray) -> "RotationMotion":
        pos, rot = resample(self.times, self.root_pos, self.local, new_times)
        return RotationMotion(np.asarray(new_times, dtype=np.float64), pos, rot)

    def at_rate(self, fps: float, loops: bool) -> tuple["RotationMotion", "RotationMotion | None"]:
        """Resample by time to `fps`.

        A looping clip becomes exactly one cycle of m = round(duration * fps) frames, sampled at
        k * duration / m (so its rate is within 1/(2m) of fps and cycles repeat without drift);
        the pose at the end of the cycle is returned separately, for blending the seam.
        A non-looping clip is sampled at k / fps over its duration.
        """
        t0 = self.times[0]
        if loops:
            m = max(2, int(round(self.duration * fps)))
            grid = t0 + np.arange(m + 1) * (self.duration / m)
            grid[-1] = self.times[-1]
            full = self.sample(grid)
            return full.slice(0, m), full.slice(m, m + 1)
        n = int(np.floor(self.duration * fps + 1e-9)) + 1
        return self.sample(t0 + np.arange(n) / fps), None

    def slice(self, start: int, stop: int) -> "RotationMotion":
        return RotationMotion(self.times[start:stop], self.root_pos[start:stop], self.local[start:stop])

    def positions(self, skeleton: Skeleton = SKELETON, keep_horizontal_root: bool = True) -> np.ndarray:
        """World joint positions [F, J, 3]: clips travel (contract version 2). keep_horizontal_root=False
        puts the root above the origin in every frame (what version 1 clips held)."""
        root = self.root_pos.copy()
        if not keep_horizontal_root:
            root[:, [0, 2]] = 0.0
        return forward_kinematics(root, self.local, skeleton)
