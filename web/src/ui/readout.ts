// The stage's read-out: the evaluation's own numbers for the prediction on screen, from
// web/src/metrics/readout.ts (the twin of export/eval/metrics.py, tied by contract/vectors/metrics.json;
// contract/vectors/readout.json ties this whole read-out to the Python predictor and evaluation).
//   - best-of-K ADE and FDE, root-relative and in the world frame, and each sample's own, when the
//     clip's ground truth covers every predicted frame (futures as the predictor returns them: a
//     shorter sample holds its last pose, as the evaluation pads it);
//   - APD over the K futures (DLow), on root-relative poses as DLow computes it;
//   - per sample, over its own frames: bone-length error against the history's mean bone lengths,
//     and the share of frames with a foot more than 3 cm below the floor;
//   - in units people read (web/src/metrics/realism.ts, twin of export/eval/realism/mpjpe.py, tied by
//     contract/vectors/metrics.json): the mean per-joint error in cm (root-relative, as Evaluation v3's
//     mpjpe_cm column), best of K and per sample, when the ground truth covers the futures, and the
//     pose spread between the samples in cm.
import type { Skeleton } from '../contract/types';
import {
  adeFdePerSample, apd, boneLengthError, footBelowFloor, meanBoneLengths, worldPoses,
} from '../metrics/readout';
import { mpjpeCmPerSample, poseSpreadCm } from '../metrics/realism';
import type { Prediction } from '../predictor/types';

export interface Errors { ade: number; fde: number }

export interface SampleNumbers {
  rootRelative?: Errors;
  world?: Errors;
  /** Mean relative bone-length error over the sample's own frames. */
  boneLengthError: number;
  /** Share of the sample's own frames with a foot more than FOOT_DEPTH below the floor. */
  footBelowFloor: number;
  /** Mean per-joint error in cm, root-relative: over the frames (`ade`) and at the last one (`fde`). */
  perJointCm?: Errors;
}

export interface StageReadout {
  k: number;
  /** Frames per future (the longest sample), and the ground-truth frames the clip holds after the history. */
  frames: number;
  truthFrames: number;
  /** True when the ground truth covers every predicted frame: only then are ADE and FDE given. */
  covered: boolean;
  best?: { rootRelative: Errors; world: Errors };
  /** Best-of-K mean per-joint error in cm (root-relative), each minimised on its own. */
  bestPerJointCm?: Errors;
  apd: number;
  /** Pose spread between the samples in cm: averaged over the frames, and at the last frame. */
  spreadCm: { overFrames: number; last: number };
  samples: SampleNumbers[];
}

/** Metres below the floor a foot may reach before it counts (export/ops/floor.py's contact band). */
export const FOOT_DEPTH = 0.03;

const min = (a: Float64Array) => a.reduce((m, v) => Math.min(m, v), Infinity);

/**
 * `history` [n, J, 3] and `truth` [frames after the history that the clip holds, J, 3] in the world
 * frame (the same frame as `p.futures`); `truth` may be longer than the futures (it is cut to them)
 * or shorter (no ADE/FDE then).
 */
