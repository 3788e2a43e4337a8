// LCP-VAE in TypeScript: the shared `lcp` vectors (latent sampling for Table 4 rows 2-4, diversity),
// the served model on a test-split history, bad input, and the baselines' decoder condition c.
import { describe, expect, it } from 'vitest';
import { readFileSync } from 'node:fs';
import type { ModelEntry } from '../../web/src/contract/types';
import { LcpVaePredictor, sampleLatents, type LcpParams } from '../../web/src/predictor/lcp-vae';
import { PredictError, type GraphRunner, type Tensor } from '../../web/src/predictor/types';
import { streams } from '../../web/src/rng/prng';
import { diversity } from '../../web/src/sampling/diversity';
import { loadManifest, nodePredictor } from './helpers/models';
import { readVector, tolerance } from './helpers/vectors';

interface SamplingCase {
  params: LcpParams; seed: number; k: number; sigma_scale: number;
  condition: Record<string, number[][]>; z: number[][]; c: number[][] | null;
}
const vector = readVector<{ sampling: SamplingCase[]; diversity: { futures: number[][][][]; diversity: number }[] }>('lcp');
const tol = tolerance(vector);
const e2e = readVector<{
  cases: { model: string; history: number[][][]; request: { k: number; seed: number; horizon_frames?: number; controls: Record<string, number> };
    readouts?: { label: string; value: number }[] }[];
}>('e2e');
const manifest = loadManifest();
const served = manifest.models.filter((m) => m.method === 'lcp_vae');
const J = manifest.skeleton.joints.length;

function tensor(rows: number[][]): Tensor {
  return { data: Float32Array.from(rows.flat()), dims: [rows.length, rows[0].length] };
}

function maxDiff(a: ArrayLike<number>, b: number[]): number {
  expect(a.length).toBe(b.length);
  let worst = 0;
  b.forEach((v, i) => { worst = Math.max(worst, Math.abs(a[i] - v)); });
  return worst;
}

describe('lcp vectors (Python -> TypeScript, within the file\'s tolerance)', () => {
  it.each(vector.sampling.map((c, i) => [i, c] as const))('sampling case %i', (_, c) => {
    const cond = Object.fromEntries(Object.entries(c.condition).map(([k, v]) => [k, tensor(v)]));
    const { z, c: got } = sampleLatents(streams(c.seed, c.k), cond, c.k, c.sigma_scale, c.params);
    expect(maxDiff(z, c.z.flat())).toBeLessThanOrEqual(tol);
    if (c.c === null) expect(got).toBeNull();
    else expect(maxDiff(got!, c.c.flat())).toBeLessThanOrEqual(tol);
  });

  it('diversity (WAT Eq. 10)', () => {
    for (const d of vector.diversity) {
      const k = d.futures.length;
      const frames = d.futures[0].length;
      expect(Math.abs(diversity(Float32Array.from(d.futures.flat(3)), k, frames, J * 3) - d.diversity)).toBeLessThanOrEqual(tol);
    }
  });
});

// A walker test clip (test-only, so every frame is in the test split), first history frames.
function walkerHistory(name: string, start: number, frames: number) {
  const clip = JSON.parse(readFileSync(new URL(`../../public/clips/${name}.json`, import.meta.url), 'utf8')) as { positions: number[][][]; split: { role: string } };
  expect(clip.split.role).toBe('test');
  return { positions: Float32Array.from(clip.positions.slice(start, start + frames).flat(2)), frames, joints: J };
}

it('the site serves an LCP-VAE model', () => {
  expect(served.length).toBeGreaterThan(0);
});

if (served.length) describe('served LCP-VAE model in Node', () => {
  const entry = served[0];
  const n = entry.params.history_frames;
  const p = nodePredictor(manifest, entry.id);

  it('predicts K = 10 futures from a test-split history, with its diversity read-out', async () => {
    const pred = await p.predict(walkerHistory('cmu_61_13', 4, n), { k: 10, seed: 5 });
    expect(pred.k).toBe(10);
    expect(pred.frames).toBe(entry.params.future_frames);
    expect(pred.futures.length).toBe(10 * pred.frames * J * 3);
    expect(pred.futures.every(Number.isFinite)).toBe(true);
    const [readout] = pred.readouts!;
    expect(readout.label).toBe('diversity');
    expect(readout.unit).toBe('m');
    // root-relative, so planting the feet after the read-out changes it only by float32 rounding
    expect(readout.value).toBeCloseTo(diversity(pred.futures, 10, pred.frames, J * 3), 7);
    expect(readout.value).toBeGreaterThan(0);
  });

  it('diversity grows with the sigma scale and is 0 at s = 0 (the most likely future, z = mu_c)', async () => {
    const h = walkerHistory('cmu_10_04', 0, n);
    const values: number[] = [];
    for (const s of [0, 0.5, 1, 2, 6]) {
      const pred = await p.predict(h, { k: 10, seed: 1, controls: { sigma_scale: s } });
      values.push(pred.readouts![0].value);
      if (s === 0) {
        const one = pred.futures.length / 10;
        expect(pred.futures.subarray(one * 9)).toEqual(pred.futures.subarray(0, one));
      }
    }
    expect(values[0]).toBe(0);
    for (let i = 1; i < values.length; i++) expect(values[i]).toBeGreaterThan(values[i - 1]);
  });

  it('reproduces the read-outs the Python predictor stored in the end-to-end vector', async () => {
    const cases = e2e.cases.filter((c) => c.model === entry.id);
    expect(cases.length).toBeGreaterThan(0);
    for (const c of cases) {
      const pred = await p.predict({ positions: Float32Array.from(c.history.flat(2)), frames: c.history.length, joints: J },
        { k: c.request.k, seed: c.request.seed, horizonFrames: c.request.horizon_frames, controls: c.request.controls });
      expect(Math.abs(pred.readouts![0].value - c.readouts![0].value)).toBeLessThanOrEqual(tolerance(e2e, entry.id));
    }
  });

  it.each([
    ['a short history', walkerHistory('cmu_10_04', 0, 12), {}, /history has 12 frames; this model needs at least 19/],
    ['NaN in the history', { ...walkerHistory('cmu_10_04', 0, 19), positions: new Float32Array(19 * J * 3).fill(NaN) }, {}, /NaN or infinite values \(first at frame 0\)/],
    ['sigma scale above 8', walkerHistory('cmu_10_04', 0, 19), { sigma_scale: 8.5 }, /Sigma scale must be between 0 and 8, got 8.5/],
    ['sigma scale below 0', walkerHistory('cmu_10_04', 0, 19), { sigma_scale: -0.1 }, /Sigma scale must be between 0 and 8, got -0.1/],
  ])('bad input: %s', async (_, h, controls, message) => {
    await expect(p.predict(h, { k: 10, seed: 0, controls })).rejects.toThrow(PredictError);
    await expect(p.predict(h, { k: 10, seed: 0, controls })).rejects.toThrow(message);
  });
});

