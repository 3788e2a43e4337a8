// Export what is shown as clip documents of the contract (contract/clip.schema.json): one clip per
// future, each the history followed by that future, so it plays as one continuous motion, and after
// them the ground truth the same way (name "<clip>.ground_truth", action "ground truth"). Several
// models (compare mode): each future's clip is named after its model ("<clip>.<model>_sample_<n>"),
// all start with the same (longest) history, and the truth comes once. Each prediction's source
// records its run (model, its own history, seed, controls, plant_feet) so it can be made again.
// One clip document alone -> that document; several -> a JSON array of clip documents.
import type { ClipDoc } from '../contract/types';
import { validate } from '../contract/validate';
import { checkShown, float32Text, futureName, runRecord, TRUTH_FIGURE, type Shown, type ShownRun } from './shown';

export function clipDocuments(s: Shown): ClipDoc[] {
  checkShown(s);
  const J = s.joints;
  const frame = (arr: Float32Array, f: number) =>
    Array.from({ length: J }, (_, j) => [0, 1, 2].map((c) => Number(float32Text(arr[(f * J + j) * 3 + c])))) as number[][];
  const figures = [
    ...s.futures.map((fut) => ({ name: futureName(s, fut), sample: fut.sample as number | null, run: s.runs[fut.run] as ShownRun | null,
      frames: fut.frames, positions: fut.positions })),
    ...(s.truth ? [{ name: TRUTH_FIGURE, sample: null, run: null, frames: s.truth.frames, positions: s.truth.positions }] : []),
  ];
  return figures.map((fig) => {
    const frames = s.history.frames + fig.frames;
    const positions: number[][][] = [];
    for (let f = 0; f < s.history.frames; f++) positions.push(frame(s.history.positions, f));
    for (let f = 0; f < fig.frames; f++) positions.push(frame(fig.positions, f));
    const truth = fig.sample === null;
    const doc: ClipDoc = {
      format: 'motion-futures/clip', version: 2, name: `${s.name}.${fig.name}`, action: truth ? 'ground truth' : 'prediction', fps: s.fps,
      loops: false, skeleton: { joints: s.skeleton.joints, parents: s.skeleton.parents },
      split: { role: 'test', train: [], test: [[s.history.frames, frames]] },
      source: {
        dataset: truth ? 'motion-futures ground truth' : 'motion-futures prediction', file: s.name,
        ...(fig.run?.model ? { model: fig.run.model } : {}), ...(truth ? {} : { sample: fig.sample! + 1 }),
        start: s.start, history_frames: s.history.frames,
        ...(fig.run ? { run: runRecord(fig.run) } : {}),
      } as ClipDoc['source'],
      positions,
    };
    return validate(doc, 'clip', doc.name);
  });
}

/** The JSON text of the export; numbers are shortest float32 decimals like the committed clips. */
export function clipJson(s: Shown): string {
  const docs = clipDocuments(s);
  const text = docs.map((d) => JSON.stringify(d));
  return (docs.length === 1 ? text[0] : `[\n${text.join(',\n')}\n]`) + '\n';
}
