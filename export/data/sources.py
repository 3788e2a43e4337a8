"""Motion sources: each turns some files into clips on the project skeleton at the project rate.

One small base class and one subclass per source (DeepMimic; user folders of BVH, ASF/AMC or npz
files, or of several kinds at once), so `python -m export ... --data PATH` trains on any of them.
"""
from __future__ import annotations

import hashlib
import json
import re
import sys
from pathlib import Path

import numpy as np

from . import deepmimic, split
from .asf_amc import Asf, joint_positions as asf_positions, read_amc, read_asf
from .bvh import joint_positions, read_bvh
from .clip import Clip, Split
from .npz import load_npz
from .retarget import JointMap, implausible, load_map, pick_map, plausibility_warning, retarget, tried_maps
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


# The kinds of motion file a folder may hold: suffix -> (its key in contract/joint-maps/order.json, whose
# built-in maps it is tried with in that order, as the page tries them; dataset label).
KINDS = {
    ".bvh": ("bvh", "BVH motion capture"),
    ".amc": ("asf-amc", "ASF/AMC motion capture"),
    ".npz": ("npz", "joint positions (npz)"),
}
AMC_FPS = 120.0             # CMU's capture rate; a sidecar <take>.json {"fps": ...} says otherwise
CONFIG_FILES = ("labels.json", "joint-map.json")
READABLE = "DeepMimic humanoid3d_*.txt, *.bvh, *.amc with its *.asf skeleton, *.npz"


