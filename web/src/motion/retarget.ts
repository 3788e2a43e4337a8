// Retargeting named source points onto the project skeleton. Twin of export/data/retarget.py,
// whose docstring (and docs/BRING_YOUR_OWN.md) describes the one method; contract/vectors/
// retarget.json ties the two. In short: joint map -> y-up -> linear resample to 30 Hz -> walk the
// project skeleton keeping source bone directions with project bone lengths -> ground.
import type { Skeleton } from '../contract/types';
import { putOnFloor } from './floor';
import type { JointMap } from './joint-map';

export const FPS = 30;
/** Fewer frames (1/3 s at 30 Hz) cannot be a history for any served model. */
export const MIN_FRAMES = 10;
export const MAX_FRAMES = 108_000; // one hour at 30 Hz
const LEGS = [['right_hip', 'right_knee', 'right_ankle'], ['left_hip', 'left_knee', 'left_ankle']];

export class RetargetError extends Error {
  constructor(message: string, readonly kind: 'unknown-skeleton' | 'too-few-frames' | 'too-large' | 'bad-values' = 'bad-values') {
    super(message);
    this.name = 'RetargetError';
  }
}

/** Source points: [frames, names.length, 3] in the source's units and axes, frameTime seconds apart. */
export interface SourcePoints {
  names: string[];
  frames: number;
  frameTime: number;
  points: Float64Array;
}

const key = (name: string) => name.slice(name.lastIndexOf(':') + 1).toLowerCase();

/** The served guide's section on joint maps (web/bring-your-own.html, a relative URL the panel links). */
export const GUIDE_MAPS = 'bring-your-own.html#joint-maps';

/** Per project joint the source indices whose mean it follows, or null (derived); and the project
 *  joints no alternative finds, each with what was tried. */
function findJoints(map: JointMap, names: readonly string[], projectJoints: readonly string[]): { out: (number[] | null)[]; missing: string[] } {
  const exact = new Map<string, number>();
  const loose = new Map<string, number>();
  names.forEach((n, i) => {
    if (!exact.has(n)) exact.set(n, i);
    if (!loose.has(key(n))) loose.set(key(n), i);
  });
  const find = (n: string) => exact.get(n) ?? loose.get(key(n));
  const missing: string[] = [];
  const out = projectJoints.map((joint) => {
    for (const alt of map.joints[joint]) {
      if (alt === null) return null;
      const idx = alt.split('+').map(find);
      if (idx.every((i) => i !== undefined)) return idx as number[];
    }
    missing.push(`${joint} (tried ${map.joints[joint].filter((a) => a).join(', ')})`);
    return null;
  });
  return { out, missing };
}

function unknownSkeleton(map: JointMap, missing: string[], names: readonly string[], where: string, also = ''): RetargetError {
  // every joint of the file, however many: a visitor needs the spine, arm and head names to write a map
  const shown = names.filter((n) => !n.includes('/end')).join(', ');
  return new RetargetError(`${where}: unknown skeleton for joint map ${map.name}: no source joint for ${missing.join('; ')}.${also} `
    + `The file's joints are: ${shown}. Give a joint map (${GUIDE_MAPS})`, 'unknown-skeleton');
}

/** Per project joint: the source indices whose mean it follows, or null (derived). */
export function resolveJoints(map: JointMap, names: readonly string[], projectJoints: readonly string[], where: string): (number[] | null)[] {
  const { out, missing } = findJoints(map, names, projectJoints);
  if (missing.length) throw unknownSkeleton(map, missing, names, where);
  return out;
}

/** The first of `maps` whose joint names the file has (the order of joint-map.ts BVH_MAPS); when none
 *  fits, a RetargetError naming what the first lacks and every map tried. Twin of retarget.py pick_map. */
export function pickMap(maps: readonly JointMap[], names: readonly string[], projectJoints: readonly string[], where: string): JointMap {
  const misses: string[][] = [];
  for (const map of maps) {
    const { missing } = findJoints(map, names, projectJoints);
    if (!missing.length) return map;
    misses.push(missing);
  }
  let also = maps.slice(1).map((m, i) => ` Also tried joint map ${m.name}: no source joint for ${misses[i + 1].map((x) => x.split(' (')[0]).join(', ')}.`).join('');
  if (maps.length > 1) also += ` Tried in this order: ${maps.map((m) => m.name).join(', ')}.`;
  throw unknownSkeleton(maps[0], misses[0], names, where, also);
}

