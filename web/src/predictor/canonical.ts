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
