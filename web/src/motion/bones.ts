// Bone lengths of a motion, and projecting a motion onto given lengths along the kinematic tree.
// Twin of export/ops/bones.py (contract/vectors/bones.json ties them): walking from the root, each
// joint = its placed parent + the bone's length x the unit direction from parent to joint in the
// input. Acts on world positions; the root's own position is kept.
import type { Skeleton } from '../contract/types';

type Floats = Float32Array | Float64Array;

/** [parent, child] of every bone, in joint order (parents precede children). */
export function bonesOf(skeleton: Skeleton): [number, number][] {
  const out: [number, number][] = [];
  skeleton.parents.forEach((p, j) => { if (p >= 0) out.push([p, j]); });
  return out;
}

/** [frames, J, 3] -> [frames, bones]. */
export function boneLengths(motion: ArrayLike<number>, frames: number, skeleton: Skeleton): Float64Array {
  const J = skeleton.joints.length;
  const bones = bonesOf(skeleton);
  const out = new Float64Array(frames * bones.length);
  for (let f = 0; f < frames; f++) {
    bones.forEach(([p, c], b) => {
      const o = f * J * 3;
      out[f * bones.length + b] = Math.hypot(motion[o + c * 3] - motion[o + p * 3], motion[o + c * 3 + 1] - motion[o + p * 3 + 1],
        motion[o + c * 3 + 2] - motion[o + p * 3 + 2]);
    });
  }
  return out;
}

/** A copy of `motion` [frames, J, 3] with every bone given `lengths` [bones], directions kept. */
export function projectLengths<T extends Floats>(motion: T, frames: number, lengths: ArrayLike<number>, skeleton: Skeleton): T {
  const J = skeleton.joints.length;
  const out = motion.slice() as T;
  const bones = bonesOf(skeleton);
  for (let f = 0; f < frames; f++) {
    const o = f * J * 3;
    bones.forEach(([p, c], b) => {
      const dx = motion[o + c * 3] - motion[o + p * 3];
      const dy = motion[o + c * 3 + 1] - motion[o + p * 3 + 1];
      const dz = motion[o + c * 3 + 2] - motion[o + p * 3 + 2];
      const norm = Math.hypot(dx, dy, dz);
      const k = norm > 1e-12 ? lengths[b] / norm : 0;
      out[o + c * 3] = out[o + p * 3] + k * dx;
      out[o + c * 3 + 1] = out[o + p * 3 + 1] + k * dy;
      out[o + c * 3 + 2] = out[o + p * 3 + 2] + k * dz;
    });
  }
  return out;
}

/** The mean length of each bone over a history's frames. */
export function meanLengths(history: ArrayLike<number>, frames: number, skeleton: Skeleton): Float64Array {
  const all = boneLengths(history, frames, skeleton);
  const n = all.length / frames;
  const out = new Float64Array(n);
  for (let f = 0; f < frames; f++) for (let b = 0; b < n; b++) out[b] += all[f * n + b];
  return out.map((v) => v / frames);
}

/** A canonical motion (root-relative poses, the root channel in the root joint's x and z) with the
 *  skeleton's bone lengths, twin of export/ops/bones.py keep_bones (the models' last layer in numpy). */
export function keepBones<T extends Floats>(motion: T, frames: number, skeleton: Skeleton): T {
  const J = skeleton.joints.length;
  const rest = bonesOf(skeleton).map(([, c]) => Math.hypot(...(skeleton.offsets?.[c] ?? [0, 0, 0])));
  const pose = motion.slice() as T;
  for (let f = 0; f < frames; f++) { pose[f * J * 3] = 0; pose[f * J * 3 + 2] = 0; }
  const out = projectLengths(pose, frames, rest, skeleton);
  for (let f = 0; f < frames; f++) { out[f * J * 3] = motion[f * J * 3]; out[f * J * 3 + 2] = motion[f * J * 3 + 2]; }
  return out;
}
