// The training envelope, twin of export/ops/envelope.py (contract/vectors/envelope.json ties them):
// a canonical history's quantities, and named warnings for those outside what the model was trained on.
// The speed quantities (root_speed, joint_speed, tempo) are measured on the last SPEED_FRAMES frames, the
// same for every model (issue 30); tempo compares the history's joint speed with the training motion's
// through the same poses (the manifest's tempo_poses), and is null where it is not measured.
import type { Skeleton } from '../contract/types';
import { bonesOf } from '../motion/bones';
import type { RangeWarning } from './types';

const QUANTITIES: Record<string, [string, string]> = {
  root_height: ['m', 'root height'],
  root_speed: ['m/s', 'walking speed of the root'],
  scale: ['m', 'body size (root to head)'],
  bone_error: ['', 'bone length difference'],
  joint_speed: ['m/s', 'fastest joint speed'],
  tempo: ['x', "tempo (speed through its poses against the training motion's)"],
};
export const SPEED_FRAMES = 10;
const TEMPO_MATCH = 0.1;
const TEMPO_TRAVEL = 0.4;
const TEMPO_EPS = 0.05;

/** tempo's reference in the manifest: k-means centres of training poses and their median speeds. */
export interface TempoPoses { centres: number[][]; speeds: number[] }
/** A model's envelope: quantity -> [low, high], and tempo's reference poses. */
export type Envelope = { [quantity: string]: unknown };

/** Per pair of frames of world positions: the mid pose root-relative, turned to face +z, joints 1..
 * flattened; and the joints' speed about the root (m/s). Twin of envelope.py _pose_pairs. */
function posePairs(world: Float64Array, frames: number, fps: number, skeleton: Skeleton): { desc: Float64Array[]; speed: number[] } {
  const J = skeleton.joints.length;
  const s = J * 3;
  const rh = skeleton.joints.indexOf('right_hip');
  const lh = skeleton.joints.indexOf('left_hip');
  const rel = Float64Array.from(world);
  for (let f = 0; f < frames; f++) {
    const gx = world[f * s];
    const gz = world[f * s + 2];
    for (let j = 0; j < J; j++) { rel[f * s + j * 3] -= gx; rel[f * s + j * 3 + 2] -= gz; }
  }
  const desc: Float64Array[] = [];
  const speed: number[] = [];
  for (let f = 0; f + 1 < frames; f++) {
    const mid = new Float64Array(s);
    for (let i = 0; i < s; i++) mid[i] = 0.5 * (rel[(f + 1) * s + i] + rel[f * s + i]);
    const fx = mid[rh * 3 + 2] - mid[lh * 3 + 2];
    const fz = -(mid[rh * 3] - mid[lh * 3]);
    const angle = fx * fx + fz * fz < 1e-12 ? 0 : Math.atan2(fx, fz);
    const c = Math.cos(-angle);
    const sn = Math.sin(-angle);
    const d = new Float64Array((J - 1) * 3);
    for (let j = 1; j < J; j++) {
      const x = mid[j * 3];
      const z = mid[j * 3 + 2];
      d[(j - 1) * 3] = c * x + sn * z;
      d[(j - 1) * 3 + 1] = mid[j * 3 + 1];
      d[(j - 1) * 3 + 2] = -sn * x + c * z;
    }
    desc.push(d);
    let sq = 0;
    for (let i = 3; i < s; i++) sq += (rel[(f + 1) * s + i] - rel[f * s + i]) ** 2;
    speed.push(Math.sqrt(sq) * fps);
  }
  return { desc, speed };
}

/** World-like positions of canonical frames: the root-relative pose moved by the root channel. */
function joined(canonical: ArrayLike<number>, from: number, frames: number, J: number): Float64Array {
  const s = J * 3;
  const out = new Float64Array(frames * s);
  for (let f = 0; f < frames; f++) {
    const o = (from + f) * s;
    for (let i = 0; i < s; i++) out[f * s + i] = canonical[o + i];
    for (let j = 1; j < J; j++) { out[f * s + j * 3] += canonical[o]; out[f * s + j * 3 + 2] += canonical[o + 2]; }
  }
  return out;
}