export function stageReadout(p: Prediction, history: Float32Array, truth: Float32Array | null, skeleton: Skeleton): StageReadout {
  const J = p.joints;
  const pose = J * 3;
  const truthFrames = truth ? Math.floor(truth.length / pose) : 0;
  const covered = truthFrames >= p.frames && p.frames > 0;
  const reference = meanBoneLengths(history, skeleton);
  const samples: SampleNumbers[] = [];
  let rel: { ade: Float64Array; fde: Float64Array } | null = null;
  let wor: { ade: Float64Array; fde: Float64Array } | null = null;
  let cm: { ade: Float64Array; fde: Float64Array } | null = null;
  if (covered) {
    const cut = truth!.subarray(0, p.frames * pose);
    rel = adeFdePerSample(p.futures, p.k, cut, J, true);
    wor = adeFdePerSample(p.futures, p.k, cut, J, false);
    cm = mpjpeCmPerSample(p.futures, p.k, cut, J, true);
  }
  for (let i = 0; i < p.k; i++) {
    const length = Math.max(1, Math.min(p.lengths[i], p.frames));
    const own = p.futures.subarray(i * p.frames * pose, (i * p.frames + length) * pose);
    samples.push({
      rootRelative: rel ? { ade: rel.ade[i], fde: rel.fde[i] } : undefined,
      world: wor ? { ade: wor.ade[i], fde: wor.fde[i] } : undefined,
      boneLengthError: boneLengthError(own, reference, skeleton),
      footBelowFloor: footBelowFloor(own, skeleton, FOOT_DEPTH),
      perJointCm: cm ? { ade: cm.ade[i], fde: cm.fde[i] } : undefined,
    });
  }
  return {
    k: p.k, frames: p.frames, truthFrames, covered,
    best: rel && wor ? { rootRelative: { ade: min(rel.ade), fde: min(rel.fde) }, world: { ade: min(wor.ade), fde: min(wor.fde) } } : undefined,
    bestPerJointCm: cm ? { ade: min(cm.ade), fde: min(cm.fde) } : undefined,
    apd: apd(worldPoses(p.futures, J), p.k),
    spreadCm: poseSpreadCm(p.futures, p.k, J),
    samples,
  };
}

/** The read-out on the clip's frames after the history (`after`: any number of them, or none), cut to
 *  the predicted frames as the stage shows them; the worker and a replay on the page both call it. */
export function readoutAfter(p: Prediction, history: Float32Array, after: Float32Array | null, skeleton: Skeleton): StageReadout {
  const pose = p.joints * 3;
  const frames = after ? Math.min(Math.floor(after.length / pose), p.frames) : 0;
  return stageReadout(p, history, frames > 0 ? after!.subarray(0, frames * pose) : null, skeleton);
}

/** What "Copy numbers" puts on the clipboard: the read-out with what it was computed on. */
export function readoutJson(r: StageReadout, about: Record<string, unknown>): string {
  const round = (v: number | undefined) => (v === undefined ? undefined : Number(v.toPrecision(6)));
  const errors = (e?: Errors) => (e ? { ade: round(e.ade), fde: round(e.fde) } : undefined);
  return JSON.stringify({
    ...about,
    units: 'cm (per-joint error, pose spread); metres (ADE, FDE, APD: the field\'s whole-pose L2); shares 0-1 (bone-length error, feet below floor)',
    definitions: 'export/eval/realism/mpjpe.py: per-joint error = mean over frames and joints of the per-joint distance '
      + '(root-relative, cm), best of K; pose spread = mean over sample pairs of the mean per-joint distance (cm). '
      + 'export/eval/metrics.py: ADE/FDE whole-pose L2 (WAT Eq. 12, DLow), best of K each on its own, about sqrt(18) = 4.2 '
      + 'times the per-joint mean; APD (DLow) on root-relative poses, at least sqrt(18 x frames) times the pose spread; bone-length error against the history\'s mean bone lengths; '
      + `feet more than ${FOOT_DEPTH} m below the floor`,
    k: r.k, frames: r.frames, truth_frames: r.truthFrames, ground_truth_covers_futures: r.covered,
    per_joint_cm_best_of_k: r.bestPerJointCm ? errors(r.bestPerJointCm) : null,
    pose_spread_cm: { over_frames: round(r.spreadCm.overFrames), last: round(r.spreadCm.last) },
    best_of_k: r.best ? { root_relative: errors(r.best.rootRelative), world: errors(r.best.world) } : null,
    apd_root_relative: round(r.apd),
    samples: r.samples.map((s, i) => ({
      sample: i + 1, per_joint_cm: errors(s.perJointCm) ?? null, root_relative: errors(s.rootRelative) ?? null, world: errors(s.world) ?? null,
      bone_length_error: round(s.boneLengthError), foot_below_floor: round(s.footBelowFloor),
    })),
  }, null, 2);
}
