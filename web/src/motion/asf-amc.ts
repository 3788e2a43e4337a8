// A dropped Acclaim ASF (skeleton) + AMC (motion) pair, the CMU database's original form -> a Motion on
// the project skeleton, or a MotionImportError naming the file, the line and the problem.
// Twin of export/data/asf_amc.py: the same grammar, the same messages, the same forward kinematics
// (its docstring states the Acclaim semantics); contract/vectors/asf.json ties the two. The points are
// retargeted (retarget.ts) with the built-in cmu-asf joint map, optionally overridden by the user's.
//
// Points are named "root" (the root position) and each bone's name for the bone's END, in metres:
// one file unit is 0.0254 / L metres for ":units length L" (CMU's 0.45: 1/0.45 inch).
import type { Skeleton } from '../contract/types';
import { MAX_BYTES, MAX_SOURCE_FRAMES, MotionImportError, motionName, type ImportedMotion, type ImportOptions } from './bvh';
import { ASF_AMC_MAPS, loadJointMap, type JointMap } from './joint-map';
import { MIN_FRAMES, pickMap, plausibilityWarning, RetargetError, retarget, type SourcePoints } from './retarget';

export const INCH = 0.0254;
/** The same bone limit as export/data/asf_amc.py: more is not a body skeleton. */
export const MAX_BONES = 1000;
/** The AMC does not state its frame rate; CMU captured at 120 Hz, so that is the default. */
export const CMU_FPS = 120;
const ROTATIONS = ['rx', 'ry', 'rz'];
const ROOT_DOFS = ['tx', 'ty', 'tz', 'rx', 'ry', 'rz'];
const NUMBER = /^[-+]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][-+]?[0-9]+)?$/;
const FRAME = /^[0-9]+$/;
// Python's str.split() / str.strip() whitespace (str.isspace), so lines break into the same tokens.
const PY_SPACE = '\\t\\n\\v\\f\\r\\x1c-\\x1f \\x85\\xa0\\u1680\\u2000-\\u200a\\u2028\\u2029\\u202f\\u205f\\u3000';
const SPACES = new RegExp(`[${PY_SPACE}]+`);
const TRIM = new RegExp(`^[${PY_SPACE}]+|[${PY_SPACE}]+$`, 'g');
const LINES = /\r\n|\r|\n/;

const strip = (s: string) => s.replace(TRIM, '');
const tokenize = (s: string) => s.split(SPACES).filter((t) => t.length > 0);
/** Python's s[:n]: the first n code points. */
function cut(s: string, n: number): string {
  return Array.from(s.slice(0, 2 * n)).slice(0, n).join('');
}

/** A 3x3 rotation, row-major. */
export type Mat3 = Float64Array;

export interface AsfBone {
  name: string;
  /** Unit vector in the world frame at rest. */
  direction: [number, number, number];
  /** File units. */
  length: number;
  /** C: the bone's local frame in the world frame at rest. */
  axis: Mat3;
  /** Subset of rx ry rz, in the AMC's value order. */
  dof: string[];
  /** Index into Asf.bones, -1 for the root. */
  parent: number;
}

export interface Asf {
  /** File order. */
  bones: AsfBone[];
  /** The AMC root values, e.g. tx ty tz rx ry rz. */
  rootOrder: string[];
  rootAxis: Mat3;
  rootPosition: [number, number, number];
  /** Metres per file length unit. */
  metres: number;
  /** Angle unit of the ASF (and the AMC's default). */
  degrees: boolean;
  /** The points asfAmcPoints returns: the root, then each bone's end. */
  names: string[];
}

export interface Amc {
  /** Frame numbers as written (they count up by one). */
  first: bigint;
  frames: number;
  /** "root" and each bone with dofs -> [frames * dofs], row-major. */
  values: Map<string, Float64Array>;
  degrees: boolean;
}

const fail = (where: string, line: number, text: string) => new MotionImportError(`${where}: line ${line}: ${text}`, 'not-asf-amc');
const bad = (text: string) => new MotionImportError(text, 'not-asf-amc');

function numbers(tokens: string[], count: number, where: string, n: number, what: string): number[] {
  const values = tokens.map((t) => (NUMBER.test(t) ? Number(t) : NaN));
  if (values.length !== count || !values.every(Number.isFinite)) {
    throw fail(where, n, `${what} needs ${count} number${count > 1 ? 's' : ''}, found "${cut(tokens.join(' '), 40)}"`);
  }
  return values;
}

