"""Acclaim ASF/AMC motion capture (the CMU database's original form): parse, then forward kinematics.

Our own reader (tested in tests/export/test_asf_amc.py): on PyPI, asfamc-parser 0.0.2 reads the
text but has no forward kinematics, and nothing maintained does both.

ASF, the skeleton: sections start with a keyword at the start of a line.
    :units      length L (file lengths are inches x L, CMU's convention), angle deg|rad, mass (ignored)
    :root       order TX TY TZ RX RY RZ (the AMC's root values), axis XYZ, position x y z, orientation x y z
    :bonedata   begin / id / name / direction x y z / length l / axis ax ay az XYZ / dof rx ry rz /
                limits (lo hi) ... / end, once per bone
    :hierarchy  begin / parent child child ... / end
    (:version, :name, :documentation and other sections are skipped)
AMC, the motion: ":FULLY-SPECIFIED", ":DEGREES" or ":RADIANS", then per frame its number on its own
line and one line per bone with dofs: "name v1 v2 ...", values in the bone's dof order.

Semantics (Acclaim, as in CMU's own viewer): C = the bone's `axis` rotation, M = its AMC rotation,
each an Euler rotation applied in the order written (XYZ: first about x, then y, then z, all about
the fixed axes, so R = Rz Ry Rx). The bone's world rotation is L = L_parent C M C^-1 and its end is
the parent's end + L (direction x length); the root's rotation is C_root M_root C_root^-1 from its
`orientation`/`axis` and the RX RY RZ values, its position `position` + (TX, TY, TZ).

Points are named "root" (the root position) and each bone's name for the bone's END, in metres:
CMU's `length 0.45` makes one file unit 1/0.45 inch = 0.0254 / 0.45 m.
"""
from __future__ import annotations

import re
import warnings
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from scipy.spatial.transform import Rotation

INCH = 0.0254
MAX_BYTES = 64 * 1024 * 1024
MAX_BONES = 1000
ROTATIONS = ("rx", "ry", "rz")
ROOT_DOFS = ("tx", "ty", "tz", "rx", "ry", "rz")
_NUMBER_RE = re.compile(r"[-+]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][-+]?[0-9]+)?")
_FRAME_RE = re.compile(r"[0-9]+")
_BAD_CHAR_RE = re.compile(r"[^0-9eE+\-. \t\n]")   # bone values hold nothing else
_SPACE_BYTES = np.frombuffer(b" \t\n", dtype=np.uint8)


class AsfAmcFormatError(ValueError):
    """The file is not an ASF/AMC this project can read; the message names the file, the line and why."""


@dataclass
class Bone:
    name: str
    direction: np.ndarray   # [3] unit vector in the world frame at rest
    length: float           # file units
    axis: np.ndarray        # [3, 3] C: the bone's local frame in the world frame at rest
    dof: list[str]          # subset of rx ry rz, in the AMC's value order
    parent: int             # index into Asf.bones, -1 for the root


@dataclass
class Asf:
    bones: list[Bone]       # file order
    root_order: list[str]   # the AMC root values, e.g. tx ty tz rx ry rz
    root_axis: np.ndarray   # [3, 3] C_root from orientation and axis
    root_position: np.ndarray
    metres: float           # metres per file length unit
    degrees: bool           # angle unit of the ASF (and the AMC's default)

    @property
    def names(self) -> list[str]:
        """The points joint_positions returns: the root, then each bone's end."""
        return ["root"] + [b.name for b in self.bones]


@dataclass
class Amc:
    frames: np.ndarray              # [F] frame numbers as written
    values: dict[str, np.ndarray]   # "root" and each bone with dofs -> [F, dofs]
    degrees: bool

    def __len__(self) -> int:
        return len(self.frames)


def _fail(where: str, line: int, text: str) -> AsfAmcFormatError:
    return AsfAmcFormatError(f"{where}: line {line}: {text}")


def _numbers(tokens: list[str], count: int, where: str, n: int, what: str) -> list[float]:
    values = [float(t) if _NUMBER_RE.fullmatch(t) else None for t in tokens]
    if len(values) != count or None in values or not all(np.isfinite(v) for v in values):
        found = " ".join(tokens)[:40]
        raise _fail(where, n, f"{what} needs {count} number{'s' if count > 1 else ''}, found \"{found}\"")
    return values


