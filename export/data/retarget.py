"""Retargeting any joint positions onto the project skeleton: one method, used for BVH and npz alike.

The TypeScript twin is web/src/motion/retarget.ts; contract/vectors/retarget.json ties them.

1. A joint map (contract/joint-maps/*.json, overridable by a user's small JSON) names, for each
   of the 18 project joints, the source point it follows: a source joint, an End Site
   ("Head/end"), or the mean of several ("LeftUpLeg+RightUpLeg"). The first alternative whose
   names all exist in the file wins; `null` means "derive it" (head and toes only, see 5). A file is
   tried with the built-in maps of contract/joint-maps/order.json in order (a BVH: cmu-bvh, then
   daz), on the command line and on the page alike (`pick_map`).
2. Up axis: a z-up source is turned to y-up by (x, y, z) -> (x, z, -y) (a right-handed turn).
   Leading frames far from the rest of the take (a BVH conversion's T-pose) are dropped by rule
   (`leading_outliers`).
3. Frame rate: the source points are resampled to 30 Hz by linear interpolation in time
   (t_k = k / 30). Interpolating points shortens bones between frames slightly, which step 4
   undoes, because only directions survive it.
4. Walk the project skeleton from the root: each joint = its parent + the project bone length
   (|SKELETON.offsets|) x the unit direction from the parent's source point to the joint's. So
   each bone keeps its direction from the source and takes the project's length; proportions of
   the source body are discarded. The root keeps its trajectory (height and horizontal travel),
   scaled by project leg length / source leg length (hip-knee-ankle, mean over both legs and all
   frames), so feet that touch the ground in the source still touch it and a stride covers the
   distance a project-sized body would. That ratio also makes units irrelevant: cm, m, inches or
   CMU's 1/0.45-inch units give the same result, with nothing to declare.
5. Derived end points, when the source lacks them: the head continues the upper spine
   (neck + head length x unit(neck - chest)); a toe is the ankle plus the project's rest toe
   offset turned to the pelvis heading (forward = up x (right_hip - left_hip), foot flat).
6. Ground: the clip's floor is estimated once (export/ops/floor.py: a plane through the contact
   frames' lowest foot points, robust to a T-pose frame or a glitch) and put at y = 0.

Facing is left as it comes: windows are canonicalised later (ops/facing.py). Callers check every
import with `body_problems` (upright: head above the root, ankles below it; human proportions):
a file with an assumed joint order that fails is refused, a named one is warned
(`plausibility_warning`), which names a wrong up axis and the `up` that fixes it.
"""
from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..paths import CONTRACT_DIR
from ..ops.floor import on_floor
from .skeleton import SKELETON

FPS = 30.0
# Fewer frames (1/3 s at 30 Hz) cannot be a history for any served model.
MIN_FRAMES = 10
MAX_FRAMES = 108_000  # one hour at 30 Hz
JOINT_MAPS_DIR = CONTRACT_DIR / "joint-maps"
# The maps each kind of file is tried with, in order; the page reads the same file (joint-map.ts).
ORDER_FILE = JOINT_MAPS_DIR / "order.json"
DERIVABLE = ("head", "right_toe", "left_toe")
LEADING_STEPS = 10.0     # times the median step ...
LEADING_LEGS = 0.05      # ... and leg lengths: a leading frame this far from the next is not motion
LEADING_MAX = 3
LEGS = (("right_hip", "right_knee", "right_ankle"), ("left_hip", "left_knee", "left_ankle"))


class RetargetError(ValueError):
    """The source cannot be put on the project skeleton; the message names the file and why."""


class UnknownSkeletonError(RetargetError):
    pass


@dataclass
class JointMap:
    name: str
    up: str                                   # "y" or "z"
    joints: dict[str, list[str | None]]       # project joint -> alternatives
    orders: dict[str, list[str]] = field(default_factory=dict)  # joint count -> source names (npz)


