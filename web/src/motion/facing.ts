// Canonical facing of a window, decided at one frame (its last history frame).
// Twin of export/ops/facing.py; contract/vectors/facing.json ties them.
import type { Skeleton } from '../contract/types';

/** Angle about +y from +z to the body's forward direction at one pose (frame `f` of `pos`). */
export function facingAngle(pos: Float32Array | Float64Array, f: number, skeleton: Skeleton): number {
  const j = skeleton.joints.length;
  const r = skeleton.joints.indexOf('right_hip');
  const l = skeleton.joints.indexOf('left_hip');
  const ax = pos[(f * j + r) * 3] - pos[(f * j + l) * 3];
  const az = pos[(f * j + r) * 3 + 2] - pos[(f * j + l) * 3 + 2];
  // forward = up x across on the ground plane = (across_z, 0, -across_x)
  const fx = az;
  const fz = -ax;
  if (fx * fx + fz * fz < 1e-12) return 0; // hips vertical: no defined facing
  return Math.atan2(fx, fz);
}

/** Rotate every point of a flat [..., 3] array about +y by `angle` (right-handed), in place. */
export function rotateAboutY<T extends Float32Array | Float64Array>(pos: T, angle: number): T {
  const c = Math.cos(angle);
  const s = Math.sin(angle);
  for (let i = 0; i < pos.length; i += 3) {
    const x = pos[i];
    const z = pos[i + 2];
    pos[i] = c * x + s * z;
    pos[i + 2] = -s * x + c * z;
  }
  return pos;
}

/** A rotated copy of `window` [F, J, 3] in which frame `atFrame` faces +z, and the angle undone. */
export function canonicalise<T extends Float32Array | Float64Array>(
  window: T, atFrame: number, skeleton: Skeleton,
): { canonical: T; angle: number } {
  const angle = facingAngle(window, atFrame, skeleton);
  return { canonical: rotateAboutY(window.slice() as T, -angle), angle };
}
