// Canonical facing and the root channel, twin of export/ops/facing.py and export/sample/canonical.py:
// each graph call sees a history that faces +z at its last frame with the root above the origin there.
// Poses stay root-relative (every joint measured from the ground point below the root, height kept);
// the horizontal root trajectory travels in the root channel, held in the root joint's x and z, which
// a root-relative pose leaves at 0. Turning about +y and mirroring act on both parts alike.
// contract/vectors/facing.json ties the two languages.
import type { Skeleton } from '../contract/types';
import { facingAngle, rotateAboutY } from '../motion/facing';

/** Where a canonical window sits in the world: the turn undone and the root's ground point. */
export interface Placement {
  angle: number;
  x: number;
  z: number;
}

type Floats = Float32Array | Float64Array;

/** World positions [F, J, 3] -> root-relative poses with the root channel (minus `origin`) in the root joint. */
export function splitRoot<T extends Floats>(world: T, joints: number, originX = 0, originZ = 0): T {
  const out = world.slice() as T;
  const s = joints * 3;
  for (let f = 0; f < out.length / s; f++) {
    const rx = out[f * s];
    const rz = out[f * s + 2];
    for (let j = 1; j < joints; j++) {
      out[f * s + j * 3] -= rx;
      out[f * s + j * 3 + 2] -= rz;
    }
    out[f * s] = rx - originX;
    out[f * s + 2] = rz - originZ;
  }
  return out;
}

/** The inverse of splitRoot: root-relative poses + root channel -> world positions. */
export function joinRoot<T extends Floats>(motion: T, joints: number, originX = 0, originZ = 0): T {
  const out = motion.slice() as T;
  const s = joints * 3;
  for (let f = 0; f < out.length / s; f++) {
    const rx = out[f * s] + originX;
    const rz = out[f * s + 2] + originZ;
    out[f * s] = rx;
    out[f * s + 2] = rz;
    for (let j = 1; j < joints; j++) {
      out[f * s + j * 3] += rx;
      out[f * s + j * 3 + 2] += rz;
    }
  }
  return out;
}

/** The poses of a motion that carries the root channel, without it (a copy). */
export function rootRelative<T extends Floats>(motion: T, joints: number): T {
  const out = motion.slice() as T;
  const s = joints * 3;
  for (let f = 0; f < out.length / s; f++) {
    out[f * s] = 0;
    out[f * s + 2] = 0;
  }
  return out;
}

/** A world window [F, J, 3] as the models see it, canonical at `atFrame`, and its placement. */
export function canonicalise<T extends Floats>(window: T, atFrame: number, skeleton: Skeleton): { canonical: T; placement: Placement } {
  const j = skeleton.joints.length;
  const angle = facingAngle(window, atFrame, skeleton);
  const x = window[atFrame * j * 3];
  const z = window[atFrame * j * 3 + 2];
  return { canonical: rotateAboutY(splitRoot(window, j, x, z), -angle), placement: { angle, x, z } };
}

/** A canonical motion back in the world (a copy). */
export function place<T extends Floats>(motion: T, joints: number, placement: Placement): T {
  return joinRoot(rotateAboutY(motion.slice() as T, placement.angle), joints, placement.x, placement.z);
}

/** A history [N, J, 3] (world, float32) -> canonical float32 and its placement (arithmetic in float64). */
export function toCanonical(history: Float32Array, frames: number, skeleton: Skeleton): { canonical: Float32Array; placement: Placement } {
  const { canonical, placement } = canonicalise(Float64Array.from(history), frames - 1, skeleton);
  return { canonical: Float32Array.from(canonical), placement };
}

/** Graph output (canonical) -> world float32, as the Python predictor returns it. */
export function fromCanonical(frames: Float32Array, joints: number, placement: Placement): Float32Array {
  return Float32Array.from(place(Float64Array.from(frames), joints, placement));
}

// Body scale (issue 30), twin of export/sample/canonical.py (contract/vectors/bones.json ties them): a
// history at another body size is brought to the model's size before predicting and its futures are
// scaled back, about the root's ground point at the last history frame, so the floor and the root stay
// where they are. The checked predictor (history.ts) does it once per prediction.
export const SCALE_TOLERANCE = 0.03;
export const SCALE_LIMITS: [number, number] = [0.5, 2.0];

/** World positions [frames, J, 3] -> the body's size against the skeleton: the sum of its mean bone
 * lengths over the sum of the skeleton's offsets' lengths (1 = the model's size). */
export function bodyScale(world: ArrayLike<number>, frames: number, skeleton: Skeleton): number {
  const J = skeleton.joints.length;
  let mine = 0;
  let rest = 0;
  skeleton.parents.forEach((p, c) => {
    if (p < 0) return;
    rest += Math.hypot(...(skeleton.offsets?.[c] ?? [0, 0, 0]));
    let sum = 0;
    for (let f = 0; f < frames; f++) {
      const a = (f * J + p) * 3;
      const b = (f * J + c) * 3;
      sum += Math.hypot(world[b] - world[a], world[b + 1] - world[a + 1], world[b + 2] - world[a + 2]);
    }
    mine += sum / frames;
  });
  return mine / rest;
}

/** The point scaling keeps: the root's ground point at the last frame. */
export function scaleAnchor(world: ArrayLike<number>, frames: number, joints: number): [number, number, number] {
  const o = (frames - 1) * joints * 3;
  return [world[o], 0, world[o + 2]];
}

/** Flat [..., 3] positions scaled by `factor` about `anchor` (arithmetic in float64, a float32 copy). */
export function rescale(world: ArrayLike<number>, factor: number, anchor: [number, number, number]): Float32Array {
  const out = new Float32Array(world.length);
  for (let i = 0; i < world.length; i++) out[i] = anchor[i % 3] + (world[i] - anchor[i % 3]) * factor;
  return out;
}
