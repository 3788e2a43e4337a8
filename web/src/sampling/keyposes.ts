// Keyposes (Keyposes paper, section 3.1) and their labels, twin of export/ops/keyposes.py and the
// proximity part of export/ops/proximity.py; contract/vectors/keyposes.json ties them.
// Poses are flat [frames * joints * 3] arrays.
import type { Skeleton } from '../contract/types';
import { facingAngle, rotateAboutY } from '../motion/facing';
import { softmax } from './temperature';

/** Error of every frame in [a, b] against the linear interpolation of frames a and b: the L2 norm
 *  of the whole pose difference, metres. */
export function frameErrors(pos: ArrayLike<number>, joints: number, a: number, b: number): Float64Array {
  const s = joints * 3;
  const out = new Float64Array(b - a + 1);
  for (let t = a; t <= b; t++) {
    const w = (t - a) / (b - a);
    let sum = 0;
    for (let i = 0; i < s; i++) {
      const rec = pos[a * s + i] * (1 - w) + pos[b * s + i] * w;
      const d = pos[t * s + i] - rec;
      sum += d * d;
    }
    out[t - a] = Math.sqrt(sum);
  }
  return out;
}

/** Keypose frame indices: first and last frame, then recursively the frame of largest error in each
 *  segment until the segment's mean interior error is below the threshold (ties: earliest frame). */
export function extractKeyposes(pos: ArrayLike<number>, frames: number, joints: number, threshold: number): number[] {
  if (!(threshold > 0)) throw new RangeError(`the keypose threshold must be positive, got ${threshold}`);
  if (frames < 2) return Array.from({ length: frames }, (_, i) => i);
  const keys = new Set<number>([0, frames - 1]);
  const stack: [number, number][] = [[0, frames - 1]];
  while (stack.length) {
    const [a, b] = stack.pop()!;
    if (b - a < 2) continue;
    const e = frameErrors(pos, joints, a, b);
    let sum = 0;
    let best = 1;
    for (let i = 1; i < e.length - 1; i++) {
      sum += e[i];
      if (e[i] > e[best]) best = i;
    }
    if (sum / (e.length - 2) < threshold) continue;
    const m = a + best;
    keys.add(m);
    stack.push([a, m], [m, b]);
  }
  return [...keys].sort((x, y) => x - y);
}

/** k-means' rule: each pose's label is the centre at the smallest L2 distance; with its margin. */
export function nearestCentre(values: ArrayLike<number>, count: number, centres: ArrayLike<number>, clusters: number, joints: number):
  { labels: number[]; margins: number[] } {
  const s = joints * 3;
  const labels: number[] = [];
  const margins: number[] = [];
  for (let n = 0; n < count; n++) {
    let best = Infinity;
    let second = Infinity;
    let label = 0;
    for (let c = 0; c < clusters; c++) {
      let sum = 0;
      for (let i = 0; i < s; i++) {
        const d = values[n * s + i] - centres[c * s + i];
        sum += d * d;
      }
      const dist = Math.sqrt(sum);
      if (dist < best) {
        second = best;
        best = dist;
        label = c;
      } else if (dist < second) {
        second = dist;
      }
    }
    labels.push(label);
    margins.push(second - best);
  }
  return { labels, margins };
}

/** Indices to keep: drop intermediate keyposes whose label equals both neighbours' (section 3.2). */
export function prune(labels: number[]): number[] {
  const keep: number[] = [];
  for (let i = 0; i < labels.length; i++) {
    if (i === 0 || i === labels.length - 1 || !(labels[i - 1] === labels[i] && labels[i] === labels[i + 1])) keep.push(i);
  }
  return keep;
}

/** The duration class whose half-open interval [bounds[c], bounds[c+1]) holds `frames`. */
export function durationClass(frames: number, bounds: number[]): number {
  if (frames < bounds[0]) throw new RangeError(`a keypose duration must be at least ${bounds[0]} frame, got ${frames}`);
  let c = 0;
  while (c + 1 < bounds.length && frames >= bounds[c + 1]) c++;
  return c;
}