export const SPAN_ROUNDING = 1e-4;
export const SPAN_ROUNDING_MAX = 0.1;

/** The source's duration in output frames, rounded up to a whole frame when the Frame Time's rounding
 *  alone keeps it short of one (138 frames at "0.0333333" span 136.99986 frames at 30 Hz: 137, so 138
 *  frames come out): within SPAN_ROUNDING of the duration, never more than SPAN_ROUNDING_MAX of a frame.
 *  Twin of retarget.py _span. */
export function span(frames: number, frameTime: number, outFps: number): number {
  const x = (frames - 1) * frameTime * outFps;
  const up = Math.ceil(x);
  return up - x <= Math.max(1e-9, Math.min(SPAN_ROUNDING * x, SPAN_ROUNDING_MAX)) ? up : x;
}

/** Linear interpolation in time to `outFps` over the source's duration (same arithmetic as Python). */
export function resamplePoints(src: Float64Array, frames: number, width: number, frameTime: number, outFps = FPS): { points: Float64Array; frames: number } {
  if (frames === 1) return { points: src.slice(0, width), frames: 1 };
  const n = Math.floor(span(frames, frameTime, outFps)) + 1;
  const out = new Float64Array(n * width);
  for (let k = 0; k < n; k++) {
    // a last frame that the rounded Frame Time puts past the end (by more than float rounding) is the last frame
    let u = (k / outFps) / frameTime;
    if (u > frames - 1 + 1e-9) u = frames - 1;
    const i = Math.min(Math.floor(u), frames - 2);
    const w = u - i;
    const a = i * width;
    const b = (i + 1) * width;
    for (let c = 0; c < width; c++) out[k * width + c] = src[a + c] * (1 - w) + src[b + c] * w;
  }
  return { points: out, frames: n };
}

export const LEADING_STEPS = 10;
export const LEADING_LEGS = 0.05;
export const LEADING_MAX = 3;

function median(values: number[]): number {
  const v = [...values].sort((a, b) => a - b);
  const m = v.length >> 1;
  return v.length % 2 ? v[m] : (v[m - 1] + v[m]) / 2;
}

/** How many leading source frames are far from the rest of the take (a T-pose put first), twin of
 *  retarget.py's leading_outliers: frame 0 goes while its step (mean over the mapped points) is more
 *  than LEADING_STEPS times the median step and more than LEADING_LEGS leg lengths, at most LEADING_MAX. */
export function leadingOutliers(pts: Float64Array, frames: number, n: number, sources: (number[] | null)[], joints: string[]): number {
  const used = [...new Set(sources.flatMap((s) => s ?? []))].sort((a, b) => a - b);
  if (frames < 3 || used.length === 0) return 0;
  const steps: number[] = [];
  for (let f = 0; f + 1 < frames; f++) {
    let s = 0;
    for (const i of used) {
      const a = (f * n + i) * 3;
      const b = ((f + 1) * n + i) * 3;
      s += Math.hypot(pts[b] - pts[a], pts[b + 1] - pts[a + 1], pts[b + 2] - pts[a + 2]);
    }
    steps.push(s / used.length);
  }
  const mean = (idx: number[], f: number, c: number) => idx.reduce((t, i) => t + pts[(f * n + i) * 3 + c], 0) / idx.length;
  const legsPerFrame: number[] = [];
  for (let f = 0; f < frames; f++) {
    let total = 0;
    for (const [h, k, a] of LEGS) {
      const [qh, qk, qa] = [sources[joints.indexOf(h)]!, sources[joints.indexOf(k)]!, sources[joints.indexOf(a)]!];
      const p = (idx: number[]) => [0, 1, 2].map((c) => mean(idx, f, c));
      const [ph, pk, pa] = [p(qh), p(qk), p(qa)];
      total += Math.hypot(ph[0] - pk[0], ph[1] - pk[1], ph[2] - pk[2]) + Math.hypot(pk[0] - pa[0], pk[1] - pa[1], pk[2] - pa[2]);
    }
    legsPerFrame.push(total / LEGS.length);
  }
  const leg = median(legsPerFrame);
  let drop = 0;
  while (drop < LEADING_MAX && steps.length - drop > 2) {
    if (!(steps[drop] > LEADING_STEPS * median(steps.slice(drop)) && steps[drop] > LEADING_LEGS * leg)) break;
    drop += 1;
  }
  return drop;
}

