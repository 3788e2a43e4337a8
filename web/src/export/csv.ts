// Export what is shown as CSV, long format: one row per figure, frame and joint.
//   figure,frame,time,joint,x,y,z
// figure is "history", "sample_<n>" ("<model>_sample_<n>" when several models are shown, in their
// row order) or "ground_truth" (what the clip really does next, once, after the samples); frame counts from the first history frame, so a future's and the truth's rows start at
// the history length; time = frame / fps in seconds; x, y, z in metres, y up.
import { checkShown, figureName, float32Text, futureName, TRUTH_FIGURE, type Shown } from './shown';

export const CSV_HEADER = 'figure,frame,time,joint,x,y,z';

export function csvText(s: Shown): string {
  checkShown(s);
  const rows = [CSV_HEADER];
  const J = s.joints;
  const add = (figure: string, arr: Float32Array, frames: number, first: number) => {
    for (let f = 0; f < frames; f++) {
      const t = float32Text((first + f) / s.fps);
      for (let j = 0; j < J; j++) {
        const o = (f * J + j) * 3;
        rows.push(`${figure},${first + f},${t},${s.skeleton.joints[j]},${float32Text(arr[o])},${float32Text(arr[o + 1])},${float32Text(arr[o + 2])}`);
      }
    }
  };
  add(figureName(null), s.history.positions, s.history.frames, 0);
  for (const fut of s.futures) add(futureName(s, fut), fut.positions, fut.frames, s.history.frames);
  if (s.truth) add(TRUTH_FIGURE, s.truth.positions, s.truth.frames, s.history.frames);
  return rows.join('\n') + '\n';
}