KEYS = ("format", "version", "name", "about", "extends", "up", "joints", "orders")


def _check(doc: dict, where: str) -> None:
    unknown = sorted(set(doc) - set(KEYS))
    if unknown:
        raise RetargetError(f"{where}: unknown field {unknown[0]!r} (a joint map has {', '.join(KEYS)})")
    for key in ("joints", "orders"):
        if not isinstance(doc.get(key, {}), dict):
            raise RetargetError(f"{where}: field {key}: must be a JSON object")
    if doc.get("up", "y") not in ("y", "z"):
        raise RetargetError(f"{where}: field up: must be \"y\" or \"z\", got {doc.get('up')!r}")
    for joint, alts in doc.get("joints", {}).items():
        if joint not in SKELETON.names:
            raise RetargetError(f"{where}: field joints/{joint}: not a project joint ({', '.join(SKELETON.names)})")
        if not isinstance(alts, list) or not alts or not all(a is None or (isinstance(a, str) and a) for a in alts):
            raise RetargetError(f"{where}: field joints/{joint}: must be a non-empty list of source names or null")
        if None in alts and joint not in DERIVABLE:
            raise RetargetError(f"{where}: field joints/{joint}: only {', '.join(DERIVABLE)} can be derived (null)")
    for count, names in doc.get("orders", {}).items():
        if not count.isdigit() or not isinstance(names, list) or len(names) != int(count):
            raise RetargetError(f"{where}: field orders/{count}: must list exactly {count} joint names")


def tried_maps(kind: str) -> list[str]:
    """The built-in maps a file of `kind` ("bvh", "asf-amc", "npz") is tried with, in order
    (contract/joint-maps/order.json; BVH_MAPS in joint-map.ts reads the same list)."""
    return list(json.loads(ORDER_FILE.read_text())[kind])


def builtin_map(name: str) -> dict:
    path = JOINT_MAPS_DIR / f"{name}.json"
    if not path.exists() or path == ORDER_FILE:
        known = sorted(p.stem for p in JOINT_MAPS_DIR.glob("*.json") if p != ORDER_FILE)
        raise RetargetError(f"no joint map named {name!r} (built in: {', '.join(known)})")
    return json.loads(path.read_text())


def merge_maps(base: dict, override: dict | None, where: str = "joint map") -> JointMap:
    """The base map with a user's override on top: `joints` merge per project joint, `up` and
    `orders` entries replace; `extends` in the override names another built-in base."""
    if override and override.get("extends"):
        if not isinstance(override["extends"], str):
            raise RetargetError(f"{where}: field extends: the name of a built-in joint map")
        base = builtin_map(override["extends"])
    _check(base, base.get("name", "joint map"))
    doc = {"name": base.get("name", "custom"), "up": base.get("up", "y"),
           "joints": dict(base.get("joints", {})), "orders": dict(base.get("orders", {}))}
    if override:
        _check(override, where)
        doc["up"] = override.get("up", doc["up"])
        doc["joints"].update(override.get("joints", {}))
        doc["orders"].update(override.get("orders", {}))
        doc["name"] = f"{doc['name']} + {where}"
    missing = [j for j in SKELETON.names if j not in doc["joints"]]
    if missing:
        raise RetargetError(f"{where}: no entry for project joints {', '.join(missing)}")
    return JointMap(doc["name"], doc["up"], doc["joints"], doc["orders"])


def load_map(default: str, override: Path | dict | None = None) -> JointMap:
    """A built-in map (`cmu-bvh`, `smpl`), optionally overridden by a user's JSON file or dict."""
    where = "joint map"
    if isinstance(override, (str, Path)):
        where = str(override)
        try:
            override = json.loads(Path(override).read_text())
        except (OSError, json.JSONDecodeError) as e:
            raise RetargetError(f"{where}: not a readable joint map JSON ({e})") from e
        if not isinstance(override, dict):
            raise RetargetError(f"{where}: a joint map is a JSON object")
    return merge_maps(builtin_map(default), override, where)


