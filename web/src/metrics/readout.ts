// The read-out's metrics of K predicted futures, twin of export/eval/metrics.py (the same definitions;
// contract/vectors/metrics.json ties the two). Motions are flat row-major [frames, joints, 3] metres,
// y up, world frame; a set of futures is [k, frames, joints, 3], like Prediction.futures.
import type { Skeleton } from '../contract/types';
import { rootRelative, splitRoot } from '../predictor/canonical';

type Motion = ArrayLike<number>;

/** Feet for the floor test: the foot is the lower of ankle and toe, either side (export/ops/floor.py). */
const FEET = ['right_ankle', 'right_toe', 'left_ankle', 'left_toe'];

function framesOf(length: number, count: number, joints: number, what: string): number {
  const frames = length / (count * joints * 3);
  if (!Number.isInteger(frames)) throw new Error(`${what}: ${length} numbers are not ${count} x frames x ${joints} x 3`);
  return frames;
}

/** World positions -> root-relative poses (each frame's root x and z subtracted, heights kept): the
 *  split of web/src/predictor/canonical.ts without the root channel, so the transformation has one home. */
export function worldPoses(motion: Motion, joints: number): Float64Array {
  return rootRelative(splitRoot(Float64Array.from(motion), joints), joints);
}

/**
 * Each sample's ADE and FDE against the truth [T, joints, 3]: ADE = mean over the T truth frames of the
 * whole-pose distance ||y_t - x_t||_2 (joints x 3 coordinates; WAT Eq. 12, DLow), FDE = that distance
 * at the last truth frame. Longer samples are cut to the truth; `relative` compares worldPoses.
 */
export function adeFdePerSample(
  futures: Motion, k: number, truth: Motion, joints: number, relative: boolean,
): { ade: Float64Array; fde: Float64Array } {
  const frames = framesOf(futures.length, k, joints, 'futures');
  const t = framesOf(truth.length, 1, joints, 'truth');
  if (frames < t) throw new Error(`the futures have ${frames} frames, fewer than the truth's ${t}`);
  const f = relative ? worldPoses(futures, joints) : futures;
  const g = relative ? worldPoses(truth, joints) : truth;
  const pose = joints * 3;
  const ade = new Float64Array(k);
  const fde = new Float64Array(k);
  for (let s = 0; s < k; s++) {
    let sum = 0;
    let last = 0;
    for (let i = 0; i < t; i++) {
      const a = (s * frames + i) * pose;
      let sq = 0;
      for (let c = 0; c < pose; c++) {
        const d = f[a + c] - g[i * pose + c];
        sq += d * d;
      }
      last = Math.sqrt(sq);
      sum += last;
    }
    ade[s] = sum / t;
    fde[s] = last;
  }
  return { ade, fde };
}

/** Best-of-K ADE and FDE, each minimised over the samples on its own (DLow): they may be two samples. */
export function adeFde(
  futures: Motion, k: number, truth: Motion, joints: number, relative: boolean,
): { ade: number; fde: number } {
  const { ade, fde } = adeFdePerSample(futures, k, truth, joints, relative);
  return { ade: Math.min(...ade), fde: Math.min(...fde) };
}

/**
 * DLow's APD: the mean over ordered pairs i != j of ||Y_i - Y_j||_2, each Y a whole future flattened
 * to frames x joints x 3 numbers; 0 for k = 1. Not WAT Eq. 10 (diversity: per-frame, then averaged).
 */
export function apd(futures: Motion, k: number): number {
  if (k < 2) return 0;
  const n = futures.length / k;
  let sum = 0;
  for (let i = 0; i < k; i++) {
    for (let j = i + 1; j < k; j++) {
      let sq = 0;
      for (let c = 0; c < n; c++) {
        const d = futures[i * n + c] - futures[j * n + c];
        sq += d * d;
      }
      sum += Math.sqrt(sq);
    }
  }
  return (2 * sum) / (k * (k - 1)); // each unordered pair stands for two ordered ones
}

/**
 * How many times the pose spread (mean per-joint distance between two samples, realism.ts) APD is at
 * least: a pair's APD is the L2 norm of its frames x joints joint distances, and an L2 norm of n
 * numbers is at least sqrt(n) times their mean. The read-out's sentence on field units names it.
 */
export function apdFactor(frames: number, joints = 18): number {
  return Math.sqrt(joints * frames);
}

/** The skeleton's bones as [parent, child], in joint order (as export/data/skeleton.py's `bones`). */
export function bones(skeleton: Skeleton): [number, number][] {
  const out: [number, number][] = [];
  skeleton.parents.forEach((p, j) => { if (p >= 0) out.push([p, j]); });
  return out;
}

/** [frames x bones]: each bone's length per frame, row-major. */
export function boneLengths(motion: Motion, skeleton: Skeleton): Float64Array {
  const joints = skeleton.joints.length;
  const frames = framesOf(motion.length, 1, joints, 'motion');
  const bs = bones(skeleton);
  const out = new Float64Array(frames * bs.length);
  for (let f = 0; f < frames; f++) {
    bs.forEach(([p, j], b) => {
      const a = (f * joints + p) * 3;
      const c = (f * joints + j) * 3;
      out[f * bs.length + b] = Math.hypot(motion[c] - motion[a], motion[c + 1] - motion[a + 1], motion[c + 2] - motion[a + 2]);
    });
  }
  return out;
}

/** The history's mean bone lengths: the reference of boneLengthError. */
export function meanBoneLengths(history: Motion, skeleton: Skeleton): Float64Array {
  const lengths = boneLengths(history, skeleton);
  const nb = bones(skeleton).length;
  const frames = lengths.length / nb;
  const out = new Float64Array(nb);
  for (let i = 0; i < lengths.length; i++) out[i % nb] += lengths[i];
  return out.map((v) => v / frames);
}

/** Mean over frames and bones of |L - L_ref| / L_ref: how far a motion stretches the body. */
export function boneLengthError(motion: Motion, reference: ArrayLike<number>, skeleton: Skeleton): number {
  const lengths = boneLengths(motion, skeleton);
  const nb = reference.length;
  if (nb !== bones(skeleton).length) throw new Error(`${nb} reference lengths for ${bones(skeleton).length} bones`);
  let sum = 0;
  for (let i = 0; i < lengths.length; i++) {
    const ref = reference[i % nb];
    if (!(ref > 0)) throw new Error('reference bone lengths must be positive');
    sum += Math.abs(lengths[i] - ref) / ref;
  }
  return sum / lengths.length;
}

/**
 * Share of frames whose foot (the lower of ankle and toe, either side) is more than `depth` metres
 * below the floor y = 0; a foot within `depth` counts as on the floor (export/ops/floor.py's band).
 */
export function footBelowFloor(motion: Motion, skeleton: Skeleton, depth = 0.03): number {
  const joints = skeleton.joints.length;
  const frames = framesOf(motion.length, 1, joints, 'motion');
  const feet = FEET.map((n) => {
    const j = skeleton.joints.indexOf(n);
    if (j < 0) throw new Error(`the skeleton has no joint ${n}`);
    return j;
  });
  let below = 0;
  for (let f = 0; f < frames; f++) {
    const foot = Math.min(...feet.map((j) => motion[(f * joints + j) * 3 + 1]));
    if (foot < -depth) below++;
  }
  return below / frames;
}