def _euler(values, order: str, degrees: bool) -> np.ndarray:
    """Rotation matrices for angles paired with the letters of `order`, applied first to last about fixed axes."""
    # scipy's lowercase sequences are extrinsic (fixed axes), which is the order as written.
    return Rotation.from_euler(order.lower(), values, degrees=degrees).as_matrix()


def _axis_matrix(xyz: list[float], order: str, degrees: bool, where: str, n: int) -> np.ndarray:
    order = order.upper()
    if sorted(order) != ["X", "Y", "Z"]:
        raise _fail(where, n, f'axis order "{order}" must be a permutation of XYZ')
    # The three angles are about x, y and z; the order string says which turn comes first.
    return _euler([xyz["XYZ".index(c)] for c in order], order, degrees)


def _sections(text: str) -> list[tuple[int, str]]:
    """Non-empty, comment-free stripped lines with their 1-based numbers."""
    out = []
    for i, s in enumerate(re.split(r"\r\n|\r|\n", text)):
        s = s.split("#", 1)[0].strip()
        if s:
            out.append((i + 1, s))
    return out


def parse_asf(text: str, where: str = "ASF") -> Asf:
    """Parse ASF text; raises AsfAmcFormatError naming `where`, the line and the problem."""
    lines = _sections(text.removeprefix("\ufeff"))
    if not lines or not lines[0][1].startswith(":"):
        raise AsfAmcFormatError(f'{where}: not an ASF file (it must start with a keyword such as ":version")')
    length_unit, degrees = 1.0, True
    root: dict = {}
    bones: list[dict] = []
    hierarchy: list[tuple[int, str, list[str]]] = []
    section, block = "", None
    for n, s in lines:
        tokens = s.split()
        if s.startswith(":"):
            if block is not None:
                raise _fail(where, n, f'bone block opened at line {block["line"]} has no "end"')
            section = tokens[0].lower()
            if section in (":version", ":name"):
                section = ""  # one-line values we do not need
            continue
        key = tokens[0].lower()
        if section == ":units":
            if key == "length":
                length_unit = _numbers(tokens[1:], 1, where, n, "length")[0]
                if not length_unit > 0:
                    raise _fail(where, n, "the length unit must be positive")
            elif key == "angle":
                if len(tokens) != 2 or tokens[1].lower() not in ("deg", "rad"):
                    raise _fail(where, n, 'expected "angle deg" or "angle rad"')
                degrees = tokens[1].lower() == "deg"
        elif section == ":root":
            if key == "order":
                order = [t.lower() for t in tokens[1:]]
                bad = [t for t in order if t not in ROOT_DOFS]
                if bad or len(set(order)) != len(order):
                    raise _fail(where, n, f'root order "{" ".join(tokens[1:])[:40]}" must list distinct '
                                          'TX TY TZ RX RY RZ')
                root["order"] = order
            elif key == "axis":
                if len(tokens) != 2:
                    raise _fail(where, n, 'expected "axis XYZ" (the root rotation order)')
                root["axis"] = (tokens[1], n)
            elif key in ("position", "orientation"):
                root[key] = _numbers(tokens[1:], 3, where, n, key)
            else:
                raise _fail(where, n, f'unknown root field "{tokens[0][:20]}" '
                                      '(expected order, axis, position, orientation)')
        elif section == ":bonedata":
            if key == "begin":
                if block is not None:
                    raise _fail(where, n, f'"begin" inside the bone block opened at line {block["line"]} '
                                          '(missing "end"?)')
                block = {"line": n}
            elif key == "end":
                if block is None:
                    raise _fail(where, n, '"end" without a "begin"')
                bones.append(block)
                block = None
                if len(bones) > MAX_BONES:
                    raise _fail(where, n, f"more than {MAX_BONES} bones: not a body skeleton")
            elif block is None:
                raise _fail(where, n, f'expected "begin" of a bone, found "{s[:40]}"')
            elif key == "name":
                if len(tokens) != 2:
                    raise _fail(where, n, 'expected "name bonename"')
                block["name"] = tokens[1]
            elif key == "direction":
                block["direction"] = (_numbers(tokens[1:], 3, where, n, "direction"), n)
            elif key == "length":
                block["length"] = _numbers(tokens[1:], 1, where, n, "length")[0]
            elif key == "axis":
                if len(tokens) != 5:
                    raise _fail(where, n, 'expected "axis ax ay az XYZ" (three angles and their order)')
                block["axis"] = (_numbers(tokens[1:4], 3, where, n, "axis"), tokens[4], n)
            elif key == "dof":
                dof = [t.lower() for t in tokens[1:]]
                bad = [t for t in dof if t not in ROTATIONS]
                if bad:
                    raise _fail(where, n, f'dof "{bad[0][:10]}" is not supported (only rx ry rz: CMU bones rotate, '
                                          'they do not stretch or slide)')
                if len(set(dof)) != len(dof):
                    raise _fail(where, n, "a dof is listed twice")
                block["dof"] = dof
            elif key in ("id", "bodymass", "cofmass", "limits") or s.startswith("("):
                pass  # not needed for positions
            else:
                raise _fail(where, n, f'unknown bone field "{tokens[0][:20]}"')
        elif section == ":hierarchy":
            if key in ("begin", "end"):
                continue
            hierarchy.append((n, tokens[0], tokens[1:]))
    if block is not None:
        raise AsfAmcFormatError(f'{where}: the bone block opened at line {block["line"]} has no "end" (truncated?)')
    if not bones:
        raise AsfAmcFormatError(f"{where}: no :bonedata (an ASF lists its bones there)")
    if not hierarchy:
        raise AsfAmcFormatError(f"{where}: no :hierarchy (an ASF says there which bone hangs from which)")

    names = []
    for b in bones:
        for field in ("name", "direction", "length", "axis"):
            if field not in b:
                raise _fail(where, b["line"], f"the bone block has no \"{field}\"")
        if b["name"] in names or b["name"].lower() == "root":
            raise _fail(where, b["line"], f'bone name "{b["name"]}" appears twice (or is "root")')
        names.append(b["name"])

    parents: dict[str, str] = {}
    for n, parent, children in hierarchy:
        if parent != "root" and parent not in names:
            raise _fail(where, n, f'hierarchy names "{parent[:30]}", which is not a bone in :bonedata')
        for c in children:
            if c not in names:
                raise _fail(where, n, f'hierarchy names "{c[:30]}", which is not a bone in :bonedata')
            if c in parents:
                raise _fail(where, n, f'bone "{c}" has two parents ({parents[c]} and {parent})')
            parents[c] = parent
    orphans = [nm for nm in names if nm not in parents]
    if orphans:
        raise AsfAmcFormatError(f'{where}: bone "{orphans[0]}" is not in :hierarchy (every bone needs a parent)')
    # A parent cycle would never reach the root.
    for nm in names:
        seen, p = set(), nm
        while p != "root":
            if p in seen:
                raise AsfAmcFormatError(f'{where}: :hierarchy has a cycle through "{p}"')
            seen.add(p)
            p = parents[p]

    out = []
    for b in bones:
        d, dn = b["direction"]
        d = np.asarray(d, dtype=np.float64)
        norm = np.linalg.norm(d)
        if not norm > 0:
            raise _fail(where, dn, f'bone "{b["name"]}" has a zero direction')
        xyz, order, an = b["axis"]
        parent = parents[b["name"]]
        out.append(Bone(name=b["name"], direction=d / norm, length=float(b["length"]),
                        axis=_axis_matrix(xyz, order, degrees, where, an), dof=b.get("dof", []),
                        parent=-1 if parent == "root" else names.index(parent)))
    axis, an = root.get("axis", ("XYZ", lines[0][0]))
    return Asf(bones=out, root_order=root.get("order", list(ROOT_DOFS)),
               root_axis=_axis_matrix(root.get("orientation", [0.0, 0.0, 0.0]), axis, degrees, where, an),
               root_position=np.asarray(root.get("position", [0.0, 0.0, 0.0]), dtype=np.float64),
               metres=INCH / length_unit, degrees=degrees)


