// The keypose figure's read-outs: a clip rebuilt from its keyposes alone by the predictor's own
// linear interpolation (Keyposes Eq. 3), and how far it is from the capture.
import { interpolateKeyposes } from '../sampling/keypose-interpolation';

/** pos [frames * J * 3], keys ascending with keys[0] = 0 -> the interpolated frames 0 .. last key. */
export function rebuildFromKeyposes(pos: ArrayLike<number>, joints: number, keys: number[]): Float64Array {
  const s = joints * 3;
  const first = keys[0];
  const present = Float64Array.from({ length: s }, (_, i) => pos[first * s + i]);
  const later = keys.slice(1);
  const poses = new Float64Array(later.length * s);
  later.forEach((k, n) => { for (let i = 0; i < s; i++) poses[n * s + i] = pos[k * s + i]; });
  const durations = later.map((k, n) => k - (n === 0 ? first : later[n - 1]));
  const span = keys[keys.length - 1] - first;
  const out = new Float64Array((span + 1) * s);
  out.set(present);
  if (span > 0) out.set(interpolateKeyposes(present, poses, durations, span), s);
  return out;
}

/** Mean per-joint position error between two [frames * J * 3] arrays, metres. */
export function mpjpe(a: ArrayLike<number>, b: ArrayLike<number>, joints: number): number {
  const frames = Math.min(a.length, b.length) / (joints * 3);
  let total = 0;
  for (let f = 0; f < frames; f++) {
    for (let j = 0; j < joints; j++) {
      const o = (f * joints + j) * 3;
      total += Math.hypot(a[o] - b[o], a[o + 1] - b[o + 1], a[o + 2] - b[o + 2]);
    }
  }
  return total / (frames * joints);
}
