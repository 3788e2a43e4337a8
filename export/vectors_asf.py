"""Shared test vector `asf`: Python's reading of Acclaim ASF/AMC text (export/data/asf_amc.py) and its
retargeting with the built-in `cmu-asf` joint map (export/data/retarget.py), which TypeScript
(web/src/motion/asf-amc.ts + web/src/motion/retarget.ts) must reproduce from the very same text,
stored in each case, within the file's derived tolerance.

Two cases: a tiny hand-made skeleton (the bones the cmu-asf map reads and nothing else; rotations on
several axes, non-trivial bone `axis` frames, a root with its own rotation order, orientation and
position, a bone listed before its parent, a dof order other than x y z, `length 0.45`) at 40 Hz, and
the first 41 frames of CMU take 05_02 at CMU's 120 Hz (the ASF whole, the AMC cut after frame 41).
"""
from __future__ import annotations

import numpy as np

from .data.asf_amc import joint_positions, parse_amc, parse_asf
from .data.cmu import CMU_DIR, load_index
from .data.retarget import load_map, retarget

TAKE = "05_02"
TAKE_FRAMES = 41            # at 120 Hz: 11 frames at 30 Hz, one more than a history's minimum
TINY_FPS = 40               # not CMU's 120: the frame rate is the caller's, the AMC does not state it

TINY_ASF = """# A hand-made skeleton for the shared vector: the bones the cmu-asf joint map reads.
:version 1.10
:name tiny
:units
  mass 1.0
  length 0.45
  angle deg
:documentation
   Made by hand (export/vectors_asf.py). ltibia comes before its parent lfemur on purpose.
:root
   order TX TY TZ RZ RX RY
   axis ZYX
   position 0.5 1.0 -0.5
   orientation 5 -10 15
:bonedata
  begin
     id 1
     name lhipjoint
     direction 0.65 -0.68 0.34
     length 2.5
     axis 0 0 0  XYZ
  end
  begin
     id 2
     name ltibia
     direction 0.34202 -0.939693 0
     length 7.9
     axis 0 0 20  XYZ
    dof rx
    limits (-10.0 170.0)
  end
  begin
     id 3
     name lfemur
     direction 0.34202 -0.939693 0
     length 6.6
     axis 0 0 20  XYZ
    dof rx ry rz
    limits (-160.0 20.0)
           (-70.0 70.0)
           (-60.0 70.0)
  end
  begin
     id 4
     name rhipjoint
     direction -0.65 -0.68 0.34
     length 2.5
     axis 0 0 0  XYZ
  end
  begin
     id 5
     name rfemur
     direction -0.34202 -0.939693 0
     length 6.6
     axis 0 0 -20  XYZ
    dof rz rx
  end
  begin
     id 6
     name rtibia
     direction -0.34202 -0.939693 0
     length 7.9
     axis 0 0 -20  XYZ
    dof rx
  end
  begin
     id 7
     name rfoot
     direction -0.08 -0.22 0.97
     length 2.3
     axis -90 0 -20  XYZ
    dof rx rz
  end
  begin
     id 8
     name lowerback
     direction 0.01 1 -0.05
     length 2.1
     axis 0 0 0  XYZ
    dof rx ry rz
  end
  begin
     id 9
     name upperback
     direction 0 1 0.02
     length 2.2
     axis 0 0 0  XYZ
    dof ry
  end
  begin
     id 10
     name thorax
     direction 0 1 0
     length 2.2
     axis 0 0 0  XYZ
  end
  begin
     id 11
     name lowerneck
     direction 0 1 -0.1
     length 1.6
     axis 0 0 0  XYZ
    dof rx rz
  end
  begin
     id 12
     name head
     direction 0 1 0.05
     length 1.7
     axis 0 0 0  XYZ
  end
  begin
     id 13
     name lclavicle
     direction 0.92 0.38 0
     length 3.4
     axis 0 0 -20  XYZ
    dof ry rz
  end
  begin
     id 14
     name lhumerus
     direction 1 0 0
     length 5.0
     axis 10 -30 25  ZYX
    dof rx ry rz
  end
  begin
     id 15
     name lradius
     direction 1 0 0
     length 3.6
     axis 0 0 -90  XYZ
    dof rx
  end
  begin
     id 16
     name rclavicle
     direction -0.92 0.38 0
     length 3.4
     axis 0 0 20  XYZ
  end
  begin
     id 17
     name rhumerus
     direction -1 0 0
     length 5.0
     axis 0 0 90  XYZ
    dof rz ry rx
  end
  begin
     id 18
     name rradius
     direction -1 0 0
     length 3.6
     axis 0 0 90  XYZ
    dof rx
  end
:hierarchy
  begin
    root lhipjoint rhipjoint lowerback
    lhipjoint lfemur
    lfemur ltibia
    rhipjoint rfemur
    rfemur rtibia
    rtibia rfoot
    lowerback upperback
    upperback thorax
    thorax lowerneck lclavicle rclavicle
    lowerneck head
    lclavicle lhumerus
    lhumerus lradius
    rclavicle rhumerus
    rhumerus rradius
  end
"""

