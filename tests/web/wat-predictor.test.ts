// The served WAT model run by the TypeScript predictor in Node: an action sequence from a test
// history, per-sample stops, and clear messages for bad input.
import { describe, expect, it } from 'vitest';
import { loadManifest, nodePredictor } from './helpers/models';
import { readVector } from './helpers/vectors';
import { readFileSync } from 'node:fs';
import { PredictError } from '../../web/src/predictor/types';
import { firstStop } from '../../web/src/sampling/variance-stop';
import type { WatParams } from '../../web/src/predictor/wat';

const manifest = loadManifest();
const found = manifest.models.find((m) => m.method === 'wat');
if (!found) throw new Error('public/models/manifest.json serves no WAT model: run `python -m export models --only wat-rnn`');
const entry = found;
const J = manifest.skeleton.joints.length;
const clip = JSON.parse(readFileSync(new URL('../../public/clips/cmu_10_04.json', import.meta.url), 'utf8')) as { positions: number[][][] };
const history = (frames: number, start = 3) => ({
  positions: Float32Array.from(clip.positions.slice(start, start + frames).flat(2)), frames, joints: J,
});

describe('WAT predictor (TypeScript, served model)', () => {
  const p = nodePredictor(manifest, entry.id);
  const params = entry.params as unknown as WatParams;

  it('predicts K = 10 futures for a 3-action sequence from a test history', async () => {
    const pred = await p.predict(history(10), { k: 10, seed: 1, actions: ['walk', 'punch', 'jump'] });
    const { min_frames: tMin, delta } = params.stop;
    const tMax = params.future_frames;
    expect(pred.k).toBe(10);
    expect(pred.frames).toBe(Math.max(...pred.lengths));
    expect(pred.futures.length).toBe(10 * pred.frames * J * 3);
    expect(pred.futures.every(Number.isFinite)).toBe(true);
    for (const [i, s] of pred.samples.entries()) {
      expect(s.segments.map((g) => g.action)).toEqual(['walk', 'punch', 'jump']);
      expect(s.length).toBe(pred.lengths[i]);
      expect(s.segments.reduce((c, g) => c + g.length, 0)).toBe(s.length);
      for (const g of s.segments) {
        expect(g.length).toBeGreaterThanOrEqual(tMin);
        expect(g.length).toBeLessThanOrEqual(tMax);
        expect(g.stopped).toBe(g.length < tMax);
        expect(g.flagged).toBe(g.smoothness! > params.smoothness.flag_threshold);
      }
      // the plotted curve is the one the stop rule saw: the first segment stops where it says
      const series = pred.curves![0].series[i];
      const first = s.segments[0];
      if (first.stopped) expect(firstStop(series, delta, tMin, tMax).length).toBe(first.length);
    }
    expect(pred.curves![0].levels![0].value).toBe(delta);
  });

  // The e2e vector checks lengths and positions (e2e-vector.test.ts); here the segments too.
  const vector = readVector<{
    cases: { model: string; clip: string; start: number; history: number[][][]; request: { k: number; seed: number; actions: string[] };
      segments: { start: number; length: number; action: string; stopped: boolean }[][] }[];
  }>('e2e');
  const cases = vector.cases.filter((c) => c.model === entry.id);
  it('the end-to-end vector has WAT cases', () => { expect(cases.length).toBeGreaterThan(0); });
  for (const c of cases) {
    it(`segments of ${c.clip}@${c.start} (${c.request.actions.join(' -> ')}) match Python exactly`, async () => {
      const pred = await p.predict({ positions: Float32Array.from(c.history.flat(2)), frames: c.history.length, joints: J },
        { k: c.request.k, seed: c.request.seed, actions: c.request.actions });
      expect(pred.samples.map((s) => s.segments.map(({ start, length, action, stopped }) => ({ start, length, action, stopped }))))
        .toEqual(c.segments);
    });
  }

  it('the prior temperature 0 decodes the prior mean for every sample, and the default is the manifest\'s', async () => {
    const spec = entry.controls.find((c) => c.id === 'temperature')!;
    expect(spec.min).toBe(0);
    const mean = await p.predict(history(10), { k: 3, seed: 4, actions: ['walk'], controls: { temperature: 0 } });
    const n = mean.frames * J * 3;
    for (let i = 1; i < 3; i++) expect(mean.futures.subarray(i * n, (i + 1) * n)).toEqual(mean.futures.subarray(0, n));
    const byDefault = await p.predict(history(10), { k: 3, seed: 4, actions: ['walk'] });
    const explicit = await p.predict(history(10), { k: 3, seed: 4, actions: ['walk'], controls: { temperature: spec.default as number } });
    expect(explicit.futures).toEqual(byDefault.futures);
    expect(byDefault.futures).not.toEqual(mean.futures);
  });

  it.each([
    [history(10), { k: 2, seed: 0, actions: ['walk'], controls: { temperature: 4.5 } }, /Prior temperature must be between 0 and 4, got 4.5/],
    [history(10), { k: 2, seed: 0, actions: ['moonwalk'] }, /unknown action 'moonwalk'/],
    [history(10), { k: 0, seed: 0, actions: ['walk'] }, /K must be an integer from 1 to 50, got 0/],
    [history(10), { k: 51, seed: 0, actions: ['walk'] }, /K must be an integer from 1 to 50, got 51/],
    [history(10), { k: 2, seed: 0, actions: [] }, /the action sequence is empty/],
    [history(6), { k: 2, seed: 0, actions: ['walk'] }, /history has 6 frames; this model needs at least 10/],
    [history(10), { k: 2, seed: 0, actions: Array(6).fill('walk') }, /at most 5 are allowed/],
  ])('bad input %# gives a PredictError with a clear message', async (h, req, message) => {
    await expect(p.predict(h, req)).rejects.toThrow(PredictError);
    await expect(p.predict(h, req)).rejects.toThrow(message);
  });
});