def _dofs(asf: Asf) -> dict[str, int]:
    return {"root": len(asf.root_order), **{b.name: len(b.dof) for b in asf.bones if b.dof}}


def _token_counts(block: str, rows: int) -> np.ndarray | None:
    """Numbers per line of a newline-joined block, counted on the bytes (a bulk check, no per-line Python)."""
    buf = np.frombuffer(block.encode("ascii"), dtype=np.uint8)
    space = np.isin(buf, _SPACE_BYTES)
    starts = np.flatnonzero(~space & np.concatenate([[True], space[:-1]]))
    counts = np.bincount(np.searchsorted(np.flatnonzero(buf == 10), starts), minlength=rows)
    return counts if len(counts) == rows else None


def _fast_body(body: list[str], first: int, dofs: dict[str, int]) -> tuple[np.ndarray, dict] | None:
    """The common layout (every frame lists the same bones in the same order) read column by column
    with numpy. None when anything differs; the line-by-line reader then reads it or names the problem."""
    if not _FRAME_RE.fullmatch(body[0]):
        return None
    k = next((i for i in range(1, len(body)) if _FRAME_RE.fullmatch(body[i])), len(body)) - 1
    period = k + 1
    if k < 1 or len(body) % period:
        return None
    frames = len(body) // period
    order = [body[1 + b].split(" ", 1)[0] for b in range(k)]
    if sorted(order) != sorted(dofs):
        return None
    numbers = [str(first + f) for f in range(frames)]
    if body[0::period] != numbers:
        return None
    values = {}
    for b, name in enumerate(order):
        col = body[1 + b::period]
        prefix = name + " "
        cut = len(prefix)
        if not all(s.startswith(prefix) for s in col):
            return None
        block = "\n".join([s[cut:] for s in col])
        if _BAD_CHAR_RE.search(block):
            return None
        counts = _token_counts(block, frames)
        if counts is None or np.any(counts != dofs[name]):
            return None
        with warnings.catch_warnings():
            # numpy stops at a token it cannot read (e.g. "1.5.3") with a warning or an error
            warnings.simplefilter("error", DeprecationWarning)
            try:
                v = np.fromstring(block, sep=" ")
            except (DeprecationWarning, ValueError):
                return None
        if v.size != frames * dofs[name] or not np.all(np.isfinite(v)):
            return None
        values[name] = v.reshape(frames, dofs[name])
    return np.arange(first, first + frames), values


