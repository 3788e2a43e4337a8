// The sample closest to the ground truth on stage, by the evaluation's per-joint error
// (web/src/metrics/realism.ts mpjpeCmPerSample): the mean over the truth's frames and the joints of
// the distance between the sample's joint and the truth's, in the world frame (what the overlaid
// figures show). A sample shorter than the truth holds its last pose, as the evaluation pads it.
import { mpjpeCmPerSample } from '../metrics/realism';
import type { Track } from './tracks';

export interface BestSample {
  sample: number;
  /** Its mean per-joint error (cm). */
  cm: number;
  /** Every sample's error (cm), in the order of the prediction tracks. */
  errors: { sample: number; cm: number }[];
  /** The ground-truth frames compared (the truth may end before the futures do). */
  frames: number;
  /** Compare mode: the method's row (track.group) and its name. */
  group?: number;
  groupLabel?: string;
}

/** The best prediction sample among `tracks`, or null without a ground-truth track or a sample. A tie
 *  goes to the lower sample number. */
export function bestSample(tracks: readonly Track[]): BestSample | null {
  const truth = tracks.find((t) => t.role === 'truth');
  const samples = tracks.filter((t) => t.role === 'prediction' && t.sample !== undefined && t.frames > 0);
  if (!truth || truth.frames < 1 || !samples.length) return null;
  const J = truth.joints;
  const pose = J * 3;
  const T = truth.frames;
  const futures = new Float32Array(samples.length * T * pose);
  samples.forEach((s, i) => {
    if (s.joints !== J) throw new Error(`best sample: track ${s.id} has ${s.joints} joints, the truth ${J}`);
    const own = Math.min(s.frames, T);
    futures.set(s.positions.subarray(0, own * pose), i * T * pose);
    const last = s.positions.subarray((s.frames - 1) * pose, s.frames * pose);
    for (let f = own; f < T; f++) futures.set(last, (i * T + f) * pose);
  });
  const { ade } = mpjpeCmPerSample(futures, samples.length, truth.positions.subarray(0, T * pose), J, false);
  const errors = samples.map((s, i) => ({ sample: s.sample!, cm: ade[i] }));
  let best = errors[0];
  for (const e of errors) if (e.cm < best.cm || (e.cm === best.cm && e.sample < best.sample)) best = e;
  return { sample: best.sample, cm: best.cm, errors, frames: T };
}

/** Compare mode: the best sample of each method's row (track.group; a prediction alone is row 0),
 *  each against its own row's truth, in row order. A row without a truth or a sample has none, and a
 *  row whose tracks do not fit its truth has none either: the other rows keep theirs. */
export function bestPerRow(tracks: readonly Track[]): BestSample[] {
  const rows = [...new Set(tracks.map((t) => t.group ?? 0))].sort((a, b) => a - b);
  return rows.flatMap((group) => {
    const own = tracks.filter((t) => (t.group ?? 0) === group);
    let best: BestSample | null;
    try {
      best = bestSample(own);
    } catch {
      best = null; // a track that does not fit the truth: no highlight in this row, the figures still draw
    }
    const label = own.find((t) => t.groupLabel)?.groupLabel;
    return best ? [{ ...best, group, ...(label ? { groupLabel: label } : {}) }] : [];
  });
}
