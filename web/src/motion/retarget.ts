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

/** Per project joint: the source indices whose mean it follows, or null (derived). */
export function resolveJoints(map: JointMap, names: readonly string[], projectJoints: readonly string[], where: string): (number[] | null)[] {
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
  if (missing.length) {
    let shown = names.filter((n) => !n.includes('/end')).join(', ');
    if (shown.length >= 400) shown = `${shown.slice(0, 400)}…`;
    throw new RetargetError(`${where}: unknown skeleton for joint map ${map.name}: no source joint for ${missing.join('; ')}. `
      + `The file's joints are: ${shown}. Give a joint map (docs/BRING_YOUR_OWN.md)`, 'unknown-skeleton');
  }
  return out;
}

/** Linear interpolation in time to `outFps` over the source's duration (same arithmetic as Python). */
export function resamplePoints(src: Float64Array, frames: number, width: number, frameTime: number, outFps = FPS): { points: Float64Array; frames: number } {
  if (frames === 1) return { points: src.slice(0, width), frames: 1 };
  const n = Math.floor((frames - 1) * frameTime * outFps + 1e-9) + 1;
  const out = new Float64Array(n * width);
  for (let k = 0; k < n; k++) {
    const u = (k / outFps) / frameTime;
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
