// Planted feet, twin of export/ops/foot_plant.py: the root's horizontal travel re-derived from the
// feet on the floor, so a foot in contact stays where it is in the world while the body passes over
// it. Per step t -> t+1 each foot joint (ankles, toes) weighs w = min(c(y_t), c(y_t+1)) * g(s), c a
// ramp from 1 at FULL to 0 at NONE, g one from 1 at SLOW to 0 at SLIDING of the joint's world speed
// under the method's root (a foot swinging low is not on the floor; continuous, so float32
// differences between runtimes cannot flip a whole root path); the root's step becomes (1 - a) * the method's + a * the weighted opposite of the
// feet's steps relative to the root, a = the largest weight. Heights and root-relative poses stay.
import type { Skeleton } from '../contract/types';

export const FOOT_JOINTS = ['left_ankle', 'left_toe', 'right_ankle', 'right_toe'] as const;
export const FULL = 0.02;
export const NONE = 0.04;
export const SLOW = 1.0;
export const SLIDING = 2.5;
const FPS = 30;

export function speedWeight(speed: number): number {
  return Math.min(1, Math.max(0, (SLIDING - speed) / (SLIDING - SLOW)));
}

export function contactWeight(height: number): number {
  return Math.min(1, Math.max(0, (NONE - height) / (NONE - FULL)));
}

/** In place: futures [k, frames, J, 3] (world) continuing `present` [J, 3], the history's last frame. */
export function plantFeet(present: ArrayLike<number>, futures: Float32Array, k: number, frames: number,
  skeleton: Skeleton): void {
  const J = skeleton.joints.length;
  const s = J * 3;
  const idx = FOOT_JOINTS.map((n) => {
    const i = skeleton.joints.indexOf(n);
    if (i < 0) throw new Error(`the skeleton has no ${n} joint to plant`);
    return i;
  });
  const prevX = new Float64Array(idx.length);
  const prevZ = new Float64Array(idx.length);
  const relX = new Float64Array(idx.length);
  const relZ = new Float64Array(idx.length);
  const weight = new Float64Array(idx.length);
  for (let i = 0; i < k; i++) {
    const base = i * frames * s;
    // the previous frame as predicted (root, feet relative to it) and the new root path so far
    let rootX = present[0];
    let rootZ = present[2];
    let newX = rootX;
    let newZ = rootZ;
    for (let f = 0; f < idx.length; f++) {
      const j = idx[f] * 3;
      prevX[f] = present[j];
      prevZ[f] = present[j + 2];
      relX[f] = present[j] - rootX;
      relZ[f] = present[j + 2] - rootZ;
      weight[f] = contactWeight(present[j + 1]);
    }
    for (let t = 0; t < frames; t++) {
      const o = base + t * s;
      const x = futures[o];
      const z = futures[o + 2];
      let total = 0;
      let most = 0;
      let px = 0;
      let pz = 0;
      for (let f = 0; f < idx.length; f++) {
        const j = o + idx[f] * 3;
        const rx = futures[j] - x;
        const rz = futures[j + 2] - z;
        const c = contactWeight(futures[j + 1]);
        const w = Math.min(weight[f], c) * speedWeight(Math.hypot(futures[j] - prevX[f], futures[j + 2] - prevZ[f]) * FPS);
        prevX[f] = futures[j];
        prevZ[f] = futures[j + 2];
        total += w;
        most = Math.max(most, w);
        px -= w * (rx - relX[f]);
        pz -= w * (rz - relZ[f]);
        relX[f] = rx;
        relZ[f] = rz;
        weight[f] = c;
      }
      const d = Math.max(total, 1e-12);
      newX += (1 - most) * (x - rootX) + most * (px / d);
      newZ += (1 - most) * (z - rootZ) + most * (pz / d);
      rootX = x;
      rootZ = z;
      const dx = newX - x;
      const dz = newZ - z;
      for (let j = 0; j < J; j++) {
        futures[o + j * 3] += dx;
        futures[o + j * 3 + 2] += dz;
      }
    }
  }
}