def _slow_body(body: list[str], start: int, dofs: dict[str, int], where: str) -> tuple[np.ndarray, dict]:
    """Line by line: any bone order per frame, blank lines; the first problem is raised with its line."""
    frames: list[int] = []
    rows: dict[str, list[list[float]]] = {name: [] for name in dofs}
    seen: set[str] = set()
    frame_line = 0

    def close(n: int) -> None:
        missing = [name for name in dofs if name not in seen]
        if missing:
            raise _fail(where, n, f"frame {frames[-1]} (line {frame_line}) has no values for "
                                  f"{', '.join(missing[:3])}{' ...' if len(missing) > 3 else ''} "
                                  "(a fully specified AMC gives every bone with dofs in every frame)")

    for i, s in enumerate(body):
        n = start + i
        s = s.strip()
        if not s:
            continue
        tokens = s.split()
        if _FRAME_RE.fullmatch(s):
            if frames:
                close(n)
                if int(s) != frames[-1] + 1:
                    raise _fail(where, n, f"frame {s} follows frame {frames[-1]} (frames must count up by one)")
            frames.append(int(s))
            frame_line, seen = n, set()
            continue
        name = tokens[0]
        if not frames:
            raise _fail(where, n, f'"{s[:40]}" comes before the first frame number')
        if name not in dofs:
            hint = f' (frame numbers are whole numbers, found "{name[:20]}")' if _NUMBER_RE.fullmatch(name) else ""
            raise _fail(where, n, f'"{name[:30]}" is not a bone with dofs in the ASF{hint}')
        if name in seen:
            raise _fail(where, n, f'bone "{name}" appears twice in frame {frames[-1]}')
        seen.add(name)
        what = f'bone "{name}"' if name != "root" else "the root"
        rows[name].append(_numbers(tokens[1:], dofs[name], where, n, what))
    if not frames:
        raise AsfAmcFormatError(f"{where}: no frames (a frame is its number on its own line, then one line per bone)")
    close(start + len(body) - 1)
    return np.asarray(frames), {name: np.asarray(r, dtype=np.float64).reshape(len(frames), dofs[name])
                                for name, r in rows.items()}