def _key(name: str) -> str:
    # "mixamorig:LeftArm" and "leftarm" both match "LeftArm".
    return name.rsplit(":", 1)[-1].lower()


def _resolve(jmap: JointMap, names: list[str]) -> tuple[list[list[int] | None], list[str]]:
    """(per project joint the source indices whose mean it follows, or None (derived); the project
    joints no alternative finds, each with what was tried)."""
    exact = {n: i for i, n in enumerate(names)}
    loose: dict[str, int] = {}
    for i, n in enumerate(names):
        loose.setdefault(_key(n), i)

    def find(name: str) -> int | None:
        return exact.get(name, loose.get(_key(name)))

    out: list[list[int] | None] = []
    missing = []
    for joint in SKELETON.names:
        choice: list[int] | None = None
        found = False
        for alt in jmap.joints[joint]:
            if alt is None:
                found = True
                break
            idx = [find(part) for part in alt.split("+")]
            if None not in idx:
                choice, found = idx, True
                break
        if not found:
            missing.append(f"{joint} (tried {', '.join(a for a in jmap.joints[joint] if a)})")
        out.append(choice)
    return out, missing


def _unknown(jmap: JointMap, missing: list[str], names: list[str], where: str, also: str = "") -> UnknownSkeletonError:
    # every joint of the file, however many: a visitor needs the spine, arm and head names to write a map
    shown = ", ".join(n for n in names if "/end" not in n)
    return UnknownSkeletonError(
        f"{where}: unknown skeleton for joint map {jmap.name}: no source joint for {'; '.join(missing)}.{also} "
        f"The file's joints are: {shown}. Give a joint map (docs/BRING_YOUR_OWN.md)")


def resolve(jmap: JointMap, names: list[str], where: str) -> list[list[int] | None]:
    """Per project joint: the source indices whose mean it follows, or None (derived)."""
    out, missing = _resolve(jmap, names)
    if missing:
        raise _unknown(jmap, missing, names, where)
    return out


def pick_map(maps: list[JointMap], names: list[str], where: str) -> JointMap:
    """The first of `maps` whose joint names the file has (the order of tried_maps); when none fits,
    an UnknownSkeletonError naming what the first lacks and every map tried. Twin: importBvh's choice in bvh.ts."""
    misses = []
    for jmap in maps:
        missing = _resolve(jmap, names)[1]
        if not missing:
            return jmap
        misses.append(missing)
    also = "".join(f" Also tried joint map {m.name}: no source joint for {', '.join(x.split(' (')[0] for x in miss)}."
                   for m, miss in zip(maps[1:], misses[1:]))
    if len(maps) > 1:
        also += f" Tried in this order: {', '.join(m.name for m in maps)}."
    raise _unknown(maps[0], misses[0], names, where, also)


def to_y_up(points: np.ndarray, up: str) -> np.ndarray:
    if up == "y":
        return points
    return np.stack([points[..., 0], points[..., 2], -points[..., 1]], axis=-1)


def resample_points(points: np.ndarray, frame_time: float, out_fps: float = FPS) -> np.ndarray:
    """Linear interpolation in time from frames `frame_time` apart to `out_fps`, over the source's duration."""
    frames = len(points)
    if frames == 1:
        return points[:1].copy()
    n = int(np.floor(_span(frames, frame_time, out_fps))) + 1
    # u = (k / out_fps) / frame_time, written the same way in TypeScript so both pick the same frames;
    # a last frame that the rounded Frame Time puts past the end (by more than float rounding, which
    # is left as it always was) takes the source's last frame.
    u = (np.arange(n) / out_fps) / frame_time
    u = np.where(u > frames - 1 + 1e-9, frames - 1.0, u)
    idx = np.minimum(np.floor(u), frames - 2).astype(int)
    w = (u - idx)[:, None, None]
    return points[idx] * (1 - w) + points[idx + 1] * w


