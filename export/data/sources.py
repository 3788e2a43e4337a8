"""Motion sources: each turns some files into clips on the project skeleton at the project rate.

One small base class and one subclass per source (DeepMimic, BVH folders, npz folders), so
`python -m export ... --data PATH` trains on any of them.
"""
from __future__ import annotations

import hashlib
import json
import re
from pathlib import Path

from . import deepmimic, split
from .bvh import joint_positions, read_bvh
from .clip import Clip, Split
from .npz import load_npz
from .retarget import JointMap, implausible, load_map, retarget
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

    def split_rules(self) -> list[str]:
        """The split in words, for the clip index."""
        return split.RULES

    def notes(self) -> dict[str, str]:
        """Per action, how its held-out takes differ from its training takes (for the results)."""
        return {}

    def data_files(self) -> list[Path]:
        """The source files the clips are read from, for the data hash."""
        raise NotImplementedError


class DeepMimicSource(MotionSource):
    """The humanoid clips inside the pybullet wheel: 15 actions plus the test-only walker takes."""

    name = "deepmimic"

    def __init__(self, root: Path | None = None):
        self.root = Path(root) if root else deepmimic.pybullet_data_dir() / "data" / "motions"

    def data_files(self) -> list[Path]:
        return sorted(self.root.glob("humanoid3d_*.txt")) + sorted((self.root / "walker").glob("*.txt"))

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


class FolderSource(MotionSource):
    """A user's folder of motion files, retargeted onto the project skeleton (data/retarget.py).

    Labels: `labels.json` in the folder maps a file (its path relative to the folder, with or
    without the suffix) to an action, or to {"action": ..., "test_only": true}; otherwise a
    file's action is the name of the first sub-folder it sits in (`walk/take1.bvh` -> walk).
    `joint-map.json` in the folder, if present, overrides the built-in joint map.
    """

    suffix = ""
    default_map = ""
    dataset = ""

    def __init__(self, root: str | Path, joint_map: Path | dict | None = None):
        self.root = Path(root)
        if joint_map is None and (self.root / "joint-map.json").exists():
            joint_map = self.root / "joint-map.json"
        self.joint_map: JointMap = load_map(self.default_map, joint_map)

    def files(self) -> list[Path]:
        return sorted(p for p in self.root.rglob(f"*{self.suffix}") if p.is_file())

    def data_files(self) -> list[Path]:
        extra = [self.root / n for n in ("labels.json", "joint-map.json") if (self.root / n).exists()]
        return self.files() + extra

    def _labels(self) -> dict[str, dict]:
        path = self.root / "labels.json"
        if not path.exists():
            return {}
        try:
            doc = json.loads(path.read_text())
        except (OSError, json.JSONDecodeError) as e:
            raise ValueError(f"{path}: not readable JSON ({e})") from e
        if not isinstance(doc, dict):
            raise ValueError(f"{path}: must map file names to actions")
        out = {}
        for key, value in doc.items():
            entry = {"action": value} if isinstance(value, str) else value
            if not isinstance(entry, dict) or not isinstance(entry.get("action"), str) or not entry["action"] \
                    or set(entry) - {"action", "test_only"}:
                raise ValueError(f"{path}: field {key}: an action name or {{\"action\": ..., \"test_only\": true}}")
            out[key.removesuffix(self.suffix)] = entry
        return out

    def _label(self, rel: Path, labels: dict[str, dict]) -> tuple[str, bool]:
        key = rel.with_suffix("").as_posix()
        entry = labels.get(key) or labels.get(rel.stem)
        if entry:
            return entry["action"], bool(entry.get("test_only", False))
        if len(rel.parts) > 1:
            return rel.parts[0], False
        raise ValueError(f"{self.root / rel}: no action label: put it in a sub-folder named after its action "
                         f"(walk/{rel.name}) or list it in {self.root / 'labels.json'}")

    def _load(self) -> list[tuple[Clip, bool]]:
        files = self.files()
        if not files:
            raise FileNotFoundError(f"{self.root}: no {self.suffix} files")
        labels = self._labels()
        out = []
        for path in files:
            rel = path.relative_to(self.root)
            action, test_only = self._label(rel, labels)
            positions = self._positions(path)
            out.append((Clip(name=clip_name(rel), action=action, fps=FPS, positions=positions, loops=False,
                             split=Split("train", [], []),
                             source={"dataset": f"{self.dataset} ({self.root.name})", "file": rel.as_posix(),
                                     "license": "as given by the user", "joint_map": self.joint_map.name}),
                        test_only))
        return out

    def _positions(self, path: Path):
        raise NotImplementedError


