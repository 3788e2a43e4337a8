// The training envelope, twin of export/ops/envelope.py (contract/vectors/envelope.json ties them):
// a canonical history's quantities, and named warnings for those outside what the model was trained on.
import type { Skeleton } from '../contract/types';
import { bonesOf } from '../motion/bones';
import type { RangeWarning } from './types';

const QUANTITIES: Record<string, [string, string]> = {
  root_height: ['m', 'root height'],
  root_speed: ['m/s', 'walking speed of the root'],
  scale: ['m', 'body size (root to head)'],
  bone_error: ['', 'bone length difference'],
  joint_speed: ['m/s', 'fastest joint speed'],
};

/** One canonical history [frames, J, 3] (root-relative poses, the root channel in the root joint) -> its quantities. */
export function measure(canonical: ArrayLike<number>, frames: number, fps: number, skeleton: Skeleton): Record<string, number> {
  const J = skeleton.joints.length;
  const s = J * 3;
  const head = skeleton.joints.indexOf('head');
  const bones = bonesOf(skeleton);
  const rest = bones.map(([, c]) => Math.hypot(...(skeleton.offsets?.[c] ?? [0, 0, 0])));
  let height = 0;
  let scale = 0;
  let path = 0;
  let boneError = 0;
  let jointSpeed = 0;
  // world-like: the root-relative pose moved by the root channel (the canonical frame's ground point)
  const px = (f: number, j: number) => (j === 0 ? 0 : canonical[f * s + j * 3]) + canonical[f * s];
  const pz = (f: number, j: number) => (j === 0 ? 0 : canonical[f * s + j * 3 + 2]) + canonical[f * s + 2];
  const py = (f: number, j: number) => canonical[f * s + j * 3 + 1];
  for (let f = 0; f < frames; f++) {
    height += canonical[f * s + 1];
    scale += Math.hypot(canonical[f * s + head * 3], canonical[f * s + head * 3 + 1] - canonical[f * s + 1], canonical[f * s + head * 3 + 2]);
    bones.forEach(([p, c], b) => {
      const ax = p === 0 ? 0 : canonical[f * s + p * 3];
      const az = p === 0 ? 0 : canonical[f * s + p * 3 + 2];
      const len = Math.hypot(canonical[f * s + c * 3] - ax, canonical[f * s + c * 3 + 1] - canonical[f * s + p * 3 + 1], canonical[f * s + c * 3 + 2] - az);
      boneError = Math.max(boneError, Math.abs(len - rest[b]) / rest[b]);
    });
    if (f > 0) {
      path += Math.hypot(canonical[f * s] - canonical[(f - 1) * s], canonical[f * s + 2] - canonical[(f - 1) * s + 2]);
      for (let j = 0; j < J; j++) {
        jointSpeed = Math.max(jointSpeed, Math.hypot(px(f, j) - px(f - 1, j), py(f, j) - py(f - 1, j), pz(f, j) - pz(f - 1, j)));
      }
    }
  }
  return {
    root_height: height / frames,
    root_speed: frames > 1 ? (path / (frames - 1)) * fps : 0,
    scale: scale / frames,
    bone_error: boneError,
    joint_speed: jointSpeed * fps,
  };
}

/** The named warnings for a history outside `env` (quantity -> [low, high]). */
export function checkEnvelope(canonical: ArrayLike<number>, frames: number, fps: number, skeleton: Skeleton,
  env: Record<string, [number, number]>): RangeWarning[] {
  const out: RangeWarning[] = [];
  for (const [q, v] of Object.entries(measure(canonical, frames, fps, skeleton))) {
    const range = env[q];
    if (!range) continue;
    const [lo, hi] = range;
    if (v >= lo && v <= hi) continue;
    const [unit, what] = QUANTITIES[q];
    const u = unit ? ` ${unit}` : '';
    out.push({
      quantity: q, value: Math.round(v * 1e4) / 1e4, min: lo, max: hi, unit,
      message: `The history's ${what} is ${v.toFixed(2)}${u}, outside what this model was trained on (${lo.toFixed(2)}-${hi.toFixed(2)}${u}): the prediction may be unreliable.`,
    });
  }
  return out;
}