SPAN_ROUNDING = 1e-4   # a Frame Time written to 4-6 digits (".0083333", "0.0333333") is off by up to this share
SPAN_ROUNDING_MAX = 0.1  # output frames: never more, so a real fraction of a frame (x.25, x.5, x.75) is not rounded up


def _span(frames: int, frame_time: float, out_fps: float) -> float:
    """The source's duration in output frames, rounded up to a whole frame when the Frame Time's rounding
    alone keeps it short of one (138 frames at "0.0333333" span 136.99986 frames at 30 Hz: 137, so 138 frames
    come out, not 137). Twin: span in retarget.ts."""
    x = (frames - 1) * frame_time * out_fps
    up = np.ceil(x)
    return float(up) if up - x <= max(1e-9, min(SPAN_ROUNDING * x, SPAN_ROUNDING_MAX)) else x


PLAUSIBLE_HEAD = 0.25    # the head stands at least this many leg lengths above the root ...
PLAUSIBLE_FEET = 0.25    # ... and the ankles this many below it
PLAUSIBLE_SYMMETRY = 0.2  # left and right bones differ by at most this fraction
PLAUSIBLE_LEG = 1.2       # a leg (hip-knee-ankle) is this many times longer than any arm segment
AXES = "xyz"


def _axis_words(v: np.ndarray) -> str:
    """The file axis a direction runs along: "+y", "-z", ..."""
    a = int(np.argmax(np.abs(v)))
    return ("+" if v[a] > 0 else "-") + AXES[a]


def body_problems(points: np.ndarray, names: list[str], jmap: JointMap, where: str) -> list[str]:
    """Why the body as read (the map's joints, its `up` axis) cannot be a person standing upright with a
    human build; empty when it can. Upright: the head (or neck) at least PLAUSIBLE_HEAD leg lengths above
    the root and the ankles PLAUSIBLE_FEET below it (medians over frames); build: left and right bones
    match and the legs are longer than the arms' segments. A wrong up axis fails the first two and the
    message names the axis the body does stand along and the `up` that reads it upright.
    Twin: bodyProblems in retarget.ts."""
    sources = resolve(jmap, names, where)
    raw = np.asarray(points, dtype=np.float64)
    pts = to_y_up(raw, jmap.up)
    q = {j: pts[:, idx].mean(axis=1) for j, idx in zip(SKELETON.names, sources) if idx is not None}
    length = lambda a, b: float(np.median(np.linalg.norm(q[a] - q[b], axis=-1)))   # noqa: E731
    leg = np.mean([length(a, b) + length(b, c) for a, b, c in LEGS])
    out = []
    top = "head" if "head" in q else "neck"
    above = float(np.median(q[top][:, 1] - q["root"][:, 1]))
    below = float(np.median(q["root"][:, 1] - (q["left_ankle"][:, 1] + q["right_ankle"][:, 1]) / 2))
    if not above > PLAUSIBLE_HEAD * leg:
        out.append(f"the {top} is {above:.3g} above the root, less than {PLAUSIBLE_HEAD} leg lengths ({leg:.3g})")
    if not below > PLAUSIBLE_FEET * leg:
        out.append(f"the ankles are {below:.3g} below the root, less than {PLAUSIBLE_FEET} leg lengths ({leg:.3g})")
    if out:
        # the file's own axes: along which does the body run from the feet to the head?
        qr = {j: raw[:, idx].mean(axis=1) for j, idx in zip(SKELETON.names, sources) if idx is not None}
        body = np.median(qr[top] - (qr["left_ankle"] + qr["right_ankle"]) / 2, axis=0)
        along = _axis_words(body)
        fix = {"+y": "y", "+z": "z"}.get(along)
        if fix and fix != jmap.up:
            out.append(f"the body stands along {along} of the file, so the file looks {fix}-up: it was read with "
                       f"\"up\": \"{jmap.up}\" and lies flat; set \"up\": \"{fix}\" in the joint map")
        else:
            out.append(f"the body runs along {along} of the file from the feet to the head (upside down or lying "
                       f"down, read with \"up\": \"{jmap.up}\"); if the file stands upright, check its up axis "
                       "and the map's left and right joints")
    for a, b in (("hip", "knee"), ("knee", "ankle"), ("shoulder", "elbow"), ("elbow", "wrist")):
        r, l = length(f"right_{a}", f"right_{b}"), length(f"left_{a}", f"left_{b}")
        if abs(r - l) > PLAUSIBLE_SYMMETRY * (r + l) / 2:
            out.append(f"the right {a}-{b} bone ({r:.3g}) and the left one ({l:.3g}) differ by more than "
                       f"{PLAUSIBLE_SYMMETRY:.0%}")
    arm = max(length(f"{s}_{a}", f"{s}_{b}") for s in ("left", "right") for a, b in (("shoulder", "elbow"), ("elbow", "wrist")))
    if not leg > PLAUSIBLE_LEG * arm:
        out.append(f"the legs ({leg:.3g}) are not longer than {PLAUSIBLE_LEG} x the longest arm segment ({arm:.3g})")
    return out