class FolderSource(MotionSource):
    """A user's folder of motion files, retargeted onto the project skeleton (data/retarget.py).
    This class reads every kind of KINDS; the subclasses below read one kind each.

    Files: `*.bvh` (frame rate from the header), `*.npz` (data/npz.py) and `*.amc` motions with an
    `*.asf` skeleton: the AMC's skeleton is `<subject>.asf` (the name's part before the first "_",
    as CMU names them: `05.asf` for `05_02.amc`) beside it or in a folder above it, else the only
    `.asf` in the nearest folder that holds any; otherwise the AMC is skipped. An AMC plays at
    120 fps (CMU's rate) unless a sidecar `<take>.json` says {"fps": ...}. Suffixes match in any case.
    Labels: `labels.json` in the folder maps a file (its path relative to the folder, with or
    without the suffix) to an action, or to {"action": ..., "test_only": true}; otherwise a
    file's action is the name of the first sub-folder it sits in (`walk/take1.bvh` -> walk).
    Joint maps: each kind is tried with the built-in maps of contract/joint-maps/order.json in order
    (a BVH: cmu-bvh, then daz; the page tries the same), the first whose joint names the file has
    wins; `joint-map.json` in the folder, if present, overrides each of them.
    Every file read is checked for a body standing upright with a human build (retarget.body_problems):
    a wrong up axis or an ASF from another subject is printed as a warning, naming the fix.
    Every other file is skipped and named with the reason (`skipped`, printed when clips load);
    a file of a kind read here that cannot be read is an error, named.
    """

    name = "folder"
    kinds: tuple[str, ...] = tuple(KINDS)

    def __init__(self, root: str | Path, joint_map: Path | dict | None = None):
        self.root = Path(root)
        if joint_map is None and (self.root / "joint-map.json").exists():
            joint_map = self.root / "joint-map.json"
        self.maps: dict[str, list[JointMap]] = {k: [load_map(m, joint_map) for m in tried_maps(KINDS[k][0])]
                                                for k in self.kinds}
        self._skeletons: dict[Path, Asf] = {}
        self.warnings: list[str] = []   # one per file that fails the plausibility check, printed as read

    @property
    def joint_map(self) -> JointMap:
        """The first joint map tried for the first kind read (the only kind, for a one-kind source)."""
        return self.maps[self.kinds[0]][0]

    def _scan(self) -> tuple[list[Path], list[Path], list[tuple[Path, str]]]:
        """(motion files read, other files they need: skeletons and sidecars, skipped files with why)."""
        read, needed, skipped, skeletons = [], [], [], []
        for path in sorted(p for p in self.root.rglob("*") if p.is_file()):
            suffix = path.suffix.lower()
            if path.parent == self.root and path.name in CONFIG_FILES:
                continue
            if suffix in self.kinds:
                if suffix == ".amc":
                    asf, why = self.skeleton_of(path)
                    if asf is None:
                        skipped.append((path, why))
                        continue
                    needed.append(asf)
                read.append(path)
            elif suffix == ".asf" and ".amc" in self.kinds:
                skeletons.append(path)
            elif suffix == ".json" and self._sidecar(path):
                needed.append(path)
            elif suffix in KINDS or suffix == ".asf":
                skipped.append((path, f"a {suffix} file: this source reads {', '.join(self.kinds)} only"))
            else:
                skipped.append((path, f"not a motion file this version reads ({READABLE})"))
        used = set(needed)
        skipped += [(p, "a skeleton that no .amc file here uses") for p in skeletons if p not in used]
        return read, sorted(used), sorted(skipped)

    def _sidecar(self, path: Path) -> bool:
        """Whether a .json is the sidecar of an .amc or .npz this source reads (same name, beside it)."""
        kinds = {".amc", ".npz"} & set(self.kinds)
        return any(p.stem == path.stem and p.suffix.lower() in kinds and p.is_file() for p in path.parent.iterdir())

    def files(self) -> list[Path]:
        return self._scan()[0]

    @property
    def skipped(self) -> list[tuple[Path, str]]:
        """The files in the folder this source does not read, each with the reason."""
        return self._scan()[2]

    def data_files(self) -> list[Path]:
        read, needed, _ = self._scan()
        extra = [self.root / n for n in CONFIG_FILES if (self.root / n).exists()]
        return read + needed + extra

    def skeleton_of(self, amc: Path) -> tuple[Path | None, str]:
        """The .asf an .amc moves (see the class docstring), or None and why there is none."""
        subject = amc.stem.split("_", 1)[0].strip().lower() if "_" in amc.stem else None
        folders = [amc.parent, *[p for p in amc.parent.parents if p == self.root or self.root in p.parents]]
        found = [(d, sorted(p for p in d.iterdir() if p.is_file() and p.suffix.lower() == ".asf")) for d in folders]
        for _, asfs in found:
            match = [p for p in asfs if p.stem.lower() == subject]
            if match:
                return match[0], ""
        nearest = next((asfs for _, asfs in found if asfs), [])
        if len(nearest) == 1:
            return nearest[0], ""
        want = f"no {subject}.asf beside it or in a folder above" if subject else "no <subject>.asf for it"
        if not nearest:
            return None, f"no skeleton: {want}, and no .asf file there at all"
        return None, (f"no skeleton: {want}, and {len(nearest)} .asf files to choose from "
                      f"({', '.join(p.name for p in nearest[:4])}{' ...' if len(nearest) > 4 else ''})")

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
            suffix = Path(key).suffix.lower()
            out[key[:-len(suffix)] if suffix in KINDS else key] = entry
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
        files, _, skipped = self._scan()
        for path, why in skipped:
            print(f"{self.root.name}: skipped {path.relative_to(self.root).as_posix()}: {why}", file=sys.stderr)
        if not files:
            shown = "; ".join(f"{p.relative_to(self.root).as_posix()}: {why}" for p, why in skipped[:5])
            raise FileNotFoundError(f"{self.root}: no {' or '.join(self.kinds)} files it can read"
                                    + (f" (skipped {shown})" if shown else ""))
        labels = self._labels()
        out = []
        for path in files:
            rel = path.relative_to(self.root)
            action, test_only = self._label(rel, labels)
            kind = path.suffix.lower()
            positions, jmap = self._read(path)
            out.append((Clip(name=clip_name(rel), action=action, fps=FPS, positions=positions, loops=False,
                             split=Split("train", [], []),
                             source={"dataset": f"{KINDS[kind][1]} ({self.root.name})", "file": rel.as_posix(),
                                     "license": "as given by the user", "joint_map": jmap.name}),
                        test_only))
        return out

    def _warn(self, text: str | None) -> None:
        if text:
            self.warnings.append(text)
            print(f"{self.root.name}: warning: {text}", file=sys.stderr)

    def _positions(self, path: Path) -> np.ndarray:
        """Project positions [F, 18, 3] at 30 Hz of one motion file."""
        return self._read(path)[0]

    def _read(self, path: Path) -> tuple[np.ndarray, JointMap]:
        """Project positions [F, 18, 3] at 30 Hz of one motion file, and the joint map that read it."""
        kind = path.suffix.lower()
        if kind == ".bvh":
            bvh = read_bvh(path)
            points = joint_positions(bvh)
            jmap = pick_map(self.maps[kind], bvh.names, str(path))
            self._warn(plausibility_warning(points, bvh.names, jmap, str(path)))
            return retarget(points, bvh.names, bvh.frame_time, jmap, str(path)), jmap
        if kind == ".amc":
            return self._amc_positions(path)
        return _npz_positions(path, self.maps[kind], self._warn)

    def _amc_positions(self, path: Path) -> tuple[np.ndarray, JointMap]:
        asf_path, why = self.skeleton_of(path)
        if asf_path is None:
            raise ValueError(f"{path}: {why}")
        if asf_path not in self._skeletons:
            self._skeletons[asf_path] = read_asf(asf_path)
        asf = self._skeletons[asf_path]
        points = asf_positions(asf, read_amc(path, asf))
        jmap = pick_map(self.maps[".amc"], asf.names, str(path))
        self._warn(skeleton_warning(asf_path, path))
        self._warn(plausibility_warning(points, asf.names, jmap, str(path)))
        return retarget(points, asf.names, 1.0 / amc_fps(path), jmap, str(path)), jmap


