"""Motion sources: each turns some files into clips on the project skeleton at the project rate.

One small base class and one subclass per source (DeepMimic now; BVH and npz folders plug in
the same way), so `python -m export ... --data PATH` trains on any of them.
"""
from __future__ import annotations

from pathlib import Path

from . import deepmimic, split
from .clip import Clip, Split
from ..ops.loop import repeat_cycles

FPS = 30.0


class MotionSource:
    """Base class: `clips()` returns every clip with its split assigned."""

    name = "source"

    def clips(self) -> list[Clip]:
        out = [split.assign(clip, test_only) for clip, test_only in self._load()]
        names = [c.name for c in out]
        dupes = {n for n in names if names.count(n) > 1}
        if dupes:
            raise ValueError(f"{self.name}: clip names must be unique, repeated: {sorted(dupes)}")
        return out

    def _load(self) -> list[tuple[Clip, bool]]:
        raise NotImplementedError


class DeepMimicSource(MotionSource):
    """The humanoid clips inside the pybullet wheel: 15 actions plus the test-only walker takes."""

    name = "deepmimic"

    def __init__(self, root: Path | None = None):
        self.root = Path(root) if root else deepmimic.pybullet_data_dir() / "data" / "motions"

    def _load(self) -> list[tuple[Clip, bool]]:
        items = [(p, p.stem.removeprefix("humanoid3d_"), p.stem.removeprefix("humanoid3d_"), False)
                 for p in sorted(self.root.glob("humanoid3d_*.txt"))]
        # The walker takes are walking (straight and turning): action "walk", a second take.
        items += [(p, "walker_" + p.stem.lstrip("0"), "walk", True)
                  for p in sorted((self.root / "walker").glob("*.txt"))]
        if not items:
            raise FileNotFoundError(f"no DeepMimic humanoid clips under {self.root}")
        return [(self._clip(p, name, action), test_only) for p, name, action, test_only in items]

    @staticmethod
    def _clip(path: Path, name: str, action: str) -> Clip:
        raw, loops = deepmimic.load(path)
        motion, end = raw.at_rate(FPS, loops)
        clip = Clip(
            name=name, action=action, fps=FPS, positions=motion.positions(), loops=loops,
            split=Split("train", [], []),
            source={"dataset": "DeepMimic humanoid (pybullet_data/data/motions)",
                    "file": str(path.relative_to(path.parents[1] if path.parent.name == "walker" else path.parent)),
                    "license": deepmimic.LICENSE},
            cycle_frames=len(motion) if loops else None,
        )
        if loops:
            clip.repeat = lambda cycles: repeat_cycles(motion, end, cycles).positions()
        return clip


def default_source() -> MotionSource:
    return DeepMimicSource()


def source_for(path: str | Path) -> MotionSource:
    """The source for a user's folder; BVH and npz folders are added by the bring-your-own-data issue."""
    path = Path(path)
    if not path.exists():
        raise FileNotFoundError(f"{path}: no such folder")
    if path.is_dir() and any(path.glob("humanoid3d_*.txt")):
        return DeepMimicSource(path)
    raise ValueError(f"{path}: no motion files this version can read (DeepMimic humanoid3d_*.txt)")
