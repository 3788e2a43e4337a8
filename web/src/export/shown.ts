// "What is shown": the history, the futures on stage (all K, or the selected one) of every model on
// stage (one, or each compared one: ui/compare.ts) and the ground truth that follows the history in
// the clip (as far as the futures go), as plain arrays on the project skeleton. The exporters
// (glb.ts, clip-json.ts, csv.ts) take only this; each writes the truth once, as a figure of its own
// named "ground_truth", and each future's figure names its model when several are shown.
import type { Skeleton } from '../contract/types';
import type { Motion } from '../motion/clip';
import type { Prediction } from '../predictor/types';

/** One model's prediction as its export records it: enough to make it again. */
export interface ShownRun {
  /** The model's id (a contract name). */
  model?: string;
  /** The manifest's hash of the model's files. */
  hash?: string;
  /** The model's short name as the stage labels it ("WAT (RNN)"). */
  label?: string;
  /** This model's own history: frames [start, start + historyFrames) of the clip; every run's ends
   *  where the shown history ends. */
  start: number;
  historyFrames: number;
  seed?: number;
  controls?: Record<string, number | boolean | string[]>;
  /** False: the method's own root travel (predictor/foot-plant.ts did not plant the feet). */
  plantFeet?: boolean;
}

export interface ShownFuture {
  /** 0-based sample index in its prediction (shown as #sample+1). */
  sample: number;
  /** Index of its model in Shown.runs. */
  run: number;
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
  /** First history frame in the clip: the longest of the runs' histories (they all end together). */
  start: number;
  history: { frames: number; positions: Float32Array };
  /** The models whose futures these are, in the stage's row order (the page's model first). */
  runs: ShownRun[];
  futures: ShownFuture[];
  /** The sample selected on stage (its future alone, of each model that has it), or null: all. */
  selected?: number | null;
  /** What the clip really does after the history, as far as the longest future (none when the clip
   *  ends with the history): frame 0 follows the last history frame. */
  truth?: { frames: number; positions: Float32Array };
}

/** A run with its prediction: what shownFromRuns takes. */
export interface RunPrediction extends ShownRun {
  prediction: Prediction;
}

/** The ground truth's figure name in every export. */
export const TRUTH_FIGURE = 'ground_truth';

/** The Shown of one or more predictions from the same history end of `m` (one model, or compare
 *  mode's rows): every sample up to its own length, or only sample `selected` of each run that has
 *  it, as the stage selects it in every row. */
export function shownFromRuns(m: Motion, runs: readonly RunPrediction[], options: { selected?: number | null; truth?: boolean } = {}): Shown {
  if (!runs.length) throw new Error('export: there is no prediction to export; predict first');
  const end = runs[0].start + runs[0].historyFrames;
  for (const r of runs) {
    if (r.start + r.historyFrames !== end) throw new Error(`export: ${r.model ?? 'a model'}'s history ends at frame ${r.start + r.historyFrames}, not ${end} like the others'`);
    if (r.prediction.joints !== m.joints) throw new Error(`export: ${r.model ?? 'a model'} predicts ${r.prediction.joints} joints, the clip has ${m.joints}`);
  }
  if (runs.length > 1 && new Set(runs.map((r) => r.model)).size !== runs.length) throw new Error('export: each compared model needs its own id');
  const start = Math.min(...runs.map((r) => r.start));
  const stride = m.joints * 3;
  const selected = options.selected ?? null;
  const futures: ShownFuture[] = runs.flatMap(({ prediction: p }, run) => {
    const samples = selected !== null ? (selected < p.k ? [selected] : []) : [...Array(p.k).keys()];
    return samples.map((i) => ({
      sample: i, run, frames: p.lengths[i], positions: p.futures.slice(i * p.frames * stride, (i * p.frames + p.lengths[i]) * stride),
    }));
  });
  // as on stage (ui/predict-controller.ts, ui/compare.ts): the clip's next frames, up to the longest future
  const truthFrames = Math.min(m.frames - end, Math.max(0, ...runs.flatMap((r) => [...r.prediction.lengths])));
  return {
    name: m.name, fps: m.fps, skeleton: { joints: m.skeleton.joints, parents: m.skeleton.parents }, joints: m.joints, start,
    history: { frames: end - start, positions: m.positions.slice(start * stride, end * stride) },
    runs: runs.map(({ prediction: _, ...run }) => run),
    futures,
    selected,
    ...(options.truth !== false && truthFrames > 0
      ? { truth: { frames: truthFrames, positions: m.positions.slice(end * stride, (end + truthFrames) * stride) } } : {}),
  };
}

/** A figure's name in every export: "history" or "sample_<n>" (1-based, as the page shows it). */
export function figureName(sample: number | null): string {
  return sample === null ? 'history' : `sample_${sample + 1}`;
}

/** A future's figure name: "sample_<n>", or "<model>_sample_<n>" when the export holds several models
 *  ("_", not ".": glTF loaders turn a dot in a node name into an underscore). */
export function futureName(s: Shown, f: ShownFuture): string {
  return s.runs.length > 1 ? `${s.runs[f.run].model}_${figureName(f.sample)}` : figureName(f.sample);
}

/** The models of an export, as its file name and titles join them ("wat-rnn", "wat-rnn+lcp-vae"). */
export function modelsText(s: Shown): string {
  return s.runs.map((r) => r.model).filter(Boolean).join('+');
}

/** A run as the JSON and GLB exports record it (snake case, as the read-out's JSON): the model, its
 *  history, seed, controls and whether the feet were planted, so the futures can be made again. */
export function runRecord(r: ShownRun): Record<string, unknown> {
  return {
    ...(r.model ? { model: r.model } : {}), ...(r.hash ? { model_hash: r.hash } : {}), ...(r.label ? { model_label: r.label } : {}),
    history_start: r.start, history_frames: r.historyFrames,
    ...(r.seed !== undefined ? { seed: r.seed } : {}), ...(r.controls ? { controls: r.controls } : {}),
    ...(r.plantFeet !== undefined ? { plant_feet: r.plantFeet } : {}),
  };
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
  if (!s.runs.length) throw new Error('export: the export names no model run');
  for (const f of s.futures) {
    if (!s.runs[f.run]) throw new Error(`export: future #${f.sample + 1} names model run ${f.run}, of ${s.runs.length}`);
    if (f.positions.length !== f.frames * n || f.frames < 1) throw new Error(`export: future #${f.sample + 1} has the wrong size`);
  }
  if (s.truth && (s.truth.positions.length !== s.truth.frames * n || s.truth.frames < 1)) throw new Error('export: the ground truth has the wrong size');
  for (const arr of [s.history.positions, ...s.futures.map((f) => f.positions), ...(s.truth ? [s.truth.positions] : [])]) {
    for (const v of arr) if (!Number.isFinite(v)) throw new Error('export: a position is not a finite number');
  }
}