def parse_amc(text: str, asf: Asf, where: str = "AMC") -> Amc:
    """Parse AMC text for the skeleton `asf`; raises AsfAmcFormatError naming `where`, the line and the problem."""
    lines = text.removeprefix("\ufeff").replace("\r\n", "\n").replace("\r", "\n").split("\n")
    degrees = asf.degrees
    i = 0
    while i < len(lines):
        s = lines[i].strip()
        if not s or s.startswith("#"):
            i += 1
            continue
        if not s.startswith(":"):
            break
        key = s.split()[0].upper()
        if key in (":DEGREES", ":RADIANS"):
            degrees = key == ":DEGREES"
        elif key != ":FULLY-SPECIFIED":
            raise _fail(where, i + 1, f'unknown keyword "{s[:40]}" (expected :FULLY-SPECIFIED, :DEGREES or :RADIANS)')
        i += 1
    body = lines[i:]
    while body and not body[-1].strip():
        body.pop()
    if not body:
        raise AsfAmcFormatError(f"{where}: no frames (a frame is its number on its own line, then one line per bone)")
    dofs = _dofs(asf)
    fast = None
    if _FRAME_RE.fullmatch(body[0]):
        fast = _fast_body(body, int(body[0]), dofs)
    frames, values = fast if fast is not None else _slow_body(body, i + 1, dofs, where)
    return Amc(frames=frames, values=values, degrees=degrees)


def _read_text(path: Path) -> str:
    try:
        size = path.stat().st_size
        if size > MAX_BYTES:
            raise AsfAmcFormatError(f"{path}: {size / 2**20:.0f} MB is larger than this reader takes "
                                    f"({MAX_BYTES // 2**20} MB)")
        return path.read_text(encoding="utf-8", errors="replace")
    except OSError as e:
        raise AsfAmcFormatError(f"{path}: cannot be read ({e.strerror or e})") from e


def read_asf(path: str | Path) -> Asf:
    path = Path(path)
    return parse_asf(_read_text(path), str(path))


def read_amc(path: str | Path, asf: Asf) -> Amc:
    path = Path(path)
    return parse_amc(_read_text(path), asf, str(path))


def joint_positions(asf: Asf, amc: Amc) -> np.ndarray:
    """World positions [F, 1 + bones, 3] in metres of the root and each bone's end (`asf.names`)."""
    frames = len(amc)
    root = amc.values["root"]
    pos = np.tile(asf.root_position, (frames, 1))
    rot_cols = [k for k, d in enumerate(asf.root_order) if d in ROTATIONS]
    for k, d in enumerate(asf.root_order):
        if d.startswith("t"):
            pos[:, "xyz".index(d[1])] += root[:, k]
    if rot_cols:
        m = _euler(root[:, rot_cols], "".join(asf.root_order[k][1] for k in rot_cols), amc.degrees)
        world_root = asf.root_axis @ m @ asf.root_axis.T
    else:
        world_root = np.broadcast_to(np.eye(3), (frames, 3, 3))

    out = np.zeros((frames, 1 + len(asf.bones), 3))
    out[:, 0] = pos
    world: list[np.ndarray | None] = [None] * len(asf.bones)
    done = [False] * len(asf.bones)
    # Parents first: the hierarchy may list a child before its parent in :bonedata.
    todo = list(range(len(asf.bones)))
    while todo:
        rest = []
        for j in todo:
            bone = asf.bones[j]
            if bone.parent >= 0 and not done[bone.parent]:
                rest.append(j)
                continue
            parent_rot = world_root if bone.parent < 0 else world[bone.parent]
            start = out[:, 0] if bone.parent < 0 else out[:, 1 + bone.parent]
            if bone.dof:
                m = _euler(amc.values[bone.name], "".join(d[1] for d in bone.dof), amc.degrees)
                rot = parent_rot @ (bone.axis @ m @ bone.axis.T)
            else:
                rot = parent_rot
            world[j] = rot
            out[:, 1 + j] = start + rot @ (bone.direction * bone.length)
            done[j] = True
        todo = rest
    return out * asf.metres


def read_asf_amc(asf_path: str | Path, amc_path: str | Path) -> tuple[list[str], np.ndarray]:
    """(names, positions [F, N, 3] metres) of an ASF skeleton moved by an AMC motion."""
    asf = read_asf(asf_path)
    return asf.names, joint_positions(asf, read_amc(amc_path, asf))
