// "What is shown": the history, the futures on stage (all K, or the selected one) and the ground truth
// that follows the history in the clip (as far as the futures go), as plain arrays on the project
// skeleton. The exporters (glb.ts, clip-json.ts, csv.ts) take only this; each writes the truth as a
// figure of its own, named "ground_truth".
import type { Skeleton } from '../contract/types';
import type { Motion } from '../motion/clip';
import type { Prediction } from '../predictor/types';

export interface ShownFuture {
  /** 0-based sample index in the prediction (shown as #sample+1). */
  sample: number;
  frames: number;
  /** [frames, joints, 3] metres; frame 0 follows the last history frame. */
  positions: Float32Array;
}

export interface Shown {
  /** The history's clip (or dropped file) name; a contract name. */
  name: string;
  fps: number;
  skeleton: Skeleton;
  joints: number;
  /** First history frame in the clip. */
  start: number;
  history: { frames: number; positions: Float32Array };
  futures: ShownFuture[];
  /** What the clip really does after the history, as far as the longest future (none when the clip
   *  ends with the history): frame 0 follows the last history frame. */
  truth?: { frames: number; positions: Float32Array };
  model?: string;
}

/** The ground truth's figure name in every export. */
export const TRUTH_FIGURE = 'ground_truth';

/** The Shown of a prediction from frames [start, start + historyFrames) of `m`: every sample up
 *  to its own length, or only `selected` when a sample is selected. */
export function shownFromPrediction(
  m: Motion, start: number, historyFrames: number, p: Prediction,
  options: { selected?: number | null; model?: string; truth?: boolean } = {},
): Shown {
  const stride = p.joints * 3;
  const samples = options.selected !== undefined && options.selected !== null ? [options.selected] : [...Array(p.k).keys()];
  // as on stage (ui/predict-controller.ts predictionTracks): the clip's next frames, up to the longest sample
  const truthFrames = Math.min(m.frames - start - historyFrames, Math.max(0, ...p.lengths));
  const from = (start + historyFrames) * stride;
  return {
    name: m.name, fps: m.fps, skeleton: { joints: m.skeleton.joints, parents: m.skeleton.parents }, joints: p.joints, start,
    history: { frames: historyFrames, positions: m.positions.slice(start * stride, (start + historyFrames) * stride) },
    futures: samples.map((i) => ({
      sample: i, frames: p.lengths[i], positions: p.futures.slice(i * p.frames * stride, (i * p.frames + p.lengths[i]) * stride),
    })),
    ...(options.truth !== false && truthFrames > 0
      ? { truth: { frames: truthFrames, positions: m.positions.slice(from, from + truthFrames * stride) } } : {}),
    model: options.model,
  };
}

/** A figure's name in every export: "history" or "sample_<n>" (1-based, as the page shows it). */
export function figureName(sample: number | null): string {
  return sample === null ? 'history' : `sample_${sample + 1}`;
}

/** Shortest decimal that reads back as the same float32 (the contract's number format). */
export function float32Text(v: number): string {
  const f = Math.fround(v);
  if (f === 0) return '0';
  for (let p = 1; p < 10; p++) {
    const s = f.toPrecision(p);
    if (Math.fround(Number(s)) === f) return String(Number(s));
  }
  return String(f);
}

/** Check a Shown before exporting it; throws an Error naming the problem. */
export function checkShown(s: Shown): void {
  const n = s.joints * 3;
  if (s.skeleton.joints.length !== s.joints) throw new Error(`export: ${s.joints} joints but the skeleton has ${s.skeleton.joints.length}`);
  if (s.history.positions.length !== s.history.frames * n || s.history.frames < 1) throw new Error('export: the history has the wrong size');
  if (!s.futures.length) throw new Error('export: there is no future to export; predict first');
  for (const f of s.futures) {
    if (f.positions.length !== f.frames * n || f.frames < 1) throw new Error(`export: future #${f.sample + 1} has the wrong size`);
  }
  if (s.truth && (s.truth.positions.length !== s.truth.frames * n || s.truth.frames < 1)) throw new Error('export: the ground truth has the wrong size');
  for (const arr of [s.history.positions, ...s.futures.map((f) => f.positions), ...(s.truth ? [s.truth.positions] : [])]) {
    for (const v of arr) if (!Number.isFinite(v)) throw new Error('export: a position is not a finite number');
  }
}
