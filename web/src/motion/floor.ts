// The floor of a clip, twin of export/ops/floor.py: estimated once per clip, never per history.
// The foot is the lower of ankle and toe; contact frames are those whose lowest foot point lies within
// CONTACT_BAND of the floor; the floor is the least-squares plane y = a x + b z + c through them,
// starting from a low percentile (never the single lowest point, so a T-pose frame or a glitch
// cannot lift the clip), tilted only where the contacts spread over MIN_SPREAD metres.
import type { Skeleton } from '../contract/types';

export const FEET = ['right_ankle', 'right_toe', 'left_ankle', 'left_toe'];
export const CONTACT_BAND = 0.03;
const START_PERCENTILE = 10;
const MIN_SPREAD = 1.0;
const MAX_SLOPE = 0.1;

/** numpy's percentile with linear interpolation. */
function percentile(values: number[], p: number): number {
  const v = [...values].sort((a, b) => a - b);
  const pos = (p / 100) * (v.length - 1);
  const i = Math.floor(pos);
  return i + 1 < v.length ? v[i] + (pos - i) * (v[i + 1] - v[i]) : v[i];
}

/** Solve the 3x3 normal equations of y = a x + b z + c. */
function fitPlane(pts: [number, number, number][]): [number, number, number] {
  const m = [[0, 0, 0], [0, 0, 0], [0, 0, 0]];
  const r = [0, 0, 0];
  for (const [x, y, z] of pts) {
    const row = [x, z, 1];
    for (let i = 0; i < 3; i++) {
      r[i] += row[i] * y;
      for (let k = 0; k < 3; k++) m[i][k] += row[i] * row[k];
    }
  }
  for (let c = 0; c < 3; c++) {              // Gaussian elimination with partial pivoting
    let piv = c;
    for (let i = c + 1; i < 3; i++) if (Math.abs(m[i][c]) > Math.abs(m[piv][c])) piv = i;
    [m[c], m[piv]] = [m[piv], m[c]];
    [r[c], r[piv]] = [r[piv], r[c]];
    for (let i = c + 1; i < 3; i++) {
      const f = m[i][c] / m[c][c];
      for (let k = c; k < 3; k++) m[i][k] -= f * m[c][k];
      r[i] -= f * r[c];
    }
  }
  const out = [0, 0, 0];
  for (let i = 2; i >= 0; i--) {
    let s = r[i];
    for (let k = i + 1; k < 3; k++) s -= m[i][k] * out[k];
    out[i] = s / m[i][i];
  }
  return [out[0], out[1], out[2]];
}

/** (a, b, c) of the floor y = a x + b z + c of a clip [frames, J, 3] (world frame, y up). */
export function floorPlane(positions: ArrayLike<number>, frames: number, skeleton: Skeleton): [number, number, number] {
  const J = skeleton.joints.length;
  const feet = FEET.map((n) => skeleton.joints.indexOf(n));
  const low: [number, number, number][] = [];
  for (let f = 0; f < frames; f++) {
    let best = feet[0];
    for (const j of feet) if (positions[(f * J + j) * 3 + 1] < positions[(f * J + best) * 3 + 1]) best = j;
    const o = (f * J + best) * 3;
    low.push([positions[o], positions[o + 1], positions[o + 2]]);
  }
  let a = 0;
  let b = 0;
  let c = percentile(low.map((p) => p[1]), START_PERCENTILE);
  for (let round = 0; round < 4; round++) {
    const pts = low.filter(([x, y, z]) => Math.abs(y - (a * x + b * z + c)) <= CONTACT_BAND);
    if (pts.length < 3) break;
    const span = (k: 0 | 2) => Math.max(...pts.map((p) => p[k])) - Math.min(...pts.map((p) => p[k]));
    if (Math.max(span(0), span(2)) >= MIN_SPREAD) {
      const [a2, b2, c2] = fitPlane(pts);
      if (Math.hypot(a2, b2) <= MAX_SLOPE) {
        [a, b, c] = [a2, b2, c2];
        continue;
      }
    }
    a = 0;
    b = 0;
    c = percentile(pts.map((p) => p[1]), 50);
  }
  return [a, b, c];
}

/** The clip with its floor at y = 0, in place: each frame shifted down by the floor height under its root. */
export function putOnFloor(positions: Float64Array, frames: number, skeleton: Skeleton): Float64Array {
  const J = skeleton.joints.length;
  const [a, b, c] = floorPlane(positions, frames, skeleton);
  for (let f = 0; f < frames; f++) {
    const o = f * J * 3;
    const h = a * positions[o] + b * positions[o + 2] + c;
    for (let j = 0; j < J; j++) positions[o + j * 3 + 1] -= h;
  }
  return positions;
}