# Per bone with dofs, per value: (at frame 1, change per frame, change per frame squared), in
# hundredths, so every number in the AMC is an exact decimal whatever the machine.
TINY_MOTION = {
    "root": [(40, 25, 0), (1650, 3, -1), (-20, 12, 1), (500, 150, 0), (-300, 40, 4), (1000, -90, 2)],
    "lowerback": [(-500, 30, 0), (200, -20, 1), (100, 15, -1)],
    "upperback": [(300, -40, 2)],
    "lowerneck": [(-900, 50, 0), (250, 10, -2)],
    "lfemur": [(-2500, 300, -10), (800, -50, 2), (-600, 40, 1)],
    "ltibia": [(1500, 200, 8)],
    "rfemur": [(700, -60, 3), (-1800, -150, 9)],
    "rtibia": [(3000, -180, 6)],
    "rfoot": [(-1500, 70, 0), (1000, -30, 1)],
    "lclavicle": [(400, 20, 0), (-600, 30, -1)],
    "lhumerus": [(-4000, 250, 0), (1200, -100, 3), (6000, -200, 5)],
    "lradius": [(2500, 150, -4)],
    "rhumerus": [(-3500, 90, 2), (800, 120, -3), (-1500, 60, 0)],
    "rradius": [(1800, -100, 6)],
}
TINY_FRAMES = 15


def _hundredths(n: int) -> str:
    sign = "-" if n < 0 else ""
    return f"{sign}{abs(n) // 100}.{abs(n) % 100:02d}"


def tiny_amc() -> str:
    lines = ["#!OML:ASF tiny.asf", ":FULLY-SPECIFIED", ":DEGREES"]
    for f in range(TINY_FRAMES):
        lines.append(str(f + 1))
        for bone, coeffs in TINY_MOTION.items():
            lines.append(" ".join([bone] + [_hundredths(a + b * f + c * f * f) for a, b, c in coeffs]))
    return "\n".join(lines) + "\n"


def take_text(take: str = TAKE, frames: int = TAKE_FRAMES) -> tuple[str, str, str, str]:
    """(asf file, asf text, amc file, amc text cut after `frames` frames) of a CMU ASF/AMC take."""
    entry = next(e for e in load_index() if e["take"] == take)
    asf_text = (CMU_DIR / entry["asf"]).read_text()
    lines = (CMU_DIR / entry["file"]).read_text().splitlines()
    cut = lines.index(str(frames + 1))      # the line holding the number of the first frame left out
    return (f"data/cmu/{entry['asf']}", asf_text, f"data/cmu/{entry['file']}", "\n".join(lines[:cut]) + "\n")


def _case(name: str, asf_file: str, asf_text: str, amc_file: str, amc_text: str, fps: float) -> dict:
    asf = parse_asf(asf_text, asf_file)
    amc = parse_amc(amc_text, asf, amc_file)
    points = joint_positions(asf, amc)
    positions = retarget(points, asf.names, 1.0 / fps, load_map("cmu-asf"), amc_file)
    return {"name": name, "asf_file": asf_file, "amc_file": amc_file, "fps": fps, "asf": asf_text,
            "amc": amc_text, "names": asf.names, "frames": len(points), "points": np.asarray(points).tolist(),
            "retargeted_frames": len(positions), "positions": np.asarray(positions).tolist()}


def asf_vector() -> dict:
    cases = [_case("hand-made", "tiny.asf", TINY_ASF, "tiny.amc", tiny_amc(), TINY_FPS)]
    cases.append(_case(f"cmu {TAKE}, first {TAKE_FRAMES} frames", *take_text(), 120))
    return {"about": "ASF + AMC text (stored in each case) at `fps` -> `names` and `points` [frames][names][3], "
                     "metres (export/data/asf_amc.py: the root, then each bone's end), and `positions` "
                     "[retargeted_frames][18][3] at 30 Hz with the cmu-asf joint map (export/data/retarget.py); "
                     "TypeScript (web/src/motion/asf-amc.ts) must reproduce them from the same text",
            "cases": cases}