/** Source points -> project positions [frames, joints, 3] at 30 Hz, float64. */
export function retarget(
  src: SourcePoints, map: JointMap, skeleton: Skeleton, where: string, minFrames = MIN_FRAMES,
): { positions: Float64Array; frames: number } {
  const { names, frameTime } = src;
  const n = names.length;
  if (src.points.length !== src.frames * n * 3) {
    throw new RetargetError(`${where}: expected points [frames, ${n}, 3], got ${src.points.length} numbers for ${src.frames} frames`);
  }
  for (let i = 0; i < src.points.length; i++) {
    if (!Number.isFinite(src.points[i])) throw new RetargetError(`${where}: contains NaN or infinite positions`);
  }
  if (!(Number.isFinite(frameTime) && frameTime > 0)) throw new RetargetError(`${where}: the frame time must be positive, got ${frameTime}`);
  if (!skeleton.offsets) throw new RetargetError(`${where}: the project skeleton has no offsets (bone lengths)`);
  const joints = skeleton.joints;
  const sources = resolveJoints(map, names, joints, where);
  if (src.frames === 0) throw new RetargetError(`${where}: too few frames: the file has none`, 'too-few-frames');
  if ((src.frames - 1) * frameTime * FPS >= MAX_FRAMES) {
    throw new RetargetError(`${where}: ${src.frames} frames ${frameTime} s apart last longer than an hour; check the frame time or cut the take shorter`, 'too-large');
  }

  let pts = src.points;
  if (map.up === 'z') {
    pts = new Float64Array(src.points.length);
    for (let i = 0; i < pts.length; i += 3) { pts[i] = src.points[i]; pts[i + 1] = src.points[i + 2]; pts[i + 2] = -src.points[i + 1]; }
  }
  // a leading T-pose (or any leading frame far from the rest of the take) goes, by rule
  const drop = leadingOutliers(pts, src.frames, n, sources, joints);
  const rs = resamplePoints(pts.subarray(drop * n * 3), src.frames - drop, n * 3, frameTime);
  const F = rs.frames;
  if (F < minFrames) {
    throw new RetargetError(`${where}: too few frames: ${src.frames} at ${Number((1 / frameTime).toPrecision(4))} Hz is ${F} at 30 Hz, `
      + `and a history needs at least ${minFrames}`, 'too-few-frames');
  }
  // q[j]: [F, 3] source point each project joint follows (mean of its source points)
  const q = sources.map((idx) => {
    if (!idx) return null;
    const out = new Float64Array(F * 3);
    for (let f = 0; f < F; f++) {
      for (let c = 0; c < 3; c++) {
        let s = 0;
        for (const i of idx) s += rs.points[(f * n + i) * 3 + c];
        out[f * 3 + c] = s / idx.length;
      }
    }
    return out;
  });
  const J = joints.length;
  const at = (name: string) => joints.indexOf(name);
  const dist = (a: Float64Array, b: Float64Array, f: number) =>
    Math.hypot(a[f * 3] - b[f * 3], a[f * 3 + 1] - b[f * 3 + 1], a[f * 3 + 2] - b[f * 3 + 2]);
  let legSum = 0;
  for (const [h, k, a] of LEGS) {
    const [qh, qk, qa] = [q[at(h)]!, q[at(k)]!, q[at(a)]!];
    let s = 0;
    for (let f = 0; f < F; f++) s += dist(qh, qk, f) + dist(qk, qa, f);
    legSum += s / F;
  }
  const sourceLeg = legSum / LEGS.length;
  const lengths = skeleton.offsets.map((o) => Math.hypot(o[0], o[1], o[2]));
  const projectLeg = lengths[at('right_knee')] + lengths[at('right_ankle')];
  if (!(sourceLeg > 1e-9)) throw new RetargetError(`${where}: the source legs have zero length; check the joint map`);

  const out = new Float64Array(F * J * 3);
  const o = (f: number, j: number) => (f * J + j) * 3;
  const qRoot = q[0]!;
  // the root keeps its trajectory (height and travel), scaled like the legs
  for (let f = 0; f < F; f++) for (let c = 0; c < 3; c++) out[o(f, 0) + c] = qRoot[f * 3 + c] * (projectLeg / sourceLeg);
  const [chest, rHip, lHip] = [at('chest'), at('right_hip'), at('left_hip')];
  for (let j = 1; j < J; j++) {
    const p = skeleton.parents[j];
    const L = lengths[j];
    const qj = q[j];
    const qp = q[p];
    for (let f = 0; f < F; f++) {
      const base = o(f, p);
      let dx: number, dy: number, dz: number;
      if (qj && qp) {
        dx = qj[f * 3] - qp[f * 3]; dy = qj[f * 3 + 1] - qp[f * 3 + 1]; dz = qj[f * 3 + 2] - qp[f * 3 + 2];
        const norm = Math.hypot(dx, dy, dz);
        if (norm < 1e-6 * sourceLeg) {
          throw new RetargetError(`${where}: the source points for ${joints[p]} and ${joints[j]} coincide (frame ${f} at 30 Hz); map them to different joints`);
        }
        out[o(f, j)] = out[base] + L * dx / norm;
        out[o(f, j) + 1] = out[base + 1] + L * dy / norm;
        out[o(f, j) + 2] = out[base + 2] + L * dz / norm;
      } else if (joints[j] === 'head') {
        // continue the upper spine
        dx = out[base] - out[o(f, chest)]; dy = out[base + 1] - out[o(f, chest) + 1]; dz = out[base + 2] - out[o(f, chest) + 2];
        const norm = Math.max(Math.hypot(dx, dy, dz), 1e-12);
        out[o(f, j)] = out[base] + L * dx / norm;
        out[o(f, j) + 1] = out[base + 1] + L * dy / norm;
        out[o(f, j) + 2] = out[base + 2] + L * dz / norm;
      } else {
        // a toe: the rest offset turned to the pelvis heading (forward = up x across)
        const ax = out[o(f, rHip)] - out[o(f, lHip)];
        const az = out[o(f, rHip) + 2] - out[o(f, lHip) + 2];
        let fx = az;
        let fz = -ax;
        let norm = Math.hypot(fx, fz);
        if (norm < 1e-9) { fx = 1; fz = 0; norm = 1; } // hips vertical: no heading; keep +x
        const rest = skeleton.offsets[j];
        out[o(f, j)] = out[base] + rest[0] * fx / norm;
        out[o(f, j) + 1] = out[base + 1] + rest[1];
        out[o(f, j) + 2] = out[base + 2] + rest[0] * fz / norm;
      }
    }
  }
  return { positions: putOnFloor(out, F, skeleton), frames: F };
}