function matmul(a: Mat3, b: Mat3): Mat3 {
  const out = new Float64Array(9);
  for (let i = 0; i < 3; i++) {
    for (let k = 0; k < 3; k++) out[i * 3 + k] = a[i * 3] * b[k] + a[i * 3 + 1] * b[3 + k] + a[i * 3 + 2] * b[6 + k];
  }
  return out;
}

function transpose(a: Mat3): Mat3 {
  return Float64Array.of(a[0], a[3], a[6], a[1], a[4], a[7], a[2], a[5], a[8]);
}

const IDENTITY: Mat3 = Float64Array.of(1, 0, 0, 0, 1, 0, 0, 0, 1);

function about(axis: string, angle: number): Mat3 {
  const c = Math.cos(angle);
  const s = Math.sin(angle);
  if (axis === 'x') return Float64Array.of(1, 0, 0, 0, c, -s, 0, s, c);
  if (axis === 'y') return Float64Array.of(c, 0, s, 0, 1, 0, -s, 0, c);
  return Float64Array.of(c, -s, 0, s, c, 0, 0, 0, 1);
}

/** The rotation for angles paired with the letters of `order`, applied first to last about the fixed
 *  axes (so "xyz" is Rz Ry Rx), as scipy's lowercase from_euler. */
export function euler(values: ArrayLike<number>, order: string, degrees: boolean): Mat3 {
  let r = IDENTITY;
  const k = degrees ? Math.PI / 180 : 1;
  for (let i = 0; i < order.length; i++) r = matmul(about(order[i].toLowerCase(), values[i] * k), r);
  return r;
}

function axisMatrix(xyz: number[], orderText: string, degrees: boolean, where: string, n: number): Mat3 {
  const order = orderText.toUpperCase();
  if ([...order].sort().join(',') !== 'X,Y,Z') throw fail(where, n, `axis order "${order}" must be a permutation of XYZ`);
  // The three angles are about x, y and z; the order string says which turn comes first.
  return euler([...order].map((c) => xyz['XYZ'.indexOf(c)]), order, degrees);
}

function tooLarge(text: string, where: string): void {
  if (text.length > MAX_BYTES) {
    throw new MotionImportError(`${where}: ${(text.length / 2 ** 20).toFixed(0)} MB is larger than this page reads (${MAX_BYTES / 2 ** 20} MB); cut the take shorter`, 'too-large');
  }
}

interface BoneBlock {
  line: number;
  name?: string;
  direction?: [number[], number];
  length?: number;
  axis?: [number[], string, number];
  dof?: string[];
}

