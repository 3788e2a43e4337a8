// The floor of a clip, twin of export/ops/floor.py: estimated once per clip, never per history.
// The foot is the lower of ankle and toe; contact frames are those whose lowest foot point lies within
// CONTACT_BAND of the floor; the floor is the least-squares plane y = a x + b z + c through them,
// starting from a low percentile (never the single lowest point, so a T-pose frame or a glitch
// cannot lift the clip), tilted only along a principal ground axis of the contacts that spreads over
// MIN_SPREAD metres (a walk's direction; across it the feet are only a stride apart).
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

/** Least squares of y on the given columns plus a constant (normal equations, Gaussian elimination). */
function fitLinear(rows: number[][], ys: number[]): number[] {
  const n = rows[0].length + 1;
  const m = Array.from({ length: n }, () => new Array<number>(n).fill(0));
  const r = new Array<number>(n).fill(0);
  rows.forEach((row, i) => {
    const x = [...row, 1];
    for (let p = 0; p < n; p++) {
      r[p] += x[p] * ys[i];
      for (let q = 0; q < n; q++) m[p][q] += x[p] * x[q];
    }
  });
  for (let c = 0; c < n; c++) {              // with partial pivoting
    let piv = c;
    for (let i = c + 1; i < n; i++) if (Math.abs(m[i][c]) > Math.abs(m[piv][c])) piv = i;
    [m[c], m[piv]] = [m[piv], m[c]];
    [r[c], r[piv]] = [r[piv], r[c]];
    for (let i = c + 1; i < n; i++) {
      const f = m[i][c] / m[c][c];
      for (let k = c; k < n; k++) m[i][k] -= f * m[c][k];
      r[i] -= f * r[c];
    }
  }
  const out = new Array<number>(n).fill(0);
  for (let i = n - 1; i >= 0; i--) {
    let s = r[i];
    for (let k = i + 1; k < n; k++) s -= m[i][k] * out[k];
    out[i] = s / m[i][i];
  }
  return out;
}

/** The principal axes of ground points (x, z): the first the widest spread (closed form, as Python). */
function axes(pts: [number, number][]): [[number, number], [number, number]] {
  const mx = pts.reduce((s, p) => s + p[0], 0) / pts.length;
  const mz = pts.reduce((s, p) => s + p[1], 0) / pts.length;
  let sxx = 0; let sxz = 0; let szz = 0;
  for (const [x, z] of pts) { sxx += (x - mx) ** 2; sxz += (x - mx) * (z - mz); szz += (z - mz) ** 2; }
  const t = 0.5 * Math.atan2(2 * sxz, sxx - szz);
  const u: [number, number] = [Math.cos(t), Math.sin(t)];
  return [u, [-u[1], u[0]]];
}

function median(values: number[]): number {
  const v = [...values].sort((a, b) => a - b);
  const m = v.length >> 1;
  return v.length % 2 ? v[m] : (v[m - 1] + v[m]) / 2;
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
    // a tilt only along a ground axis the contacts spread over (a walk's direction)
    const ground = pts.map(([x, , z]) => [x, z] as [number, number]);
    const cx = ground.reduce((s, p) => s + p[0], 0) / ground.length;
    const cz = ground.reduce((s, p) => s + p[1], 0) / ground.length;
    const ax = axes(ground);
    const along = ground.map(([x, z]) => ax.map((u) => (x - cx) * u[0] + (z - cz) * u[1]));
    const wide = [0, 1].filter((k) => Math.max(...along.map((p) => p[k])) - Math.min(...along.map((p) => p[k])) >= MIN_SPREAD);
    const fit = fitLinear(along.map((p) => wide.map((k) => p[k])), pts.map((p) => p[1]));
    let sx = 0;
    let sz = 0;
    wide.forEach((k, i) => { sx += fit[i] * ax[k][0]; sz += fit[i] * ax[k][1]; });
    let c0 = fit[fit.length - 1];
    if (Math.hypot(sx, sz) > MAX_SLOPE) { sx = 0; sz = 0; c0 = median(pts.map((p) => p[1])); }
    a = sx;
    b = sz;
    c = c0 - (sx * cx + sz * cz);
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
