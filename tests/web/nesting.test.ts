// Samples that nest (issue 30 item 6), twin of tests/export/test_nesting.py: with the same seed, the
// first k samples of a prediction with K > k are exactly the k samples of a prediction with K = k, for
// every stochastic served model, so best-of-K never rises with K. (Python and TypeScript draw the same
// streams: the lcp and e2e vectors tie them.)
import { readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { adeFde } from '../../web/src/metrics/readout';
import { PredictError, type History, type Prediction, type PredictRequest } from '../../web/src/predictor/types';
import { loadManifest, nodePredictor } from './helpers/models';

const manifest = loadManifest();
const J = manifest.skeleton.joints.length;
const S = J * 3;
// The stochastic models are the ones with a K control.
const stochastic = manifest.models.filter((m) => m.controls.some((c) => c.id === 'k'));
const KS = [1, 5, 10, 50];
const HELD_OUT_WALKS = ['cmu_10_04', 'cmu_07_05', 'cmu_08_04'];

function clip(name: string): number[][][] {
  return (JSON.parse(readFileSync(new URL(`../../public/clips/${name}.json`, import.meta.url), 'utf8')) as { positions: number[][][] }).positions;
}
const window = (pos: number[][][], start: number, frames: number): History => ({
  positions: Float32Array.from(pos.slice(start, start + frames).flat(2)), frames, joints: J,
});

it('the stochastic models are the four served samplers', () => {
  expect(stochastic.map((m) => m.method).sort()).toEqual(['keyposes', 'lcp_vae', 'wat', 'wat_transformer']);
});

/** small (K = k) is big's (K > k) first k samples, exactly; WAT pads every sample to the longest one's
 *  length, so only the frames both hold are compared (every sample's own frames are). */
function expectNested(big: Prediction, small: Prediction, k: number): void {
  const f = small.frames;
  expect(f).toBeLessThanOrEqual(big.frames);
  expect(Array.from(small.lengths)).toEqual(Array.from(big.lengths.subarray(0, k)));
  expect(small.samples).toEqual(big.samples.slice(0, k));
  for (let i = 0; i < k; i++) {
    expect(small.futures.subarray(i * f * S, (i + 1) * f * S)).toEqual(big.futures.subarray(i * big.frames * S, (i * big.frames + f) * S));
  }
  (small.curves ?? []).forEach((c, ci) => c.series.forEach((s, i) => expect(s).toEqual(big.curves![ci].series[i].subarray(0, f))));
  if (big.ghosts) {
    expect(small.ghosts!.frames).toEqual(big.ghosts.frames.slice(0, k));
    expect(small.ghosts!.poses).toEqual(big.ghosts.poses.slice(0, k));
  }
  expect(small.warnings).toEqual(big.warnings);
}

for (const entry of stochastic) {
  describe(`${entry.id}: samples nest across K`, () => {
    const p = nodePredictor(manifest, entry.id);
    const n = entry.params.history_frames as number;
    const walk = clip('cmu_10_04');

    /** A held-out walk and a request that exercises every draw, as in the Python twin: three actions (WAT),
     *  a recursive call (LCP-VAE, 75 > 60 frames), refine on and the longest horizon (Keyposes; the first
     *  history from frame 15 on, in steps of 3, that it accepts). */
    async function nestingCase(): Promise<[History, PredictRequest]> {
      if (entry.method === 'keyposes') {
        for (let start = 15; start + n < walk.length; start += 3) {
          const req = { k: 1, seed: 11, controls: { refine: true } };
          try {
            await p.predict(window(walk, start, n), req);
            return [window(walk, start, n), req];
          } catch (err) {
            if (!(err instanceof PredictError)) throw err;
          }
        }
        throw new Error('Keyposes accepts no history of cmu_10_04 from frame 15 on');
      }
      if (entry.method === 'lcp_vae') return [window(walk, 3, n), { k: 1, seed: 11, horizonFrames: 75 }];
      return [window(walk, 3, n), { k: 1, seed: 11, actions: ['walk', 'punch', 'jump'] }];
    }

    it('the first k samples of K = 50 are the k samples of K = 1, 5 and 10', async () => {
      const [history, req] = await nestingCase();
      const big = await p.predict(history, { ...req, k: 50 });
      const distinct = new Set(Array.from({ length: 50 }, (_, i) => big.futures.subarray(i * big.frames * S, (i + 1) * big.frames * S).join()));
      expect(distinct.size).toBe(50);
      for (const k of KS.slice(0, -1)) expectNested(big, await p.predict(history, { ...req, k }), k);
    }, 120_000);

    it('best-of-K never rises with K on held-out walks (separate predictions, 2 s after frame 40)', async () => {
      const at = 40;
      const horizon = 60;
      for (const name of HELD_OUT_WALKS) {
        const pos = clip(name);
        const truth = Float32Array.from(pos.slice(at, at + horizon).flat(2));
        const best: number[] = [];
        for (const k of KS) {
          const pred = await p.predict(window(pos, at - n, n), {
            k, seed: 3, horizonFrames: horizon, actions: entry.method.startsWith('wat') ? ['walk'] : [],
          });
          best.push(adeFde(pred.futures, k, truth, J, false).ade);
        }
        for (let i = 1; i < best.length; i++) expect(best[i], `${name}: ${best.join(', ')}`).toBeLessThanOrEqual(best[i - 1]);
      }
    }, 120_000);
  });
}
