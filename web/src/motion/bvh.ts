// A dropped BVH file -> a Motion on the project skeleton, or a MotionImportError naming the problem.
// The text is checked against the same line grammar as export/data/bvh.py first (BVHLoader itself
// only logs to the console and throws TypeErrors on bad input), then read with three.js's
// BVHLoader, put through forward kinematics, and retargeted (retarget.ts) with a joint map.
// Position channels on a non-root joint replace its OFFSET (export/data/bvh.py says why); BVHLoader
// adds the two, so bvhPoints takes the OFFSET back out of those axes.
import { BVHLoader } from 'three/examples/jsm/loaders/BVHLoader.js';
import type { Bone, QuaternionKeyframeTrack, VectorKeyframeTrack } from 'three';
import type { Skeleton } from '../contract/types';
import type { Motion } from './clip';
import { BVH_MAPS, JointMapError, loadJointMap, type JointMap } from './joint-map';
import { MIN_FRAMES, pickMap, plausibilityWarning, RetargetError, retarget, type SourcePoints } from './retarget';

// The same limits as export/data/bvh.py: a hostile or accidental file must not exhaust the tab.
export const MAX_JOINTS = 1000;
export const MAX_DEPTH = 200;
export const MAX_SOURCE_FRAMES = 100_000;
export const MAX_BYTES = 64 * 1024 * 1024;
const CHANNELS = ['Xposition', 'Yposition', 'Zposition', 'Xrotation', 'Yrotation', 'Zrotation'];
const NUMBER = /^[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?$/;
const WS = /[ \t\f\v]+/;
const CHUNK = 2000;

export type ImportProblem = 'not-bvh' | 'not-asf-amc' | 'too-large' | 'unknown-skeleton' | 'too-few-frames' | 'bad-joint-map' | 'bad-values';

/** Every way a file can fail to import; `message` names the file and the problem. */
export class MotionImportError extends Error {
  constructor(message: string, readonly problem: ImportProblem) {
    super(message);
    this.name = 'MotionImportError';
  }
}

/** What the grammar check learns: joint names (End Sites as "<joint>/end") and the motion size. */
export interface BvhOutline {
  names: string[];
  parents: number[];
  /** True for End Sites (no channels). */
  endSite: boolean[];
  /** Each joint's channel names in file order ([] for End Sites). */
  jointChannels: string[][];
  channels: number;
  frames: number;
  frameTime: number;
  /** The HIERARCHY section's lines and the frame lines, trimmed, for reading in chunks. */
  hierarchy: string[];
  rows: string[];
}

const trimWs = (s: string) => s.replace(/^[ \t\f\v]+|[ \t\f\v]+$/g, '');
const split = (s: string) => s.split(WS).filter((t) => t.length > 0);

/** Check BVH text against the grammar export/data/bvh.py reads; throws MotionImportError('not-bvh'). */
export function checkBvh(text: string, where: string): BvhOutline {
  if (text.length > MAX_BYTES) {
    throw new MotionImportError(`${where}: ${(text.length / 2 ** 20).toFixed(0)} MB is larger than this page reads (${MAX_BYTES / 2 ** 20} MB); cut the take shorter`, 'too-large');
  }
  const raw = text.replace(/^\ufeff/, '').split(/\r\n|\r|\n/);
  const lines: [number, string][] = [];
  raw.forEach((s, i) => { const t = trimWs(s); if (t) lines.push([i + 1, t]); });
  let pos = 0;
  const fail = (line: number, why: string) => new MotionImportError(`${where}: line ${line}: ${why}`, 'not-bvh');
  const next = (expecting: string): [number, string] => {
    if (pos >= lines.length) throw new MotionImportError(`${where}: the file ends where ${expecting} was expected (truncated?)`, 'not-bvh');
    return lines[pos++];
  };
  if (!lines.length || lines[0][1] !== 'HIERARCHY') {
    throw new MotionImportError(`${where}: not a BVH file (it must start with a line "HIERARCHY")`, 'not-bvh');
  }
  pos = 1;
  const names: string[] = [];
  const parents: number[] = [];
  const endSites: boolean[] = [];
  const jointChannels: string[][] = [];
  let channels = 0;
  const short = (s: string) => s.slice(0, 40);

  // An explicit stack instead of recursion, so depth is bounded by MAX_DEPTH, not by the JS stack.
  type Frame = { index: number; depth: number };
  const stack: Frame[] = [];
  const openNode = (header: [number, string], parent: number, depth: number): void => {
    const [n, t] = header;
    const tokens = split(t);
    const endSite = tokens.length >= 2 && tokens[0].toUpperCase() === 'END' && tokens[1].toUpperCase() === 'SITE';
    let name: string;
    if (endSite) {
      if (parent < 0) throw fail(n, 'End Site cannot be the root');
      const base = `${names[parent]}/end`;
      name = base;
      for (let k = 2; names.includes(name); k++) name = `${base}${k}`;
    } else {
      const kind = tokens.length ? tokens[0].toUpperCase() : '';
      if ((kind !== 'ROOT' && kind !== 'JOINT') || tokens.length < 2) {
        throw fail(n, `expected "JOINT name", "End Site" or "}", found "${short(t)}"`);
      }
      if ((kind === 'ROOT') !== (parent < 0)) {
        throw fail(n, parent >= 0 ? 'only the first joint is a ROOT (one skeleton per file)' : `the hierarchy must start with "ROOT name", found "${short(t)}"`);
      }
      name = tokens[1];
      if (names.includes(name)) throw fail(n, `joint name "${name}" appears twice`);
    }
    if (depth > MAX_DEPTH || names.length >= MAX_JOINTS) {
      throw fail(n, `more than ${MAX_JOINTS} joints or ${MAX_DEPTH} levels: not a body skeleton`);
    }
    const index = names.length;
    names.push(name);
    parents.push(parent);
    endSites.push(endSite);
    jointChannels.push([]);
    let [m, s] = next('"{"');
    if (s !== '{') throw fail(m, `expected "{" on its own line after "${short(t)}"`);
    [m, s] = next('OFFSET');
    const off = split(s);
    if (off[0] !== 'OFFSET' || off.length !== 4 || !off.slice(1).every((v) => NUMBER.test(v))) {
      throw fail(m, `expected "OFFSET x y z" (three numbers), found "${short(s)}"`);
    }
    if (endSite) {
      [m, s] = next('"}"');
      if (s !== '}') throw fail(m, 'an End Site holds only its OFFSET; expected "}"');
      return;
    }
    [m, s] = next('CHANNELS');
    const ch = split(s);
    if (ch[0] !== 'CHANNELS' || ch.length < 2 || !/^[0-9]+$/.test(ch[1])) throw fail(m, `expected "CHANNELS n names...", found "${short(s)}"`);
    const list = ch.slice(2);
    if (Number(ch[1]) !== list.length) throw fail(m, `CHANNELS says ${ch[1]} but lists ${list.length} names`);
    const bad = list.find((c) => !CHANNELS.includes(c));
    if (bad !== undefined) throw fail(m, `unknown channel "${bad}" (expected ${CHANNELS.join(', ')})`);
    channels += list.length;
    jointChannels[index] = list;
    stack.push({ index, depth });
  };
  openNode(next('"ROOT name"'), -1, 0);
  while (stack.length) {
    const top = stack[stack.length - 1];
    const child = next('"}"');
    if (child[1] === '}') stack.pop();
    else openNode(child, top.index, top.depth + 1);
  }

  const motionAt = pos;
  let [n, t] = next('"MOTION"');
  if (t !== 'MOTION') throw fail(n, `expected "MOTION" after the hierarchy, found "${short(t)}"`);
  [n, t] = next('"Frames: n"');
  let tokens = split(t);
  if (tokens.length !== 2 || tokens[0] !== 'Frames:' || !/^[0-9]+$/.test(tokens[1])) throw fail(n, `expected "Frames: n", found "${short(t)}"`);
  const frames = Number(tokens[1]);
  if (frames > MAX_SOURCE_FRAMES) {
    throw new MotionImportError(`${where}: line ${n}: ${frames} frames is more than this reader takes (${MAX_SOURCE_FRAMES}); cut the take shorter`, 'too-large');
  }
  [n, t] = next('"Frame Time: seconds"');
  tokens = split(t);
  if (tokens.length !== 3 || tokens[0] !== 'Frame' || tokens[1] !== 'Time:' || !NUMBER.test(tokens[2])) {
    throw fail(n, `expected "Frame Time: seconds", found "${short(t)}"`);
  }
  const frameTime = Number(tokens[2]);
  if (!(frameTime > 0)) throw fail(n, `Frame Time must be positive, found ${frameTime}`);
  const rows = lines.length - pos;
  if (rows !== frames) {
    throw new MotionImportError(`${where}: "Frames: ${frames}" but the file has ${rows} frame lines${rows < frames ? ' (truncated?)' : ''}`, 'not-bvh');
  }
  const firstRow = pos;
  for (; pos < lines.length; pos++) {
    const [line, s] = lines[pos];
    const values = split(s);
    if (values.length !== channels) throw fail(line, `a frame needs ${channels} numbers (one per channel), found ${values.length}`);
    for (const v of values) {
      if (!NUMBER.test(v) || !Number.isFinite(Number(v))) throw fail(line, `"${v.slice(0, 20)}" is not a finite number`);
    }
  }
  return {
    names, parents, endSite: endSites, jointChannels, channels, frames, frameTime,
    hierarchy: lines.slice(0, motionAt).map(([, l]) => l), rows: lines.slice(firstRow).map(([, l]) => l),
  };
}

/** Joint and End Site world positions of a checked BVH text, read with three.js's BVHLoader. */
export function bvhPoints(text: string, where: string): SourcePoints {
  const outline = checkBvh(text, where);
  if (outline.frames === 0) throw new MotionImportError(`${where}: too few frames: the file has none`, 'too-few-frames');
  // BVHLoader shifts lines off the front of an array, which is quadratic in the number of lines;
  // reading the motion in chunks of CHUNK frames keeps a long take linear.
  const N = outline.names.length;
  const F = outline.frames;
  const local: { pos: Float32Array | null; rot: Float32Array | null }[] = outline.names.map((_, j) =>
    (outline.endSite[j] ? { pos: null, rot: null } : { pos: new Float32Array(F * 3), rot: new Float32Array(F * 4) }));
  const head = outline.hierarchy.join('\n');
  let bones: Bone[] = [];
  for (let start = 0; start < F; start += CHUNK) {
    const rows = outline.rows.slice(start, start + CHUNK);
    let parsed: ReturnType<BVHLoader['parse']>;
    try {
      parsed = new BVHLoader().parse(`${head}\nMOTION\nFrames: ${rows.length}\nFrame Time: ${outline.frameTime}\n${rows.join('\n')}\n`);
    } catch (err) {
      // The grammar check passed, so this is a BVHLoader limit we did not foresee: still a named error.
      throw new MotionImportError(`${where}: three.js could not read this BVH (${(err as Error).message})`, 'not-bvh');
    }
    bones = parsed.skeleton.bones;
    if (bones.length !== N) throw new MotionImportError(`${where}: three.js read ${bones.length} joints, expected ${N}`, 'not-bvh');
    // Tracks come in bone order, a position and a quaternion track per joint; End Sites have none.
    const tracks = parsed.clip.tracks;
    let t = 0;
    for (let j = 0; j < N; j++) {
      const into = local[j];
      if (!into.pos || !into.rot) continue;
      if (bones[j].name !== outline.names[j] || t + 1 >= tracks.length) {
        throw new MotionImportError(`${where}: three.js read the joints differently (joint ${j}: "${bones[j].name}")`, 'not-bvh');
      }
      const pos = tracks[t++] as VectorKeyframeTrack;
      const rot = tracks[t++] as QuaternionKeyframeTrack;
      if (pos.values.length !== rows.length * 3 || rot.values.length !== rows.length * 4) {
        throw new MotionImportError(`${where}: three.js read ${pos.times.length} frames, expected ${rows.length}`, 'not-bvh');
      }
      into.pos.set(pos.values, start * 3);
      into.rot.set(rot.values, start * 4);
    }
  }
  const points = new Float64Array(F * N * 3);
  const world = new Float64Array(F * N * 4); // x, y, z, w
  for (let j = 0; j < N; j++) {
    const p = outline.parents[j];
    const { pos, rot } = local[j];
    const off = bones[j].position;
    // BVHLoader's position track is OFFSET + channel; on a non-root joint the channel alone is the position
    const own = outline.jointChannels[j];
    const [sx, sy, sz] = ['X', 'Y', 'Z'].map((a) => (p >= 0 && own.includes(`${a}position`) ? 1 : 0));
    for (let f = 0; f < F; f++) {
      const lx = pos ? pos[f * 3] - sx * off.x : off.x;
      const ly = pos ? pos[f * 3 + 1] - sy * off.y : off.y;
      const lz = pos ? pos[f * 3 + 2] - sz * off.z : off.z;
      const qx = rot ? rot[f * 4] : 0;
      const qy = rot ? rot[f * 4 + 1] : 0;
      const qz = rot ? rot[f * 4 + 2] : 0;
      const qw = rot ? rot[f * 4 + 3] : 1;
      const o = (f * N + j) * 3;
      const w = (f * N + j) * 4;
      if (p < 0) {
        points[o] = lx; points[o + 1] = ly; points[o + 2] = lz;
        world[w] = qx; world[w + 1] = qy; world[w + 2] = qz; world[w + 3] = qw;
        continue;
      }
      const po = (f * N + p) * 3;
      const pw = (f * N + p) * 4;
      const ax = world[pw]; const ay = world[pw + 1]; const az = world[pw + 2]; const aw = world[pw + 3];
      // v' = v + 2 w (a x v) + 2 a x (a x v), a = (ax, ay, az): the parent's world rotation applied to v
      const cx = ay * lz - az * ly; const cy = az * lx - ax * lz; const cz = ax * ly - ay * lx;
      points[o] = points[po] + lx + 2 * (aw * cx + ay * cz - az * cy);
      points[o + 1] = points[po + 1] + ly + 2 * (aw * cy + az * cx - ax * cz);
      points[o + 2] = points[po + 2] + lz + 2 * (aw * cz + ax * cy - ay * cx);
      // world = parent * local
      world[w] = aw * qx + ax * qw + ay * qz - az * qy;
      world[w + 1] = aw * qy - ax * qz + ay * qw + az * qx;
      world[w + 2] = aw * qz + ax * qy - ay * qx + az * qw;
      world[w + 3] = aw * qw - ax * qx - ay * qy - az * qz;
    }
  }
  return { names: outline.names, frames: F, frameTime: outline.frameTime, points };
}

/** A Motion made from a dropped file: no split, no dataset; any window of it can be a history. */
export interface ImportedMotion extends Motion {
  origin: {
    kind: 'dropped-file';
    file: string;
    format: 'bvh' | 'asf-amc';
    sourceFrames: number;
    sourceFps: number;
    jointMap: string;
    /** The frames after a history are the file's own continuation, not a held-out test set. */
    groundTruth: false;
    /** Imported, but doubtful: each a sentence naming the problem and the fix (a wrong up axis, a body
     *  without a human build, another subject's ASF); empty when the file looks right. */
    warnings: string[];
  };
}

export interface ImportOptions {
  /** The project skeleton with offsets (the clip index's or manifest's). */
  skeleton: Skeleton;
  /** A user's joint map override (parsed JSON) on top of the built-in map (importBvh: each of BVH_MAPS in
   *  turn, cmu-bvh first; importAsfAmc: cmu-asf). */
  jointMap?: unknown;
  jointMapName?: string;
  minFrames?: number;
}

/** A contract clip name from a file name: "My Take 01.bvh" -> "my_take_01". */
export function motionName(file: string): string {
  const stem = file.replace(/^.*[\\/]/, '').replace(/\.[^.]*$/, '');
  return stem.toLowerCase().replace(/[^a-z0-9_.-]+/g, '_').replace(/^[_.-]+/, '') || 'dropped';
}

/** BVH text -> ImportedMotion at 30 Hz on the project skeleton; throws MotionImportError only. */
export function importBvh(text: string, file: string, options: ImportOptions): ImportedMotion {
  const { skeleton } = options;
  let maps: JointMap[];
  try {
    // each built-in BVH map with the user's override on top (an override that `extends` a map names its own base)
    maps = BVH_MAPS.map((base) => loadJointMap(base, skeleton.joints, options.jointMap, options.jointMapName ?? 'joint map'));
  } catch (err) {
    throw new MotionImportError((err as Error).message, 'bad-joint-map');
  }
  const src = bvhPoints(text, file);
  let out;
  let map: JointMap;
  let warning: string | null;
  try {
    // the first map whose joint names the file has; when none fits, the message names what the first
    // (cmu-bvh) lacks and every map tried
    map = pickMap(maps, src.names, skeleton.joints, file);
    warning = plausibilityWarning(src, map, skeleton.joints, file);
    out = retarget(src, map, skeleton, file, options.minFrames ?? MIN_FRAMES);
  } catch (err) {
    if (err instanceof RetargetError) throw new MotionImportError(err.message, err.kind);
    throw err;
  }
  const positions = Float32Array.from(out.positions);
  for (let i = 0; i < positions.length; i++) {
    if (!Number.isFinite(positions[i])) throw new MotionImportError(`${file}: the retargeted motion has non-finite values`, 'bad-values');
  }
  return {
    name: motionName(file), action: 'unlabelled', fps: 30, skeleton: { joints: skeleton.joints, parents: skeleton.parents },
    frames: out.frames, joints: skeleton.joints.length, positions, loops: false, role: 'test', train: [],
    test: [[0, out.frames]], origin: {
      kind: 'dropped-file', file, format: 'bvh', sourceFrames: src.frames, sourceFps: 1 / src.frameTime,
      jointMap: map.name, groundTruth: false, warnings: warning ? [warning] : [],
    },
  };
}

export { JointMapError };