// The baselines are not served; their sampling is pinned by the vectors above. Here a recording
// runner checks the predictor feeds c (h_t or a sampled z_c) and batches K, also when recursing.
describe('Table 4 baselines through the same predictor', () => {
  const d = 3;
  function entryFor(decoder_condition: LcpParams['decoder_condition']): ModelEntry {
    return {
      id: 'fake', method: 'lcp_vae', label: 'fake', hash: 'sha256:' + '0'.repeat(64), graphs: {},
      params: { history_frames: 4, future_frames: 5, latent_size: d, prior: 'standard_normal', decoder_condition },
      controls: [
        { id: 'k', type: 'int', label: 'K', min: 1, max: 50, default: 10 },
        { id: 'horizon', type: 'number', label: 'Horizon (s)', min: 0.1, max: 6, default: 5 / 30 },
        { id: 'sigma_scale', type: 'number', label: 'Sigma scale', min: 0, max: 2, default: 1 },
      ],
    };
  }
  function recorder(cond: Record<string, number[]>) {
    const calls: { role: string; feeds: Record<string, Tensor> }[] = [];
    const runner: GraphRunner = {
      async run(role, feeds) {
        calls.push({ role, feeds });
        const b = feeds[role === 'condition' ? 'history' : 'z'].dims[0];
        if (role === 'condition') {
          return Object.fromEntries(Object.entries(cond).map(([k, v]) => [k, { data: Float32Array.from({ length: b * v.length }, (_, i) => v[i % v.length]), dims: [b, v.length] }]));
        }
        return { future: { data: new Float32Array(b * 5 * J * 3).fill(0.25), dims: [b, 5, J, 3] } };
      },
    };
    return { calls, runner };
  }
  const history = { positions: Float32Array.from({ length: 4 * J * 3 }, (_, i) => Math.sin(i)), frames: 4, joints: J };
  const noFiles = async (file: string): Promise<Uint8Array> => { throw new Error(`LCP-VAE reads no file (${file})`); };

  it('row 2 feeds c = h_t, the same for every sample', async () => {
    const h_t = [0.1, -0.2, 0.3, 0.4];
    const { calls, runner } = recorder({ h_t });
    const p = new LcpVaePredictor({ entry: entryFor({ name: 'h_t', size: 4 }), skeleton: manifest.skeleton, actions: [], fps: 30, runner, loadFile: noFiles });
    const pred = await p.predict(history, { k: 3, seed: 2, horizonFrames: 8 });
    expect(calls.map((c) => [c.role, Object.values(c.feeds)[0].dims[0]])).toEqual([['condition', 1], ['decoder', 3], ['condition', 3], ['decoder', 3]]);
    expect(Array.from(calls[1].feeds.c.data)).toEqual(Array.from(Float32Array.from([...h_t, ...h_t, ...h_t])));
    expect(pred.lengths).toEqual(Int32Array.from([8, 8, 8]));
  });

  it('row 3 feeds c = mu_c + s*sigma_c*eps_c, each sample drawing eps_c before z from its own stream', async () => {
    const mu_c = [0.5, -0.5], sigma_c = [0.2, 0.4];
    const { calls, runner } = recorder({ mu_c, sigma_c });
    const p = new LcpVaePredictor({ entry: entryFor({ name: 'z_c', size: 2 }), skeleton: manifest.skeleton, actions: [], fps: 30, runner, loadFile: noFiles });
    await p.predict(history, { k: 2, seed: 9, controls: { sigma_scale: 1.5 } });
    const [r0, r1] = streams(9, 2);
    const [c0, z0, c1, z1] = [r0.normals(2), r0.normals(d), r1.normals(2), r1.normals(d)];
    const epsC = Float64Array.from([...c0, ...c1]);
    const eps = Float64Array.from([...z0, ...z1]);
    const wantC = Float32Array.from([0, 1, 2, 3], (i) => Math.fround(mu_c[i % 2]) + 1.5 * Math.fround(sigma_c[i % 2]) * epsC[i]);
    expect(Array.from(calls[1].feeds.c.data)).toEqual(Array.from(wantC));
    expect(Array.from(calls[1].feeds.z.data)).toEqual(Array.from(Float32Array.from(eps, (e) => 1.5 * e)));
  });
});