export const PLAUSIBLE_HEAD = 0.25; // the head stands at least this many leg lengths above the root ...
export const PLAUSIBLE_FEET = 0.25; // ... and the ankles this many below it
export const PLAUSIBLE_SYMMETRY = 0.2; // left and right bones differ by at most this fraction
export const PLAUSIBLE_LEG = 1.2; // a leg (hip-knee-ankle) is this many times longer than any arm segment

/** Python's format(x, '.3g'), so both languages word a problem alike. */
export function g3(x: number): string {
  if (x === 0) return '0';
  const [m, e] = x.toExponential(2).split('e');
  const exp = Number(e);
  if (exp < -4 || exp >= 3) return `${m.replace(/\.?0+$/, '')}e${exp < 0 ? '-' : '+'}${String(Math.abs(exp)).padStart(2, '0')}`;
  return String(Number(x.toPrecision(3)));
}

/** Why the body as read (the map's joints, its `up` axis) cannot be a person standing upright with a
 *  human build; empty when it can. Twin of retarget.py body_problems (its docstring has the rule): head
 *  above the root and ankles below it (medians over frames, in leg lengths), left and right bones alike,
 *  legs longer than the arms' segments; a wrong up axis is named with the `up` that stands the body up. */
export function bodyProblems(src: SourcePoints, map: JointMap, projectJoints: readonly string[], where: string): string[] {
  const sources = resolveJoints(map, src.names, projectJoints, where);
  const n = src.names.length;
  const F = src.frames;
  // q(joint, yUp): [F][3] of the joint's source point, in the file's axes or turned y-up
  const track = (joint: string, yUp: boolean): number[][] => {
    const idx = sources[projectJoints.indexOf(joint)]!;
    const out: number[][] = [];
    for (let f = 0; f < F; f++) {
      const p = [0, 1, 2].map((c) => idx.reduce((t, i) => t + src.points[(f * n + i) * 3 + c], 0) / idx.length);
      out.push(yUp && map.up === 'z' ? [p[0], p[2], -p[1]] : p);
    }
    return out;
  };
  const has = (joint: string) => sources[projectJoints.indexOf(joint)] !== null;
  const cache = new Map<string, number[][]>();
  const q = (joint: string) => {
    if (!cache.has(joint)) cache.set(joint, track(joint, true));
    return cache.get(joint)!;
  };
  const length = (a: string, b: string) => median(q(a).map((p, f) => Math.hypot(p[0] - q(b)[f][0], p[1] - q(b)[f][1], p[2] - q(b)[f][2])));
  const leg = LEGS.reduce((t, [a, b, c]) => t + length(a, b) + length(b, c), 0) / LEGS.length;
  const out: string[] = [];
  const top = has('head') ? 'head' : 'neck';
  const above = median(q(top).map((p, f) => p[1] - q('root')[f][1]));
  const below = median(q('root').map((p, f) => p[1] - (q('left_ankle')[f][1] + q('right_ankle')[f][1]) / 2));
  if (!(above > PLAUSIBLE_HEAD * leg)) out.push(`the ${top} is ${g3(above)} above the root, less than ${PLAUSIBLE_HEAD} leg lengths (${g3(leg)})`);
  if (!(below > PLAUSIBLE_FEET * leg)) out.push(`the ankles are ${g3(below)} below the root, less than ${PLAUSIBLE_FEET} leg lengths (${g3(leg)})`);
  if (out.length) {
    // the file's own axes: along which does the body run from the feet to the head?
    const [t, la, ra] = [track(top, false), track('left_ankle', false), track('right_ankle', false)];
    const body = [0, 1, 2].map((c) => median(t.map((p, f) => p[c] - (la[f][c] + ra[f][c]) / 2)));
    let a = 0;
    for (let c = 1; c < 3; c++) if (Math.abs(body[c]) > Math.abs(body[a])) a = c;
    const along = `${body[a] > 0 ? '+' : '-'}${'xyz'[a]}`;
    const fix = along === '+y' ? 'y' : along === '+z' ? 'z' : null;
    if (fix && fix !== map.up) {
      out.push(`the body stands along ${along} of the file, so the file looks ${fix}-up: it was read with "up": "${map.up}" and lies flat; set "up": "${fix}" in the joint map`);
    } else {
      out.push(`the body runs along ${along} of the file from the feet to the head (upside down or lying down, read with "up": "${map.up}"); `
        + 'if the file stands upright, check its up axis and the map\'s left and right joints');
    }
  }
  for (const [a, b] of [['hip', 'knee'], ['knee', 'ankle'], ['shoulder', 'elbow'], ['elbow', 'wrist']]) {
    const r = length(`right_${a}`, `right_${b}`);
    const l = length(`left_${a}`, `left_${b}`);
    if (Math.abs(r - l) > PLAUSIBLE_SYMMETRY * (r + l) / 2) {
      out.push(`the right ${a}-${b} bone (${g3(r)}) and the left one (${g3(l)}) differ by more than ${Math.round(PLAUSIBLE_SYMMETRY * 100)}%`);
    }
  }
  const arm = Math.max(...['left', 'right'].flatMap((s) => [['shoulder', 'elbow'], ['elbow', 'wrist']].map(([a, b]) => length(`${s}_${a}`, `${s}_${b}`))));
  if (!(leg > PLAUSIBLE_LEG * arm)) out.push(`the legs (${g3(leg)}) are not longer than ${PLAUSIBLE_LEG} x the longest arm segment (${g3(arm)})`);
  return out;
}

/** One sentence for a file whose joints fail bodyProblems (null when they pass): what is wrong and the
 *  fix. importBvh and importAsfAmc put it in origin.warnings. Twin of retarget.py plausibility_warning. */
export function plausibilityWarning(src: SourcePoints, map: JointMap, projectJoints: readonly string[], where: string): string | null {
  const problems = bodyProblems(src, map, projectJoints, where);
  if (!problems.length) return null;
  return `${where}: does not look like a person standing upright with the joint map ${map.name}: ${problems.join('; ')}. `
    + `If that is not the motion, fix the joint map (${GUIDE_MAPS})`;
}