/** Parse ASF text; throws MotionImportError('not-asf-amc') naming `where`, the line and the problem. */
export function parseAsf(text: string, where = 'ASF'): Asf {
  tooLarge(text, where);
  const lines: [number, string][] = [];
  text.replace(/^\ufeff/, '').split(LINES).forEach((raw, i) => {
    const hash = raw.indexOf('#');
    const s = strip(hash >= 0 ? raw.slice(0, hash) : raw);
    if (s) lines.push([i + 1, s]);
  });
  if (!lines.length || !lines[0][1].startsWith(':')) {
    throw bad(`${where}: not an ASF file (it must start with a keyword such as ":version")`);
  }
  let lengthUnit = 1;
  let degrees = true;
  const root: { order?: string[]; axis?: [string, number]; position?: number[]; orientation?: number[] } = {};
  const bones: BoneBlock[] = [];
  const hierarchy: [number, string, string[]][] = [];
  let section = '';
  let block: BoneBlock | null = null;
  for (const [n, s] of lines) {
    const tokens = tokenize(s);
    if (s.startsWith(':')) {
      if (block !== null) throw fail(where, n, `bone block opened at line ${block.line} has no "end"`);
      section = tokens[0].toLowerCase();
      if (section === ':version' || section === ':name') section = ''; // one-line values we do not need
      continue;
    }
    const key = tokens[0].toLowerCase();
    if (section === ':units') {
      if (key === 'length') {
        lengthUnit = numbers(tokens.slice(1), 1, where, n, 'length')[0];
        if (!(lengthUnit > 0)) throw fail(where, n, 'the length unit must be positive');
      } else if (key === 'angle') {
        if (tokens.length !== 2 || !['deg', 'rad'].includes(tokens[1].toLowerCase())) throw fail(where, n, 'expected "angle deg" or "angle rad"');
        degrees = tokens[1].toLowerCase() === 'deg';
      }
    } else if (section === ':root') {
      if (key === 'order') {
        const order = tokens.slice(1).map((t) => t.toLowerCase());
        if (order.some((t) => !ROOT_DOFS.includes(t)) || new Set(order).size !== order.length) {
          throw fail(where, n, `root order "${cut(tokens.slice(1).join(' '), 40)}" must list distinct TX TY TZ RX RY RZ`);
        }
        root.order = order;
      } else if (key === 'axis') {
        if (tokens.length !== 2) throw fail(where, n, 'expected "axis XYZ" (the root rotation order)');
        root.axis = [tokens[1], n];
      } else if (key === 'position' || key === 'orientation') {
        root[key] = numbers(tokens.slice(1), 3, where, n, key);
      } else {
        throw fail(where, n, `unknown root field "${cut(tokens[0], 20)}" (expected order, axis, position, orientation)`);
      }
    } else if (section === ':bonedata') {
      if (key === 'begin') {
        if (block !== null) throw fail(where, n, `"begin" inside the bone block opened at line ${block.line} (missing "end"?)`);
        block = { line: n };
      } else if (key === 'end') {
        if (block === null) throw fail(where, n, '"end" without a "begin"');
        bones.push(block);
        block = null;
        if (bones.length > MAX_BONES) throw fail(where, n, `more than ${MAX_BONES} bones: not a body skeleton`);
      } else if (block === null) {
        throw fail(where, n, `expected "begin" of a bone, found "${cut(s, 40)}"`);
      } else if (key === 'name') {
        if (tokens.length !== 2) throw fail(where, n, 'expected "name bonename"');
        block.name = tokens[1];
      } else if (key === 'direction') {
        block.direction = [numbers(tokens.slice(1), 3, where, n, 'direction'), n];
      } else if (key === 'length') {
        block.length = numbers(tokens.slice(1), 1, where, n, 'length')[0];
      } else if (key === 'axis') {
        if (tokens.length !== 5) throw fail(where, n, 'expected "axis ax ay az XYZ" (three angles and their order)');
        block.axis = [numbers(tokens.slice(1, 4), 3, where, n, 'axis'), tokens[4], n];
      } else if (key === 'dof') {
        const dof = tokens.slice(1).map((t) => t.toLowerCase());
        const wrong = dof.filter((t) => !ROTATIONS.includes(t));
        if (wrong.length) {
          throw fail(where, n, `dof "${cut(wrong[0], 10)}" is not supported (only rx ry rz: CMU bones rotate, they do not stretch or slide)`);
        }
        if (new Set(dof).size !== dof.length) throw fail(where, n, 'a dof is listed twice');
        block.dof = dof;
      } else if (['id', 'bodymass', 'cofmass', 'limits'].includes(key) || s.startsWith('(')) {
        // not needed for positions
      } else {
        throw fail(where, n, `unknown bone field "${cut(tokens[0], 20)}"`);
      }
    } else if (section === ':hierarchy') {
      if (key === 'begin' || key === 'end') continue;
      hierarchy.push([n, tokens[0], tokens.slice(1)]);
    }
  }
  if (block !== null) throw bad(`${where}: the bone block opened at line ${(block as BoneBlock).line} has no "end" (truncated?)`);
  if (!bones.length) throw bad(`${where}: no :bonedata (an ASF lists its bones there)`);
  if (!hierarchy.length) throw bad(`${where}: no :hierarchy (an ASF says there which bone hangs from which)`);

  const names: string[] = [];
  const index = new Map<string, number>();
  for (const b of bones) {
    for (const field of ['name', 'direction', 'length', 'axis'] as const) {
      if (b[field] === undefined) throw fail(where, b.line, `the bone block has no "${field}"`);
    }
    const name = b.name!;
    if (index.has(name) || name.toLowerCase() === 'root') throw fail(where, b.line, `bone name "${name}" appears twice (or is "root")`);
    index.set(name, names.length);
    names.push(name);
  }

  const parents = new Map<string, string>();
  for (const [n, parent, children] of hierarchy) {
    if (parent !== 'root' && !index.has(parent)) throw fail(where, n, `hierarchy names "${cut(parent, 30)}", which is not a bone in :bonedata`);
    for (const c of children) {
      if (!index.has(c)) throw fail(where, n, `hierarchy names "${cut(c, 30)}", which is not a bone in :bonedata`);
      if (parents.has(c)) throw fail(where, n, `bone "${c}" has two parents (${parents.get(c)} and ${parent})`);
      parents.set(c, parent);
    }
  }
  const orphan = names.find((nm) => !parents.has(nm));
  if (orphan !== undefined) throw bad(`${where}: bone "${orphan}" is not in :hierarchy (every bone needs a parent)`);
  // A parent cycle would never reach the root.
  for (const nm of names) {
    const seen = new Set<string>();
    let p = nm;
    while (p !== 'root') {
      if (seen.has(p)) throw bad(`${where}: :hierarchy has a cycle through "${p}"`);
      seen.add(p);
      p = parents.get(p)!;
    }
  }

  const out: AsfBone[] = bones.map((b) => {
    const [d, dn] = b.direction!;
    const norm = Math.sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (!(norm > 0)) throw fail(where, dn, `bone "${b.name}" has a zero direction`);
    const [xyz, order, an] = b.axis!;
    const parent = parents.get(b.name!)!;
    return {
      name: b.name!, direction: [d[0] / norm, d[1] / norm, d[2] / norm], length: b.length!,
      axis: axisMatrix(xyz, order, degrees, where, an), dof: b.dof ?? [], parent: parent === 'root' ? -1 : index.get(parent)!,
    };
  });
  const [axis, an] = root.axis ?? ['XYZ', lines[0][0]];
  const position = root.position ?? [0, 0, 0];
  return {
    bones: out, rootOrder: root.order ?? [...ROOT_DOFS], rootAxis: axisMatrix(root.orientation ?? [0, 0, 0], axis, degrees, where, an),
    rootPosition: [position[0], position[1], position[2]], metres: INCH / lengthUnit, degrees, names: ['root', ...names],
  };
}