def implausible(points: np.ndarray, names: list[str], jmap: JointMap, where: str) -> list[str]:
    """body_problems, for a body read with an *assumed* joint order: a caller refuses the file when any
    is found (a folded body). A file that names its joints is only warned (`plausibility_warning`):
    a handstand or a crawl is a real motion."""
    return body_problems(points, names, jmap, where)


def plausibility_warning(points: np.ndarray, names: list[str], jmap: JointMap, where: str) -> str | None:
    """One sentence for a file whose named joints fail body_problems (None when they pass): what is
    wrong and the fix. Every import gets it (sources.py prints it; importBvh/importAsfAmc carry it as
    origin.warnings). Twin: plausibilityWarning in retarget.ts."""
    problems = body_problems(points, names, jmap, where)
    if not problems:
        return None
    return (f"{where}: does not look like a person standing upright with the joint map {jmap.name}: "
            f"{'; '.join(problems)}. If that is not the motion, fix the joint map (docs/BRING_YOUR_OWN.md)")


def leading_outliers(points: np.ndarray, sources: list[list[int] | None]) -> int:
    """How many leading source frames are far from the rest of the take (a T-pose that a BVH
    conversion put first, a capture settling): frame 0 is dropped while its step into the next frame,
    the mean over the mapped points, is more than LEADING_STEPS times the take's median step and more
    than LEADING_LEGS leg lengths, at most LEADING_MAX frames. A rule, not a list of files; a real
    first step is never that far from the ones after it. Twin: leadingOutliers in retarget.ts."""
    used = sorted({i for idx in sources if idx for i in idx})
    if len(points) < 3 or not used:
        return 0
    p = points[:, used]
    steps = np.linalg.norm(np.diff(p, axis=0), axis=-1).mean(axis=1)           # [F-1]
    leg = _source_leg(points, sources)
    drop = 0
    while drop < LEADING_MAX and len(steps) - drop > 2:
        if not (steps[drop] > LEADING_STEPS * np.median(steps[drop:]) and steps[drop] > LEADING_LEGS * leg):
            break
        drop += 1
    return drop


def _source_leg(points: np.ndarray, sources: list[list[int] | None]) -> float:
    """The source's leg length (hip-knee-ankle, both legs, median over frames), in its own units."""
    q = {j: points[:, idx].mean(axis=1) for j, idx in zip(SKELETON.names, sources) if idx is not None}
    legs = [np.linalg.norm(q[a] - q[b], axis=-1) + np.linalg.norm(q[b] - q[c], axis=-1) for a, b, c in LEGS]
    return float(np.median(np.mean(legs, axis=0)))


