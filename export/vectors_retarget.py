"""Shared test vector `retarget`: Python's retargeting of fixture BVH files, which TypeScript
(three.js BVHLoader + web/src/motion/retarget.ts) must reproduce from the same text, within the
file's derived tolerance."""
from __future__ import annotations

import numpy as np

from .data.bvh import joint_positions, read_bvh
from .data.retarget import load_map, retarget
from .paths import ROOT

CASES = [
    ("tests/fixtures/walk.bvh", None),
    ("tests/fixtures/walk_zup.bvh", {"up": "z"}),
    ("tests/fixtures/knee.bvh", {"joints": {"head": [None], "right_toe": [None], "left_toe": [None]}}),
    ("tests/fixtures/six_channels.bvh", None),        # position channels on every joint replace its OFFSET
    ("tests/fixtures/frame_time_rounded.bvh", None),  # "Frame Time: 0.0333333": all 31 frames come out
]


def retarget_vector() -> dict:
    cases = []
    for rel, override in CASES:
        bvh = read_bvh(ROOT / rel)
        jmap = load_map("cmu-bvh", override)
        out = retarget(joint_positions(bvh), bvh.names, bvh.frame_time, jmap, rel)
        cases.append({"file": rel, "joint_map": override, "frames": len(out),
                      "positions": out.tolist()})
    return {"about": "BVH file + joint map override (on cmu-bvh) -> positions [frames][18][3] at 30 Hz; "
                     "TypeScript must reproduce them from the same text", "cases": cases}