def skeleton_warning(asf: Path, amc: Path) -> str | None:
    """CMU names a take <subject>_<take>.amc and its skeleton <subject>.asf: an AMC moved by another
    subject's ASF (01.asf + 05_07.amc) gets that subject's bone lengths and joint axes, a body that does
    not fit its motion (feet under the floor), and nothing in the motion itself shows it reliably.
    None when the names agree or either is not named that way. Twin: skeletonWarning in asf-amc.ts."""
    subject = amc.stem.split("_", 1)[0].strip().lower() if "_" in amc.stem else ""
    other = asf.stem.strip().lower()
    if not (subject.isdigit() and other.isdigit()) or int(subject) == int(other):
        return None
    return (f"{amc}: moved by {asf.name}, the skeleton of subject {other}, but the take's name says subject "
            f"{subject}: another subject's bone lengths and joint axes do not fit the motion (feet under the floor); "
            f"use {subject}.asf")


def amc_fps(path: Path) -> float:
    """An AMC's frame rate: its sidecar <take>.json's "fps", else CMU's 120."""
    side = path.with_suffix(".json")
    if not side.exists():
        return AMC_FPS
    try:
        doc = json.loads(side.read_text())
    except (OSError, json.JSONDecodeError) as e:
        raise ValueError(f"{side}: not readable JSON ({e})") from e
    fps = doc.get("fps") if isinstance(doc, dict) and set(doc) == {"fps"} else None
    if isinstance(fps, bool) or not isinstance(fps, (int, float)) or not (np.isfinite(fps) and fps > 0):
        raise ValueError(f"{side}: the sidecar of an .amc is {{\"fps\": <frames per second>}}, e.g. {{\"fps\": 60}}")
    return float(fps)


def _npz_positions(path: Path, maps: list[JointMap], warn=lambda text: None) -> tuple[np.ndarray, JointMap]:
    motion = load_npz(path)
    jmap = pick_map(maps, motion.names, str(path)) if motion.names else maps[0]
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
    else:
        warn(plausibility_warning(motion.points, names, jmap, str(path)))
    return retarget(motion.points, names, 1.0 / motion.fps, jmap, str(path)), jmap


class BvhFolderSource(FolderSource):
    """*.bvh files only (CMU-style skeletons by default)."""

    name = "bvh"
    kinds = (".bvh",)


class NpzFolderSource(FolderSource):
    """*.npz files of joint positions only (SMPL joint orders by default; see data/npz.py)."""

    name = "npz"
    kinds = (".npz",)


class AsfAmcFolderSource(FolderSource):
    """*.amc motions with their *.asf skeletons only (CMU's own form)."""

    name = "asf-amc"
    kinds = (".amc",)


def clip_name(rel: Path) -> str:
    """A contract clip name from a relative path: `Walk/01 01.bvh` -> `walk_01_01`."""
    slug = re.sub(r"[^a-z0-9_.-]+", "_", rel.with_suffix("").as_posix().lower().replace("/", "_"))
    slug = slug.lstrip("_.-")
    return slug or "clip"


def default_source() -> MotionSource:
    """The CMU subset (split by person) and the DeepMimic clips (export/data/default.py)."""
    from .default import DefaultSource   # it builds on this module's classes
    return DefaultSource()


ONE_KIND = {".bvh": BvhFolderSource, ".amc": AsfAmcFolderSource, ".npz": NpzFolderSource}


def source_for(path: str | Path, joint_map: Path | None = None) -> MotionSource:
    """The source for a user's folder: DeepMimic humanoid3d_*.txt, else its *.bvh, *.amc (+ *.asf) and
    *.npz files: a one-kind source when it holds one kind (named after it), else one that reads them all."""
    path = Path(path)
    if not path.exists():
        raise FileNotFoundError(f"{path}: no such folder")
    if not path.is_dir():
        raise ValueError(f"{path}: --data takes a folder (put the file in a sub-folder named after its action)")
    if any(path.glob("humanoid3d_*.txt")):
        return DeepMimicSource(path)
    kinds = {p.suffix.lower() for p in path.rglob("*") if p.is_file() and p.suffix.lower() in KINDS}
    if not kinds:
        raise ValueError(f"{path}: no motion files this version can read ({READABLE})")
    if len(kinds) == 1:
        return ONE_KIND[kinds.pop()](path, joint_map)
    return FolderSource(path, joint_map)


def source_hash(source: MotionSource) -> str:
    """sha256 over the bytes of the files a source reads (never over converted floats, which differ in
    their last bits between CPUs): a model trained on other data is stale."""
    h = hashlib.sha256()
    for p in source.data_files():
        h.update(p.name.encode() + b"\0" + p.read_bytes() + b"\0")
    return "sha256:" + h.hexdigest()