/** Dofs per AMC line name: the root, then each bone with dofs, in file order. */
function dofsOf(asf: Asf): Map<string, number> {
  const out = new Map<string, number>([['root', asf.rootOrder.length]]);
  for (const b of asf.bones) if (b.dof.length) out.set(b.name, b.dof.length);
  return out;
}

/** Parse AMC text for the skeleton `asf`; throws MotionImportError naming `where`, the line and the problem. */
export function parseAmc(text: string, asf: Asf, where = 'AMC'): Amc {
  tooLarge(text, where);
  const lines = text.replace(/^\ufeff/, '').split(LINES);
  let degrees = asf.degrees;
  let i = 0;
  for (; i < lines.length; i++) {
    const s = strip(lines[i]);
    if (!s || s.startsWith('#')) continue;
    if (!s.startsWith(':')) break;
    const key = tokenize(s)[0].toUpperCase();
    if (key === ':DEGREES' || key === ':RADIANS') degrees = key === ':DEGREES';
    else if (key !== ':FULLY-SPECIFIED') throw fail(where, i + 1, `unknown keyword "${cut(s, 40)}" (expected :FULLY-SPECIFIED, :DEGREES or :RADIANS)`);
  }
  let end = lines.length;
  while (end > i && !strip(lines[end - 1])) end--;
  const noFrames = () => new MotionImportError(`${where}: no frames (a frame is its number on its own line, then one line per bone)`, 'too-few-frames');
  if (end <= i) throw noFrames();

  // Line by line, as export/data/asf_amc.py's _slow_body (its faster column reader gives the same
  // values whenever it applies): any bone order per frame, blank lines; the first problem is named.
  const dofs = dofsOf(asf);
  const rows = new Map<string, number[]>([...dofs.keys()].map((name) => [name, []]));
  let first: bigint | null = null;
  let last = 0n;
  let frames = 0;
  let frameLine = 0;
  let seen = new Set<string>();
  const close = (n: number) => {
    const missing = [...dofs.keys()].filter((name) => !seen.has(name));
    if (missing.length) {
      throw fail(where, n, `frame ${last} (line ${frameLine}) has no values for ${missing.slice(0, 3).join(', ')}${missing.length > 3 ? ' ...' : ''} `
        + '(a fully specified AMC gives every bone with dofs in every frame)');
    }
  };
  for (let k = i; k < end; k++) {
    const n = k + 1;
    const s = strip(lines[k]);
    if (!s) continue;
    if (FRAME.test(s)) {
      const number = BigInt(s);
      if (frames) {
        close(n);
        if (number !== last + 1n) throw fail(where, n, `frame ${s} follows frame ${last} (frames must count up by one)`);
      }
      if (frames >= MAX_SOURCE_FRAMES) {
        throw new MotionImportError(`${where}: line ${n}: more frames than this reader takes (${MAX_SOURCE_FRAMES}); cut the take shorter`, 'too-large');
      }
      if (first === null) first = number;
      last = number;
      frames += 1;
      frameLine = n;
      seen = new Set();
      continue;
    }
    const tokens = tokenize(s);
    const name = tokens[0];
    if (!frames) throw fail(where, n, `"${cut(s, 40)}" comes before the first frame number`);
    const count = dofs.get(name);
    if (count === undefined) {
      const hint = NUMBER.test(name) ? ` (frame numbers are whole numbers, found "${cut(name, 20)}")` : '';
      throw fail(where, n, `"${cut(name, 30)}" is not a bone with dofs in the ASF${hint}`);
    }
    if (seen.has(name)) throw fail(where, n, `bone "${name}" appears twice in frame ${last}`);
    seen.add(name);
    const values = numbers(tokens.slice(1), count, where, n, name !== 'root' ? `bone "${name}"` : 'the root');
    const row = rows.get(name)!;
    for (const v of values) row.push(v);
  }
  if (!frames) throw noFrames();
  close(end);
  return { first: first!, frames, values: new Map([...rows].map(([name, r]) => [name, Float64Array.from(r)])), degrees };
}

