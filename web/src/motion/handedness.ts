// Handedness, twin of export/ops/handedness.py (contract/vectors/envelope.json ties them): is a
// history's body one a person can have, or its mirror image with the left/right labels kept (issue 30)?
// Per frame, the cosine between forward from the hips (spine x the hips' left-to-right axis) and
// forward from the feet (ankle to toe, across the spine); the score is its mean over the frames: about
// +1 for a real body, about -1 for a reflected one. No rotation changes it. The fix is swapLeftRight.
import type { Skeleton } from '../contract/types';

/** Below this score the body is reflected (every 30-frame window of the clips scores >= +0.22, their mirrors <= -0.22). */
export const HANDEDNESS_THRESHOLD = 0;
export const HANDEDNESS_MESSAGE = 'Left and right look swapped: the hips face one way and the feet point the other, as in a '
  + 'mirror image. Swap the left and right joints (or fix the joint map) before predicting.';

type Vec = [number, number, number];

function unit(v: Vec): Vec {
  const n = Math.hypot(v[0], v[1], v[2]);
  return n > 1e-9 ? [v[0] / n, v[1] / n, v[2] / n] : [0, 0, 0];
}

/** World joint positions [frames, J, 3] -> whether the body is reflected, and the score in [-1, 1]. */
export function handedness(positions: ArrayLike<number>, frames: number, skeleton: Skeleton): { reflected: boolean; score: number } {
  const J = skeleton.joints.length;
  const at = (name: string) => {
    const j = skeleton.joints.indexOf(name);
    if (j < 0) throw new Error(`handedness needs the joint '${name}'`);
    return j;
  };
  const [root, neck, rh, lh, ra, rt, la, lt] = ['root', 'neck', 'right_hip', 'left_hip', 'right_ankle', 'right_toe',
    'left_ankle', 'left_toe'].map(at);
  const p = (f: number, j: number, c: number) => positions[(f * J + j) * 3 + c];
  const d = (f: number, a: number, b: number): Vec => [p(f, a, 0) - p(f, b, 0), p(f, a, 1) - p(f, b, 1), p(f, a, 2) - p(f, b, 2)];
  let sum = 0;
  for (let f = 0; f < frames; f++) {
    const across = d(f, rh, lh);
    const spine = d(f, neck, root);
    const hips = unit([spine[1] * across[2] - spine[2] * across[1], spine[2] * across[0] - spine[0] * across[2],
      spine[0] * across[1] - spine[1] * across[0]]);
    const r = d(f, rt, ra);
    const l = d(f, lt, la);
    const feet: Vec = [r[0] + l[0], r[1] + l[1], r[2] + l[2]];
    // only the part of the feet's direction across the spine: a foot pointing down says nothing
    const up = unit(spine);
    const along = feet[0] * up[0] + feet[1] * up[1] + feet[2] * up[2];
    const flat = unit([feet[0] - along * up[0], feet[1] - along * up[1], feet[2] - along * up[2]]);
    sum += hips[0] * flat[0] + hips[1] * flat[1] + hips[2] * flat[2];
  }
  const score = frames > 0 ? sum / frames : 0;
  return { reflected: score < HANDEDNESS_THRESHOLD, score };
}

/** [frames, J, 3] positions with every left joint's position given to its right twin and back (a new array). */
export function swapLeftRight(positions: Float32Array, frames: number, skeleton: Skeleton): Float32Array {
  const J = skeleton.joints.length;
  const twin = skeleton.joints.map((n) => {
    const other = n.startsWith('right_') ? `left_${n.slice(6)}` : n.startsWith('left_') ? `right_${n.slice(5)}` : n;
    const j = skeleton.joints.indexOf(other);
    return j < 0 ? skeleton.joints.indexOf(n) : j;
  });
  const out = new Float32Array(frames * J * 3);
  for (let f = 0; f < frames; f++) {
    for (let j = 0; j < J; j++) {
      for (let c = 0; c < 3; c++) out[(f * J + j) * 3 + c] = positions[(f * J + twin[j]) * 3 + c];
    }
  }
  return out;
}
