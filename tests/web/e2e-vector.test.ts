// The shared end-to-end vector: the TypeScript predictors, run in Node on the committed ONNX
// files, reproduce what the Python predictor wrote.
import { describe, expect, it } from 'vitest';
import { loadManifest, nodePredictor } from './helpers/models';
import { readVector, tolerance, worstDiff } from './helpers/vectors';

interface Case {
  model: string; model_hash: string; clip: string; start: number; history: number[][][];
  request: { k: number; seed: number; actions: string[]; horizon_frames?: number; controls: Record<string, number | boolean> };
  lengths: number[]; warnings: string[]; cuts: (number | null)[]; futures: number[][][][];
}
const vector = readVector<{ cases: Case[] }>('e2e');
const manifest = loadManifest();

describe('end-to-end vector (Python predictor -> TypeScript predictor)', () => {
  it('covers every served model', () => {
    expect(new Set(vector.cases.map((c) => c.model))).toEqual(new Set(manifest.models.map((m) => m.id)));
  });

  for (const c of vector.cases) {
    it(`${c.model} on ${c.clip}@${c.start}: lengths exactly, positions within the model's tolerance`, async () => {
      const entry = manifest.models.find((m) => m.id === c.model)!;
      expect(entry.hash).toBe(c.model_hash); // the vector was written for these models
      const history = Float32Array.from(c.history.flat(2));
      const pred = await nodePredictor(manifest, c.model).predict(
        { positions: history, frames: c.history.length, joints: manifest.skeleton.joints.length },
        { k: c.request.k, seed: c.request.seed, actions: c.request.actions, horizonFrames: c.request.horizon_frames, controls: c.request.controls },
      );
      expect(Array.from(pred.lengths)).toEqual(c.lengths);
      expect((pred.warnings ?? []).map((w) => w.quantity)).toEqual(c.warnings);
      expect(pred.samples.map((s) => s.cut?.frame ?? null)).toEqual(c.cuts);
      expect(worstDiff(pred.futures, c.futures.flat(3))).toBeLessThanOrEqual(tolerance(vector, c.model));
    });
  }
});