class BvhFolderSource(FolderSource):
    """*.bvh files (CMU-style skeletons by default)."""

    name = "bvh"
    suffix = ".bvh"
    default_map = "cmu-bvh"
    dataset = "BVH motion capture"

    def _positions(self, path: Path):
        bvh = read_bvh(path)
        return retarget(joint_positions(bvh), bvh.names, bvh.frame_time, self.joint_map, str(path))


class NpzFolderSource(FolderSource):
    """*.npz files of joint positions (SMPL joint orders by default; see data/npz.py)."""

    name = "npz"
    suffix = ".npz"
    default_map = "smpl"
    dataset = "joint positions (npz)"

    def _positions(self, path: Path):
        motion = load_npz(path)
        jmap = self.joint_map
        names = motion.names or jmap.orders.get(str(motion.points.shape[1]))
        how = (f"add 'joint_names' to the npz or a sidecar {path.with_suffix('.json').name} with \"names\" "
               "(the joints in the file's order)")
        if names is None:
            raise ValueError(f"{path}: {motion.points.shape[1]} joints is not a joint order the {jmap.name} map knows "
                             f"({', '.join(sorted(jmap.orders, key=int))}); {how}")
        if motion.up and motion.up != jmap.up:
            jmap = JointMap(jmap.name, motion.up, jmap.joints, jmap.orders)
        if motion.names is None:
            # The order was assumed from the joint count: refuse rather than build a folded body.
            problems = implausible(motion.points, names, jmap, str(path))
            if problems:
                raise ValueError(f"{path}: no joint names, and the assumed {jmap.name} order for "
                                 f"{motion.points.shape[1]} joints fails a plausibility check: {'; '.join(problems)}. "
                                 f"Name the joints: {how}")
        return retarget(motion.points, names, 1.0 / motion.fps, jmap, str(path))


def clip_name(rel: Path) -> str:
    """A contract clip name from a relative path: `Walk/01 01.bvh` -> `walk_01_01`."""
    slug = re.sub(r"[^a-z0-9_.-]+", "_", rel.with_suffix("").as_posix().lower().replace("/", "_"))
    slug = slug.lstrip("_.-")
    return slug or "clip"


def default_source() -> MotionSource:
    """The CMU subset (split by person) and the DeepMimic clips (export/data/default.py)."""
    from .default import DefaultSource   # it builds on this module's classes
    return DefaultSource()


def source_for(path: str | Path, joint_map: Path | None = None) -> MotionSource:
    """The source for a user's folder: DeepMimic humanoid3d_*.txt, *.bvh or *.npz files."""
    path = Path(path)
    if not path.exists():
        raise FileNotFoundError(f"{path}: no such folder")
    if not path.is_dir():
        raise ValueError(f"{path}: --data takes a folder (put the file in a sub-folder named after its action)")
    if any(path.glob("humanoid3d_*.txt")):
        return DeepMimicSource(path)
    has_bvh = any(p.is_file() for p in path.rglob("*.bvh"))
    has_npz = any(p.is_file() for p in path.rglob("*.npz"))
    if has_bvh and has_npz:
        raise ValueError(f"{path}: holds both .bvh and .npz files; give one kind per folder")
    if has_bvh:
        return BvhFolderSource(path, joint_map)
    if has_npz:
        return NpzFolderSource(path, joint_map)
    raise ValueError(f"{path}: no motion files this version can read (DeepMimic humanoid3d_*.txt, *.bvh, *.npz)")


def source_hash(source: MotionSource) -> str:
    """sha256 over the bytes of the files a source reads (never over converted floats, which differ in
    their last bits between CPUs): a model trained on other data is stale."""
    h = hashlib.sha256()
    for p in source.data_files():
        h.update(p.name.encode() + b"\0" + p.read_bytes() + b"\0")
    return "sha256:" + h.hexdigest()