/** World positions of the root and each bone's end (`asf.names`), metres, `frameTime` seconds apart. */
export function asfAmcPoints(asf: Asf, amc: Amc, frameTime: number): SourcePoints {
  const F = amc.frames;
  const B = asf.bones.length;
  const N = 1 + B;
  const points = new Float64Array(F * N * 3);
  const root = amc.values.get('root')!;
  const R = asf.rootOrder.length;
  const rotCols = asf.rootOrder.map((d, k) => (ROTATIONS.includes(d) ? k : -1)).filter((k) => k >= 0);
  const rootLetters = rotCols.map((k) => asf.rootOrder[k][1]).join('');
  const rootAxisT = transpose(asf.rootAxis);
  // parents first: :bonedata may list a child before its parent
  const order: number[] = [];
  const placed = new Array<boolean>(B).fill(false);
  while (order.length < B) {
    for (let j = 0; j < B; j++) {
      const p = asf.bones[j].parent;
      if (!placed[j] && (p < 0 || placed[p])) { order.push(j); placed[j] = true; }
    }
  }
  const local = asf.bones.map((b) => ({
    axisT: transpose(b.axis), letters: b.dof.map((d) => d[1]).join(''), values: b.dof.length ? amc.values.get(b.name)! : null,
    offset: b.direction.map((c) => c * b.length),
  }));
  const world: Mat3[] = new Array(B);
  const pos = [0, 0, 0];
  for (let f = 0; f < F; f++) {
    pos[0] = asf.rootPosition[0]; pos[1] = asf.rootPosition[1]; pos[2] = asf.rootPosition[2];
    asf.rootOrder.forEach((d, k) => { if (d[0] === 't') pos['xyz'.indexOf(d[1])] += root[f * R + k]; });
    const worldRoot = rotCols.length
      ? matmul(matmul(asf.rootAxis, euler(rotCols.map((k) => root[f * R + k]), rootLetters, amc.degrees)), rootAxisT)
      : IDENTITY;
    const o = f * N * 3;
    points[o] = pos[0]; points[o + 1] = pos[1]; points[o + 2] = pos[2];
    for (const j of order) {
      const bone = asf.bones[j];
      const l = local[j];
      const parentRot = bone.parent < 0 ? worldRoot : world[bone.parent];
      const s = o + (bone.parent < 0 ? 0 : 1 + bone.parent) * 3;
      let rot = parentRot;
      if (l.values) {
        const D = bone.dof.length;
        rot = matmul(parentRot, matmul(matmul(bone.axis, euler(l.values.subarray(f * D, f * D + D), l.letters, amc.degrees)), l.axisT));
      }
      world[j] = rot;
      const [x, y, z] = l.offset;
      const e = o + (1 + j) * 3;
      points[e] = points[s] + (rot[0] * x + rot[1] * y + rot[2] * z);
      points[e + 1] = points[s + 1] + (rot[3] * x + rot[4] * y + rot[5] * z);
      points[e + 2] = points[s + 2] + (rot[6] * x + rot[7] * y + rot[8] * z);
    }
  }
  for (let k = 0; k < points.length; k++) points[k] *= asf.metres;
  return { names: asf.names, frames: F, frameTime, points };
}

