// A dropped BVH, predicted from in Node with a served model: the "what is shown" the export tests use.
import { readFileSync } from 'node:fs';
import type { ClipIndex } from '../../../web/src/contract/types';
import { shownFromRuns, type Shown } from '../../../web/src/export/shown';
import { importBvh, type ImportedMotion } from '../../../web/src/motion/bvh';
import { window as clipWindow } from '../../../web/src/motion/clip';
import type { Prediction } from '../../../web/src/predictor/types';
import { loadManifest, nodePredictor } from './models';

const root = new URL('../../../', import.meta.url);
export const skeleton = (JSON.parse(readFileSync(new URL('public/clips/index.json', root), 'utf8')) as ClipIndex).skeleton;

export function droppedWalk(): ImportedMotion {
  return importBvh(readFileSync(new URL('tests/fixtures/walk.bvh', root), 'utf8'), 'walk.bvh', { skeleton });
}

/** The regression model's future from frames [start, start + 10) of the dropped walk. */
export async function predictFromDropped(m: ImportedMotion, start: number, model = 'regression-gru'): Promise<{ prediction: Prediction; n: number }> {
  const manifest = loadManifest();
  const entry = manifest.models.find((e) => e.id === model)!;
  const n = entry.params.history_frames;
  const prediction = await nodePredictor(manifest, model).predict(
    { positions: clipWindow(m, start, n), frames: n, joints: m.joints }, { k: 1, seed: 1, horizonFrames: 45 });
  return { prediction, n };
}

/** A K-sample Shown: the model's future plus copies bent by known offsets and cut to other lengths. */
export async function shownWithSamples(k: number, selected: number | null = null): Promise<Shown> {
  const m = droppedWalk();
  const { prediction: p, n } = await predictFromDropped(m, 12);
  const stride = p.joints * 3;
  const futures = new Float32Array(k * p.frames * stride);
  for (let i = 0; i < k; i++) {
    for (let v = 0; v < p.frames * stride; v++) futures[i * p.frames * stride + v] = p.futures[v] + (v % 3 === 0 ? 0.05 * i : 0);
  }
  const lengths = Int32Array.from({ length: k }, (_, i) => p.frames - 7 * i);
  const multi: Prediction = { ...p, k, futures, lengths, samples: Array.from({ length: k }, (_, i) => ({ length: lengths[i], stopped: true, segments: [] })) };
  return shownFromRuns(m, [{ model: 'regression-gru', start: 12, historyFrames: n, prediction: multi }], { selected });
}
