"""The `foot_plant` family of shared test vectors: planted feet (ops/foot_plant.py) on served clips.

Inputs are served walks and runs whose root travel is stretched (x 1.6) or shrunk (x 0.4) about the
present, so their feet slide as a model's do, and one sample held still; the Python result in float64.
TypeScript (web/src/predictor/foot-plant.ts) must reproduce it within the file's tolerance; registered
in export/vectors.py, which derives that tolerance.
"""
from __future__ import annotations

import json

import numpy as np

from .ops.foot_plant import plant_feet

FRAMES = 24
STRETCH = (1.6, 0.4)


def _served(role: str = "test") -> list[tuple[str, np.ndarray]]:
    from .data.clip_json import read_clip
    from .paths import CLIPS_DIR
    index = json.loads((CLIPS_DIR / "index.json").read_text())
    names = sorted(c["name"] for c in index["clips"] if c["role"] == role and c["frames"] >= FRAMES + 6
                   and c.get("action") in ("walk", "run"))[:2]
    return [(n, read_clip(CLIPS_DIR / f"{n}.json").positions[5:6 + FRAMES].astype(np.float32).astype(np.float64))
            for n in names]


def _stretched(motion: np.ndarray, factor: float) -> np.ndarray:
    """The frames after the first with the root's travel from the first frame times `factor`."""
    out = motion[1:].copy()
    shift = (motion[1:, 0, [0, 2]] - motion[0, 0, [0, 2]]) * (factor - 1)
    out[..., [0, 2]] += shift[:, None]
    return out


def foot_plant_vector() -> dict:
    cases = []
    for name, m in _served():
        futures = np.stack([_stretched(m, f) for f in STRETCH] + [np.repeat(m[:1], FRAMES, 0)])
        cases.append({"clip": name, "present": m[0].tolist(), "futures": futures.tolist(),
                      "planted": plant_feet(m[0], futures).tolist()})
    return {"about": "ops/foot_plant.plant_feet on served walks and runs with their root travel stretched and "
                     "shrunk about the present, and held still: present [J][3], futures [K][T][J][3], planted",
            "cases": cases}
