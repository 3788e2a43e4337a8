// The Keyposes predictor in Node on the committed model: reproduces the Python end-to-end cases,
// samples differing label sequences, joins the history without a jump, and rejects bad input
// with clear messages.
import { describe, expect, it } from 'vitest';
import { readFileSync } from 'node:fs';
import * as ort from 'onnxruntime-web';
import type { Manifest } from '../../web/src/contract/types';
import { KeyposesPredictor } from '../../web/src/predictor/keyposes';
import { OrtRunner, type OrtModule } from '../../web/src/predictor/ort-runner';
import { PredictError, type History } from '../../web/src/predictor/types';
import { PACE_RANGE, pace, travel } from '../../web/src/sampling/keyposes';
import { loadManifest, nodePredictor } from './helpers/models';
import { readVector, tolerance, worstDiff } from './helpers/vectors';

const modelsDir = new URL('../../public/models/', import.meta.url);
const manifest: Manifest = loadManifest();
const entry = manifest.models.find((m) => m.method === 'keyposes');
const J = manifest.skeleton.joints.length;
const readModelFile = async (file: string) => new Uint8Array(readFileSync(new URL(file, modelsDir)));

function predictor(loadFile = readModelFile) {
  const runner = new OrtRunner(ort as unknown as OrtModule, entry!, readModelFile);
  return new KeyposesPredictor({ entry: entry!, skeleton: manifest.skeleton, actions: manifest.actions, fps: manifest.fps, runner, loadFile });
}

function clipHistory(name: string, start: number, frames: number): History {
  const doc = JSON.parse(readFileSync(new URL(`../../public/clips/${name}.json`, import.meta.url), 'utf8')) as { positions: number[][][] };
  return { positions: Float32Array.from(doc.positions.slice(start, start + frames).flat(2)), frames, joints: J };
}

interface Case {
  model: string; model_hash: string; clip: string; start: number; history: number[][][];
  request: { k: number; seed: number; horizon_frames?: number; controls: Record<string, number | boolean> };
  lengths: number[]; labels: number[][]; marks: number[][]; futures: number[][][][];
}
const e2e = readVector<{ cases: Case[] }>('e2e');

