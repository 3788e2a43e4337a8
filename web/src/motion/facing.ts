// Facing: the body's heading at one frame, and turning points about +y. Canonical windows and the
// root channel are built from these in web/src/predictor/canonical.ts (twin of export/ops/facing.py).
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

