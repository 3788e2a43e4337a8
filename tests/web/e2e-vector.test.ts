// The shared end-to-end vector: the TypeScript predictors, run in Node on the committed ONNX
// files, reproduce what the Python predictor wrote.
import { describe, expect, it } from 'vitest';
import { readFileSync } from 'node:fs';
import { loadManifest, nodePredictor } from './helpers/models';

interface Case {
  model: string; model_hash: string; clip: string; start: number; history: number[][][];
  request: { k: number; seed: number; actions: string[]; horizon_frames?: number; controls: Record<string, number | boolean> };
  lengths: number[]; futures: number[][][][];
}
const vector = JSON.parse(readFileSync(new URL('../../contract/vectors/e2e.json', import.meta.url), 'utf8')) as { cases: Case[] };
const manifest = loadManifest();

describe('end-to-end vector (Python predictor -> TypeScript predictor)', () => {
  it('covers every served model', () => {
    expect(new Set(vector.cases.map((c) => c.model))).toEqual(new Set(manifest.models.map((m) => m.id)));
  });

  for (const c of vector.cases) {
    it(`${c.model} on ${c.clip}@${c.start}: lengths exactly, positions to 1e-4`, async () => {
      const entry = manifest.models.find((m) => m.id === c.model)!;
      expect(entry.hash).toBe(c.model_hash); // the vector was written for these models
      const history = Float32Array.from(c.history.flat(2));
      const pred = await nodePredictor(manifest, c.model).predict(
        { positions: history, frames: c.history.length, joints: manifest.skeleton.joints.length },
        { k: c.request.k, seed: c.request.seed, actions: c.request.actions, horizonFrames: c.request.horizon_frames, controls: c.request.controls },
      );
      expect(Array.from(pred.lengths)).toEqual(c.lengths);
      const want = c.futures.flat(3);
      expect(pred.futures.length).toBe(want.length);
      let worst = 0;
      want.forEach((v, i) => { worst = Math.max(worst, Math.abs(pred.futures[i] - v)); });
      expect(worst).toBeLessThan(1e-4);
    });
  }
});