/** Parse both texts and run forward kinematics: the source points in metres, `fps` frames a second. */
export function asfAmcSource(asfText: string, amcText: string, asfFile: string, amcFile: string, fps = CMU_FPS): SourcePoints {
  const asf = parseAsf(asfText, asfFile);
  return asfAmcPoints(asf, parseAmc(amcText, asf, amcFile), 1 / fps);
}

export interface AsfAmcOptions extends ImportOptions {
  /** Frames per second of the AMC. The file does not state it; CMU's takes are 120 Hz (the default). */
  fps?: number;
}

/** An ASF + AMC pair -> ImportedMotion at 30 Hz on the project skeleton (cmu-asf joint map, or the
 *  user's override on top of it); throws MotionImportError only. `origin.file` is the AMC. */
export function importAsfAmc(asfText: string, amcText: string, asfFile: string, amcFile: string, options: AsfAmcOptions): ImportedMotion {
  const skeleton: Skeleton = options.skeleton;
  let maps: JointMap[];
  try {
    maps = ASF_AMC_MAPS.map((base) => loadJointMap(base, skeleton.joints, options.jointMap, options.jointMapName ?? 'joint map'));
  } catch (err) {
    throw new MotionImportError((err as Error).message, 'bad-joint-map');
  }
  // The AMC has no frame rate of its own: the caller's, else CMU's 120 Hz.
  const fps = options.fps ?? CMU_FPS;
  if (!(Number.isFinite(fps) && fps > 0)) {
    throw new MotionImportError(`${amcFile}: the frame rate must be a positive number of frames per second, got ${fps}`, 'bad-values');
  }
  const src = asfAmcSource(asfText, amcText, asfFile, amcFile, fps);
  let out;
  let map: JointMap;
  const warnings: string[] = [];
  try {
    map = pickMap(maps, src.names, skeleton.joints, amcFile);
    for (const w of [skeletonWarning(asfFile, amcFile), plausibilityWarning(src, map, skeleton.joints, amcFile)]) if (w) warnings.push(w);
    out = retarget(src, map, skeleton, amcFile, options.minFrames ?? MIN_FRAMES);
  } catch (err) {
    if (err instanceof RetargetError) throw new MotionImportError(err.message, err.kind);
    throw err;
  }
  const positions = Float32Array.from(out.positions);
  for (let i = 0; i < positions.length; i++) {
    if (!Number.isFinite(positions[i])) throw new MotionImportError(`${amcFile}: the retargeted motion has non-finite values`, 'bad-values');
  }
  return {
    name: motionName(amcFile), action: 'unlabelled', fps: 30, skeleton: { joints: skeleton.joints, parents: skeleton.parents },
    frames: out.frames, joints: skeleton.joints.length, positions, loops: false, role: 'test', train: [],
    test: [[0, out.frames]], origin: {
      kind: 'dropped-file', file: amcFile, format: 'asf-amc', sourceFrames: src.frames, sourceFps: fps,
      jointMap: map.name, groundTruth: false, warnings,
    },
  };
}

/** CMU names a take <subject>_<take>.amc and its skeleton <subject>.asf: an AMC moved by another
 *  subject's ASF (01.asf + 05_07.amc) gets that subject's bone lengths and joint axes, which do not fit
 *  the motion, and nothing in the motion itself shows it reliably. null when the names agree or either is
 *  not named that way. Twin of export/data/sources.py skeleton_warning. */
export function skeletonWarning(asfFile: string, amcFile: string): string | null {
  const stem = (f: string) => f.replace(/^.*[\\/]/, '').replace(/\.[^.]*$/, '');
  const take = stem(amcFile);
  const subject = take.includes('_') ? take.split('_')[0].trim().toLowerCase() : '';
  const other = stem(asfFile).trim().toLowerCase();
  if (!/^[0-9]+$/.test(subject) || !/^[0-9]+$/.test(other) || Number(subject) === Number(other)) return null;
  const asfName = asfFile.replace(/^.*[\\/]/, '');
  return `${amcFile}: moved by ${asfName}, the skeleton of subject ${other}, but the take's name says subject ${subject}: `
    + `another subject's bone lengths and joint axes do not fit the motion (feet under the floor); use ${subject}.asf`;
}
