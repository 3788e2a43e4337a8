// The DCT figure's data (WAT Eq. 4): a transition Z of 2L poses built from real clips, and one
// coordinate's approximation by the first M DCT bases with the predictor's own dctBasis.
import type { Skeleton } from '../contract/types';
import { canonicalise, rootRelative } from '../predictor/canonical';
import { dctBasis } from '../sampling/dct-smoothness';

/**
 * tail: the last L frames of one clip, head: the first L of another, both [l * J * 3]. Each part
 * is turned to face +z at the join (the tail at its last frame, the head at its first), as WAT
 * joins a history to an instance of another action in the history's canonical frame. Eq. 4 acts
 * on root-relative poses (web/src/predictor/canonical.ts), so where each clip stands does not matter.
 */
export function joinWindows(tail: Float32Array, head: Float32Array, l: number, skeleton: Skeleton): Float64Array {
  const s = skeleton.joints.length * 3;
  if (tail.length !== l * s || head.length !== l * s) throw new RangeError(`joinWindows: need ${l} frames on each side`);
  const j = skeleton.joints.length;
  const a = rootRelative(canonicalise(Float64Array.from(tail), l - 1, skeleton).canonical, j);
  const b = rootRelative(canonicalise(Float64Array.from(head), 0, skeleton).canonical, j);
  const z = new Float64Array(2 * l * s);
  z.set(a);
  z.set(b, l * s);
  return z;
}

/** One coordinate (joint j, axis 0..2) of every frame of z [frames * J * 3]. */
export function coordinate(z: ArrayLike<number>, frames: number, joints: number, joint: number, axis: number): Float64Array {
  const out = new Float64Array(frames);
  for (let f = 0; f < frames; f++) out[f] = z[(f * joints + joint) * 3 + axis];
  return out;
}

/** D D^T x for one coordinate's series x [frames]: its projection on the first `bases` DCT bases. */
export function dctApproximation(x: ArrayLike<number>, bases: number): Float64Array {
  const n = x.length;
  const d = dctBasis(n, bases);
  const coef = new Float64Array(bases);
  for (let m = 0; m < bases; m++) for (let t = 0; t < n; t++) coef[m] += d[t * bases + m] * x[t];
  const out = new Float64Array(n);
  for (let t = 0; t < n; t++) for (let m = 0; m < bases; m++) out[t] += d[t * bases + m] * coef[m];
  return out;
}
