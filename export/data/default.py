"""The default data: the CMU subset in data/cmu/ (split by person) and the DeepMimic clips of the
pybullet wheel as a second source.

DeepMimic's clips are one capture each (the only acrobatics: backflip, cartwheel, roll, ...), so they
are train-only: no person of theirs can be held out. Both sources' labels are folded into the served
vocabulary (data/vocabulary.py): DeepMimic's walk and walker takes are "walk", its run "run", its
dance_a and dance_b "dance", its kick joins CMU's "kick" (CMU holds out the soccer kicks of subject
10; DeepMimic's is a martial-arts kick like the trained karate kicks of subject 135). Every other
DeepMimic action keeps its own name. The split by person is checked on the folded labels.
"""
from __future__ import annotations

from pathlib import Path

from . import split, vocabulary
from .clip import Clip, Split
from .cmu import CMU_DIR, CmuSource, load_index
from .sources import DeepMimicSource, MotionSource

DEEPMIMIC_SUBJECT = "deepmimic"


class DefaultSource(MotionSource):
    name = "default"

    def __init__(self, cmu_root: Path = CMU_DIR, deepmimic_root: Path | None = None):
        self.cmu = CmuSource(cmu_root)
        self.deepmimic = DeepMimicSource(deepmimic_root)

    def clips(self) -> list[Clip]:
        out = self.cmu.clips()
        for clip in out:
            clip.source = {**clip.source, "action_fine": clip.action}
            clip.action = vocabulary.label(clip.action)
        for clip, _ in self.deepmimic._load():
            clip.name = f"deepmimic_{clip.name}"
            clip.action = vocabulary.label(clip.action)
            clip.subject = DEEPMIMIC_SUBJECT
            clip.split = Split("train", [(0, len(clip))], [])
            out.append(clip)
        names = [c.name for c in out]
        dupes = {n for n in names if names.count(n) > 1}
        if dupes:
            raise ValueError(f"{self.name}: clip names must be unique, repeated: {sorted(dupes)}")
        problems = split.person_split_problems(out, frozenset({DEEPMIMIC_SUBJECT}))
        if problems:
            raise ValueError(f"{self.name}: the split by person fails: {'; '.join(problems)}")
        return out

    def split_rules(self) -> list[str]:
        return self.cmu.split_rules() + [
            "the DeepMimic clips (one capture each, one performer) are train-only",
            "labels are folded into the served vocabulary (export/data/vocabulary.py): "
            + "; ".join(f"{a} <- {', '.join(sorted(f for f, b in vocabulary.FOLD.items() if b == a))}"
                        for a in sorted(set(vocabulary.FOLD.values())))]

    def notes(self) -> dict[str, str]:
        return dict(split.HELD_OUT_NOTES)

    def data_files(self) -> list[Path]:
        """Every source file the clips are read from: what the data hash covers."""
        cmu = [self.cmu.root / "index.json"]
        for e in load_index(self.cmu.root):
            cmu.append(self.cmu.root / e["file"])
            if e.get("asf"):
                cmu.append(self.cmu.root / e["asf"])
        return sorted(set(cmu)) + self.deepmimic.data_files()