def retarget(points: np.ndarray, names: list[str], frame_time: float, jmap: JointMap, where: str,
             min_frames: int = MIN_FRAMES) -> np.ndarray:
    """Source points [F, N, 3] named `names`, `frame_time` seconds apart -> project positions
    [F', 18, 3] at 30 Hz."""
    points = np.asarray(points, dtype=np.float64)
    if points.ndim != 3 or points.shape[2] != 3 or points.shape[1] != len(names):
        raise RetargetError(f"{where}: expected points [frames, {len(names)}, 3], got {points.shape}")
    if not np.all(np.isfinite(points)):
        raise RetargetError(f"{where}: contains NaN or infinite positions")
    if not (np.isfinite(frame_time) and frame_time > 0):
        raise RetargetError(f"{where}: the frame time must be positive, got {frame_time}")
    sources = resolve(jmap, names, where)
    if len(points) == 0:
        raise RetargetError(f"{where}: too few frames: the file has none")
    if (len(points) - 1) * frame_time * FPS >= MAX_FRAMES:
        raise RetargetError(f"{where}: {len(points)} frames {frame_time:g} s apart last longer than an hour; "
                            "check the frame time or cut the take shorter")
    raw = to_y_up(points, jmap.up)
    raw = raw[leading_outliers(raw, sources):]
    pts = resample_points(raw, frame_time)
    if len(pts) < min_frames:
        raise RetargetError(f"{where}: too few frames: {len(points)} at {1 / frame_time:.4g} Hz is {len(pts)} at 30 Hz, "
                            f"and a history needs at least {min_frames}")
    q = {j: pts[:, idx].mean(axis=1) for j, idx in zip(SKELETON.names, sources) if idx is not None}

    source_leg = np.mean([np.linalg.norm(q[a] - q[b], axis=-1) + np.linalg.norm(q[b] - q[c], axis=-1)
                          for a, b, c in LEGS])
    lengths = np.linalg.norm(SKELETON.offsets, axis=-1)
    project_leg = lengths[SKELETON.index("right_knee")] + lengths[SKELETON.index("right_ankle")]
    if not source_leg > 1e-9:
        raise RetargetError(f"{where}: the source legs have zero length; check the joint map")

    out = np.zeros((len(pts), SKELETON.num_joints, 3))
    out[:, 0] = q["root"] * (project_leg / source_leg)
    for j, (name, parent) in enumerate(zip(SKELETON.names, SKELETON.parents)):
        if parent < 0:
            continue
        if name in q:
            d = q[name] - q[SKELETON.names[parent]]
            norm = np.linalg.norm(d, axis=-1, keepdims=True)
            bad = np.flatnonzero(norm[:, 0] < 1e-6 * source_leg)
            if len(bad):
                raise RetargetError(f"{where}: the source points for {SKELETON.names[parent]} and {name} coincide "
                                    f"(frame {bad[0]} at 30 Hz); map them to different joints")
            out[:, j] = out[:, parent] + lengths[j] * d / norm
        elif name == "head":
            out[:, j] = out[:, parent] + lengths[j] * _unit(out[:, parent] - out[:, SKELETON.index("chest")])
        else:  # a toe: the rest offset turned to the pelvis heading
            across = out[:, SKELETON.index("right_hip")] - out[:, SKELETON.index("left_hip")]
            fwd = np.stack([across[:, 2], np.zeros(len(across)), -across[:, 0]], axis=-1)
            flat = np.linalg.norm(fwd, axis=-1) < 1e-9
            fwd[flat] = (1.0, 0.0, 0.0)  # hips vertical (lying on the side): no heading; keep +x
            rest = SKELETON.offsets[j]
            out[:, j] = out[:, parent] + rest[0] * _unit(fwd) + rest[1] * np.array([0.0, 1.0, 0.0])
    return on_floor(out)


def _unit(v: np.ndarray) -> np.ndarray:
    n = np.linalg.norm(v, axis=-1, keepdims=True)
    return v / np.maximum(n, 1e-12)
