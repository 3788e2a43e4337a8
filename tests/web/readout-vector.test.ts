// The stage's read-out against the evaluation (contract/vectors/readout.json, export/vectors_readout.py):
// the TypeScript predictor, run in Node on the committed ONNX files with the case's history, request and
// seed, then the read-out (web/src/ui/readout.ts) give the best-of-K and per-sample ADE and FDE (root-
// relative and world frame) that export/eval/metrics.py gave for the Python predictor's futures.
import { describe, expect, it } from 'vitest';
import { stageReadout } from '../../web/src/ui/readout';
import { loadManifest, nodePredictor } from './helpers/models';
import { readVector, tolerance, worstDiff } from './helpers/vectors';

interface Errors { ade: number; fde: number; ade_per_sample: number[]; fde_per_sample: number[] }
interface Case {
  model: string; model_hash: string; clip: string; start: number; horizon_frames: number;
  history: number[][][]; truth: number[][][];
  request: { k: number; seed: number; actions: string[]; horizon_frames?: number; controls: Record<string, number | boolean> };
  lengths: number[]; root_relative: Errors; world: Errors;
}

const vector = readVector<{ cases: Case[] }>('readout');
const e2e = readVector<{ cases: unknown[] }>('e2e');
const manifest = loadManifest();

describe('read-out vector (Python predictor + evaluation -> TypeScript predictor + read-out)', () => {
  for (const c of vector.cases) {
    it(`${c.model} on ${c.clip}@${c.start}, K = ${c.request.k}, seed ${c.request.seed}: lengths exactly, ADE/FDE within tolerance`, async () => {
      const entry = manifest.models.find((m) => m.id === c.model)!;
      expect(entry.hash).toBe(c.model_hash); // the vector was written for these models
      const J = manifest.skeleton.joints.length;
      const history = Float32Array.from(c.history.flat(2));
      const truth = Float32Array.from(c.truth.flat(2));
      const p = await nodePredictor(manifest, c.model).predict(
        { positions: history, frames: c.history.length, joints: J },
        { k: c.request.k, seed: c.request.seed, actions: c.request.actions, horizonFrames: c.request.horizon_frames, controls: c.request.controls },
      );
      expect(Array.from(p.lengths)).toEqual(c.lengths);
      expect(p.frames).toBe(c.horizon_frames);
      const r = stageReadout(p, history, truth, manifest.skeleton);
      expect(r.covered).toBe(true);
      // The futures themselves come from native onnxruntime in Python and from onnxruntime's wasm here:
      // they differ by up to the e2e vector's tolerance for this model (per coordinate), and the
      // read-out's arithmetic adds at most this file's float32-vs-float64 tolerance. A whole-pose
      // distance moves by at most sqrt(3J) ~ 7 times a per-coordinate difference, which the e2e
      // tolerance (30 times the measured per-coordinate gap) still covers at the gaps measured.
      const tol = tolerance(e2e, c.model) + tolerance(vector, c.model);
      for (const [kind, got] of [['root_relative', r.best!.rootRelative], ['world', r.best!.world]] as const) {
        const want = c[kind];
        expect(Math.abs(got.ade - want.ade), `${kind} best-of-K ADE`).toBeLessThanOrEqual(tol);
        expect(Math.abs(got.fde - want.fde), `${kind} best-of-K FDE`).toBeLessThanOrEqual(tol);
        const per = r.samples.map((s) => (kind === 'root_relative' ? s.rootRelative! : s.world!));
        expect(worstDiff(per.map((e) => e.ade), want.ade_per_sample), `${kind} per-sample ADE`).toBeLessThanOrEqual(tol);
        expect(worstDiff(per.map((e) => e.fde), want.fde_per_sample), `${kind} per-sample FDE`).toBeLessThanOrEqual(tol);
      }
    });
  }
});