describe.runIf(entry)('Keyposes predictor (TypeScript, committed model)', () => {
  const cases = e2e.cases.filter((c) => c.model === entry?.id);

  it('has end-to-end cases for this model', () => {
    expect(cases.length).toBeGreaterThanOrEqual(2);
  });

  // Held-out histories Keyposes accepts (at least 3 keyposes): the e2e cases' own, found by the
  // export's first_accepted_start.
  const acceptedHistory = (i: number) => ({
    positions: Float32Array.from(cases[i].history.flat(2)), frames: cases[i].history.length, joints: J,
  });

  for (const c of cases) {
    it(`${c.clip}@${c.start}: labels and marks exactly, positions within the model's tolerance`, async () => {
      expect(entry!.hash).toBe(c.model_hash);
      // through the whole predictor (createCheckedPredictor): the vector's futures have planted feet
      const pred = await nodePredictor(manifest, entry!.id).predict(
        { positions: Float32Array.from(c.history.flat(2)), frames: c.history.length, joints: J },
        { k: c.request.k, seed: c.request.seed, horizonFrames: c.request.horizon_frames, controls: c.request.controls },
      );
      expect(pred.samples.map((s) => s.labels)).toEqual(c.labels);
      expect(pred.samples.map((s) => s.marks)).toEqual(c.marks);
      expect(Array.from(pred.lengths)).toEqual(c.lengths);
      expect(worstDiff(pred.futures, c.futures.flat(3))).toBeLessThanOrEqual(tolerance(e2e, c.model));
      expect(Math.min(...pred.margins!)).toBeGreaterThanOrEqual(1e-3);
    });
  }

  it('K = 10 futures from a test-split history: differing label sequences, no jump, ghosts at the marks', async () => {
    const n = entry!.params.history_frames;
    const history = acceptedHistory(0);
    const pred = await predictor().predict(history, { k: 10, seed: 3, controls: { temperature: 0.3, refine: true } });
    expect(pred.k).toBe(10);
    expect(pred.frames).toBe(150);
    expect(new Set(pred.samples.map((s) => s.labels!.join(','))).size).toBeGreaterThan(1);
    const s = J * 3;
    const last = history.positions.subarray((n - 1) * s, n * s);
    for (let q = 0; q < 10; q++) {
      let step = 0;
      for (let i = 0; i < s; i += 3) {
        const d = Math.hypot(pred.futures[q * 150 * s + i] - last[i], pred.futures[q * 150 * s + i + 1] - last[i + 1],
          pred.futures[q * 150 * s + i + 2] - last[i + 2]);
        step = Math.max(step, d);
      }
      expect(step).toBeLessThan(0.15); // the first future frame is one interpolation step from the present
      const sample = pred.samples[q];
      expect(sample.marks!.length).toBe(sample.labels!.length);
      expect(pred.ghosts!.frames[q]).toEqual(sample.marks);
      expect(pred.ghosts!.poses[q].length).toBe(sample.marks!.length * s);
    }
  });

  it('the same seed gives the same futures; another seed other ones', async () => {
    const history = acceptedHistory(1);
    const p = predictor();
    const a = await p.predict(history, { k: 4, seed: 11, horizonFrames: 60, controls: { refine: false } });
    const b = await p.predict(history, { k: 4, seed: 11, horizonFrames: 60, controls: { refine: false } });
    const c = await p.predict(history, { k: 4, seed: 12, horizonFrames: 60, controls: { refine: false, temperature: 1.5 } });
    expect(Array.from(b.futures)).toEqual(Array.from(a.futures));
    expect(c.samples.map((x) => x.labels)).not.toEqual(a.samples.map((x) => x.labels));
  });

  it.each([
    [{ temperature: 0 }, /Temperature must be between 0.05 and 1.5, got 0/],
    [{ temperature: -1 }, /Temperature must be between/],
    [{ refine: 1 }, /Refine must be true or false/],
  ])('bad control %o', async (controls, message) => {
    const history = clipHistory('cmu_10_04', 0, entry!.params.history_frames);
    const run = predictor().predict(history, { k: 2, seed: 0, controls: controls as Record<string, number | boolean> });
    await expect(run).rejects.toThrow(PredictError);
    await expect(predictor().predict(history, { k: 2, seed: 0, controls: controls as Record<string, number | boolean> })).rejects.toThrow(message);
  });

  it('a still history (one pose held) is predicted, from that pose, with finite futures', async () => {
    const n = entry!.params.history_frames;
    const still = clipHistory('cmu_10_04', 0, 1);
    const positions = new Float32Array(n * J * 3);
    for (let f = 0; f < n; f++) positions.set(still.positions, f * J * 3);
    const pred = await predictor().predict({ positions, frames: n, joints: J }, { k: 2, seed: 0, horizonFrames: 30 });
    expect(pred.futures.every(Number.isFinite)).toBe(true);
    // the first predicted frame stays near the held pose: mean joint distance under 10 cm
    let d = 0;
    for (let j = 0; j < J; j++) {
      d += Math.hypot(...[0, 1, 2].map((a) => pred.futures[j * 3 + a] - still.positions[j * 3 + a])) / J;
    }
    expect(d).toBeLessThan(0.1);
  });

  it('a history with fewer keyposes than the model needs is rejected with the count and the threshold', async () => {
    // The served model needs 2 (a held pose gives 2 at its ends); a model needing 3 refuses the same history.
    const k = entry!.params.keyposes as { threshold: number; min_observed: number };
    const strict = { ...entry!, params: { ...entry!.params, keyposes: { ...k, min_observed: 3 } } };
    const runner = new OrtRunner(ort as unknown as OrtModule, strict, readModelFile);
    const p = new KeyposesPredictor({ entry: strict, skeleton: manifest.skeleton, actions: manifest.actions, fps: manifest.fps,
      runner, loadFile: readModelFile });
    const n = entry!.params.history_frames;
    const still = clipHistory('cmu_10_04', 0, 1);
    const positions = new Float32Array(n * J * 3);
    for (let f = 0; f < n; f++) positions.set(still.positions, f * J * 3);
    await expect(p.predict({ positions, frames: n, joints: J }, { k: 2, seed: 0 }))
      .rejects.toThrow(new RegExp(`the history yields (1 keypose|2 keyposes) at the ${k.threshold} m threshold; Keyposes needs at least 3`));
  });

  it('a missing centres file names the file', async () => {
    const history = clipHistory('cmu_10_04', 0, entry!.params.history_frames);
    const missing = async (file: string) => { throw new Error(`models/${file} could not be loaded (HTTP 404)`); };
    await expect(predictor(missing).predict(history, { k: 2, seed: 0 })).rejects.toThrow(/keyposes\.centres\.json could not be loaded/);
  });
});

describe('the travel follows the history pace (export/ops/keypose_travel.py pace)', () => {
  const table = [0, 0.03, 0, 0.05, 0, 0];                      // metres per frame, facing frame
  const walk = Float64Array.from({ length: 22 }, (_, i) => (i % 2 ? Math.floor(i / 2) * 0.06 : 0));
  it('scales the table by the history speed over its own labels\' table speed, by hand', () => {
    expect(pace(walk, [0, 1], table)).toBeCloseTo(1.5, 12);
    const path = travel([1, 0], [2, 3], table, 6, 1.5);
    const z = [0.075, 0.15, 0.195, 0.24, 0.285, 0.285];
    z.forEach((v, f) => expect(path[f * 2 + 1]).toBeCloseTo(v, 12));
  });
  it('stops for a standing history, sets no pace for labels that barely travel, caps a racing one', () => {
    expect(pace(new Float64Array(22), [0, 1], table)).toBe(PACE_RANGE[0]);
    expect(pace(walk, [2], table)).toBe(1);
    expect(pace(walk.map((v) => v * 100), [0, 1], table)).toBe(PACE_RANGE[1]);
  });
});