/** The last SPEED_FRAMES of a canonical history against tempo's reference; null when not measured. */
export function tempo(canonical: ArrayLike<number>, frames: number, fps: number, reference: TempoPoses, skeleton: Skeleton): number | null {
  const J = skeleton.joints.length;
  const s = J * 3;
  const n = Math.min(frames, SPEED_FRAMES);
  const from = frames - n;
  if (n < 2) return null;
  const travel = Math.hypot(canonical[(frames - 1) * s] - canonical[from * s], canonical[(frames - 1) * s + 2] - canonical[from * s + 2]);
  if ((travel * fps) / (n - 1) < TEMPO_TRAVEL) return null;
  if (!reference.centres.length) return null;
  const { desc, speed } = posePairs(joined(canonical, from, n, J), n, fps, skeleton);
  let mine = 0;
  let ref = 0;
  let matched = 0;
  desc.forEach((d, p) => {
    let best = Infinity;
    let at = 0;
    reference.centres.forEach((c, k) => {
      let sq = 0;
      for (let i = 0; i < d.length; i++) sq += (d[i] - c[i]) ** 2;
      if (sq < best) { best = sq; at = k; }
    });
    if (Math.sqrt(best / (J - 1)) < TEMPO_MATCH) {
      matched += 1;
      mine += speed[p];
      ref += reference.speeds[at];
    }
  });
  if (2 * matched < desc.length) return null;
  return (mine + TEMPO_EPS) / (ref + TEMPO_EPS);
}

/** One canonical history [frames, J, 3] (root-relative poses, the root channel in the root joint) -> its
 * quantities (tempo only with a reference, null where not measured). */
export function measure(canonical: ArrayLike<number>, frames: number, fps: number, skeleton: Skeleton,
  reference?: TempoPoses): Record<string, number | null> {
  const J = skeleton.joints.length;
  const s = J * 3;
  const head = skeleton.joints.indexOf('head');
  const bones = bonesOf(skeleton);
  const rest = bones.map(([, c]) => Math.hypot(...(skeleton.offsets?.[c] ?? [0, 0, 0])));
  const from = Math.max(0, frames - SPEED_FRAMES);
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
    if (f > from) {
      path += Math.hypot(canonical[f * s] - canonical[(f - 1) * s], canonical[f * s + 2] - canonical[(f - 1) * s + 2]);
      for (let j = 0; j < J; j++) {
        jointSpeed = Math.max(jointSpeed, Math.hypot(px(f, j) - px(f - 1, j), py(f, j) - py(f - 1, j), pz(f, j) - pz(f - 1, j)));
      }
    }
  }
  const recent = frames - from;
  const out: Record<string, number | null> = {
    root_height: height / frames,
    root_speed: recent > 1 ? (path / (recent - 1)) * fps : 0,
    scale: scale / frames,
    bone_error: boneError,
    joint_speed: jointSpeed * fps,
  };
  if (reference) out.tempo = tempo(canonical, frames, fps, reference, skeleton);
  return out;
}

/** The named warnings for a history outside `env` (quantity -> [low, high], and tempo_poses). */
export function checkEnvelope(canonical: ArrayLike<number>, frames: number, fps: number, skeleton: Skeleton,
  env: Envelope): RangeWarning[] {
  const out: RangeWarning[] = [];
  for (const [q, v] of Object.entries(measure(canonical, frames, fps, skeleton, env.tempo_poses as TempoPoses | undefined))) {
    const range = env[q] as [number, number] | undefined;
    if (!range || v === null) continue;
    const [lo, hi] = range;
    if (v >= lo && v <= hi) continue;
    const [unit, what] = QUANTITIES[q];
    const u = unit ? ` ${unit}` : '';
    const message = q === 'tempo'
      ? `The history moves ${v.toFixed(2)}x as fast through its poses as the training motion does (${lo.toFixed(2)}-${hi.toFixed(2)}x): is it played ${v > hi ? 'faster' : 'slower'} than real time? The prediction may be unreliable.`
      : `The history's ${what} is ${v.toFixed(2)}${u}, outside what this model was trained on (${lo.toFixed(2)}-${hi.toFixed(2)}${u}): the prediction may be unreliable.`;
    out.push({ quantity: q, value: Math.round(v * 1e4) / 1e4, min: lo, max: hi, unit, message });
  }
  return out;
}
