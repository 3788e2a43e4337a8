// Realism measures the stage shows, twins of export/eval/realism/mpjpe.py (mpjpe_cm_per_sample, mpjpe_cm,
// pose_spread_cm) and export/eval/realism/skating.py (contact_speeds, median_contact_speed); the shared
// vector contract/vectors/metrics.json ties the two. Motions are flat row-major [frames, joints, 3] metres,
// y up, world frame, floor y = 0; a set of futures is [k, frames, joints, 3], like readout.ts.
import type { Skeleton } from '../contract/types';
import { worldPoses } from './readout';

type Motion = ArrayLike<number>;

const CM = 100;
/** Each side's foot joints, ankle first (it wins a tie): export/eval/realism/skating.py SIDES. */
const SIDES = [['left_ankle', 'left_toe'], ['right_ankle', 'right_toe']];

function frames(length: number, count: number, joints: number, what: string): number {
  const f = length / (count * joints * 3);
  if (!Number.isInteger(f)) throw new Error(`${what}: ${length} numbers are not ${count} x frames x ${joints} x 3`);
  return f;
}

/** Mean over joints of the per-joint distance between pose `a` of x and pose `b` of y (metres). A square
 *  root of the sum of squares, not Math.hypot: the same distance for poses in metres, about 7 times
 *  faster, which the stage's read-out needs at K = 50 (1225 pairs of samples, every frame). */
function meanJointDistance(x: Motion, a: number, y: Motion, b: number, joints: number): number {
  let sum = 0;
  for (let j = 0; j < joints; j++) {
    const p = (a * joints + j) * 3;
    const q = (b * joints + j) * 3;
    const dx = x[p] - y[q];
    const dy = x[p + 1] - y[q + 1];
    const dz = x[p + 2] - y[q + 2];
    sum += Math.sqrt(dx * dx + dy * dy + dz * dz);
  }
  return sum / joints;
}

/**
 * Each sample's MPJPE against the truth [T, joints, 3] in cm: `ade` = the mean over the T truth frames and
 * the joints of the per-joint distance, `fde` = the mean over joints at the last truth frame. Longer
 * samples are cut to the truth; `relative` compares worldPoses (root-relative). The field's whole-pose
 * ADE (adeFde) is about sqrt(joints) times this for similar per-joint errors.
 */
export function mpjpeCmPerSample(
  futures: Motion, k: number, truth: Motion, joints: number, relative: boolean,
): { ade: Float64Array; fde: Float64Array } {
  const n = frames(futures.length, k, joints, 'futures');
  const t = frames(truth.length, 1, joints, 'truth');
  if (n < t) throw new Error(`the futures have ${n} frames, fewer than the truth's ${t}`);
  const f = relative ? worldPoses(futures, joints) : futures;
  const g = relative ? worldPoses(truth, joints) : truth;
  const ade = new Float64Array(k);
  const fde = new Float64Array(k);
  for (let s = 0; s < k; s++) {
    let sum = 0;
    for (let i = 0; i < t; i++) sum += meanJointDistance(f, s * n + i, g, i, joints);
    ade[s] = (sum / t) * CM;
    fde[s] = meanJointDistance(f, s * n + t - 1, g, t - 1, joints) * CM;
  }
  return { ade, fde };
}

/** Best-of-K MPJPE in cm, `ade` and `fde` each minimised over the samples on its own. */
export function mpjpeCm(
  futures: Motion, k: number, truth: Motion, joints: number, relative: boolean,
): { ade: number; fde: number } {
  const { ade, fde } = mpjpeCmPerSample(futures, k, truth, joints, relative);
  return { ade: Math.min(...ade), fde: Math.min(...fde) };
}

/**
 * The pose spread between samples in cm: the mean over sample pairs of the mean per-joint distance
 * between their root-relative poses, at the last frame (`last`) and averaged over all frames
 * (`overFrames`); 0 for one sample.
 */
export function poseSpreadCm(futures: Motion, k: number, joints: number): { last: number; overFrames: number } {
  const n = frames(futures.length, k, joints, 'futures');
  if (k < 2) return { last: 0, overFrames: 0 };
  const f = worldPoses(futures, joints);
  let last = 0;
  let over = 0;
  for (let a = 0; a < k; a++) {
    for (let b = a + 1; b < k; b++) {
      let sum = 0;
      for (let i = 0; i < n; i++) sum += meanJointDistance(f, a * n + i, f, b * n + i, joints);
      over += sum / n;
      last += meanJointDistance(f, a * n + n - 1, f, b * n + n - 1, joints);
    }
  }
  const pairs = (k * (k - 1)) / 2;
  return { last: (last / pairs) * CM, overFrames: (over / pairs) * CM };
}

/**
 * Foot contact speeds (m/s) of a world motion, left side then right, each in time order: per step t -> t+1
 * the side's foot joint is the lower of ankle and toe at t; the step counts when that same joint is below
 * `band` at t and at t+1, and its value is the joint's horizontal speed |xz_{t+1} - xz_t| * fps.
 */
export function contactSpeeds(motion: Motion, skeleton: Skeleton, fps = 30, band = 0.03): Float64Array {
  const joints = skeleton.joints.length;
  const n = frames(motion.length, 1, joints, 'motion');
  const out: number[] = [];
  for (const names of SIDES) {
    const [ankle, toe] = names.map((name) => {
      const j = skeleton.joints.indexOf(name);
      if (j < 0) throw new Error(`the skeleton has no joint ${name}`);
      return j;
    });
    const at = (f: number, j: number) => (f * joints + j) * 3;
    for (let t = 0; t + 1 < n; t++) {
      const j = motion[at(t, toe) + 1] < motion[at(t, ankle) + 1] ? toe : ankle;
      const p = at(t, j);
      const q = at(t + 1, j);
      if (motion[p + 1] < band && motion[q + 1] < band) out.push(Math.hypot(motion[q] - motion[p], motion[q + 2] - motion[p + 2]) * fps);
    }
  }
  return Float64Array.from(out);
}

/** The median of pooled contact speeds; NaN when no step touched the floor. */
export function medianContactSpeed(speeds: ArrayLike<number>): number {
  const s = Float64Array.from(speeds).sort();
  const m = s.length >> 1;
  if (s.length === 0) return NaN;
  return s.length % 2 ? s[m] : (s[m - 1] + s[m]) / 2;
}

/** Foot skating per sample: the median contact speed of each of the k futures (NaN where none touched). */
export function footSkating(futures: Motion, k: number, skeleton: Skeleton, fps = 30, band = 0.03): Float64Array {
  const size = frames(futures.length, k, skeleton.joints.length, 'futures') * skeleton.joints.length * 3;
  const all = Float64Array.from(futures);
  return Float64Array.from({ length: k }, (_, s) =>
    medianContactSpeed(contactSpeeds(all.subarray(s * size, (s + 1) * size), skeleton, fps, band)));
}