/** Each pose turned about +y to face +z on its own (the centres carry no heading). */
export function faceForward(poses: ArrayLike<number>, count: number, skeleton: Skeleton): Float64Array {
  const s = skeleton.joints.length * 3;
  const out = Float64Array.from(poses as ArrayLike<number>);
  for (let n = 0; n < count; n++) {
    const pose = out.subarray(n * s, (n + 1) * s);
    rotateAboutY(pose, -facingAngle(pose, 0, skeleton));
  }
  return out;
}

/** Proximity [count, clusters]: minus the mean over joints of the distance to each centre. */
export function proximity(values: ArrayLike<number>, count: number, centres: ArrayLike<number>, clusters: number, joints: number): Float64Array {
  const out = new Float64Array(count * clusters);
  for (let n = 0; n < count; n++) {
    for (let c = 0; c < clusters; c++) {
      let sum = 0;
      for (let j = 0; j < joints; j++) {
        const o = j * 3;
        const dx = values[(n * joints) * 3 + o] - centres[(c * joints) * 3 + o];
        const dy = values[(n * joints) * 3 + o + 1] - centres[(c * joints) * 3 + o + 1];
        const dz = values[(n * joints) * 3 + o + 2] - centres[(c * joints) * 3 + o + 2];
        sum += Math.sqrt(dx * dx + dy * dy + dz * dz);
      }
      out[n * clusters + c] = -sum / joints;
    }
  }
  return out;
}

/** The label distribution of section 3.2.1: softmax(proximity / T), one row per pose. */
export function labelDistribution(values: ArrayLike<number>, count: number, centres: ArrayLike<number>, clusters: number,
  joints: number, temperature: number): Float64Array {
  const prox = proximity(values, count, centres, clusters, joints);
  const out = new Float64Array(count * clusters);
  for (let n = 0; n < count; n++) out.set(softmax(prox.subarray(n * clusters, (n + 1) * clusters), temperature), n * clusters);
  return out;
}

/** The history's pace within this factor of the table's; a table speed below PACE_FLOOR (m/frame) sets none. */
export const PACE_RANGE: [number, number] = [0.25, 4.0];
export const PACE_FLOOR = 1e-3;

/**
 * The factor on the table's velocities for a history, twin of export/ops/keypose_travel.py `pace`: the mean
 * speed per frame of its root channel (historyRoot [n * 2], x and z per frame) over the mean table speed
 * of its observed keypose labels; 1 where those labels barely travel, clipped to PACE_RANGE.
 */
export function pace(historyRoot: ArrayLike<number>, observed: number[], table: ArrayLike<number>): number {
  const n = historyRoot.length / 2;
  let mine = 0;
  for (let f = 1; f < n; f++) {
    mine += Math.hypot(historyRoot[f * 2] - historyRoot[(f - 1) * 2], historyRoot[f * 2 + 1] - historyRoot[(f - 1) * 2 + 1]);
  }
  mine = n > 1 ? mine / (n - 1) : 0;
  let theirs = 0;
  for (const l of observed) theirs += Math.hypot(table[l * 2], table[l * 2 + 1]);
  theirs = observed.length ? theirs / observed.length : 0;
  if (theirs < PACE_FLOOR) return 1;
  return Math.min(Math.max(mine / theirs, PACE_RANGE[0]), PACE_RANGE[1]);
}

/**
 * The root channel [frames * 2] (x, z per frame) of a sampled future, twin of export/ops/keypose_travel.py:
 * frame t (1-based) lies in the segment whose keypose it moves towards and adds that keypose's table
 * velocity (table [K * 2], metres per frame, facing frame) times `scale` (the history's pace); past the
 * last keypose the root holds.
 */
export function travel(labels: number[], durations: number[], table: ArrayLike<number>, frames: number, scale = 1): Float64Array {
  const steps = new Float64Array(frames * 2);
  let t = 0;
  for (let i = 0; i < labels.length && t < frames; i++) {
    for (let f = t; f < Math.min(t + durations[i], frames); f++) {
      steps[f * 2] = table[labels[i] * 2] * scale;
      steps[f * 2 + 1] = table[labels[i] * 2 + 1] * scale;
    }
    t += durations[i];
  }
  for (let f = 1; f < frames; f++) {    // a running sum, in order, as numpy's cumsum
    steps[f * 2] += steps[(f - 1) * 2];
    steps[f * 2 + 1] += steps[(f - 1) * 2 + 1];
  }
  return steps;
}
