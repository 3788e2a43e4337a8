import { describe, expect, it } from 'vitest';
import { loadManifest, nodePredictor } from './helpers/models';
import { PredictError } from '../../web/src/predictor/types';

const manifest = loadManifest();
const J = manifest.skeleton.joints.length;
const history = (frames: number, fill = 0) => ({ positions: new Float32Array(frames * J * 3).fill(fill), frames, joints: J });

describe('bad input to a predictor gives a clear message', () => {
  const p = nodePredictor(manifest, 'regression-gru');
  it.each([
    [history(4), { k: 1, seed: 0 }, /history has 4 frames; this model needs at least 10/],
    [history(10, NaN), { k: 1, seed: 0 }, /NaN/],
    [history(10), { k: 5, seed: 0 }, /deterministic/],
    [history(10), { k: 1, seed: -1 }, /seed must be an integer/],
    [history(10), { k: 1, seed: 0, actions: ['moonwalk'] }, /unknown action 'moonwalk'/],
    [history(10), { k: 1, seed: 0, controls: { sigma_scale: 1 } }, /has no control 'sigma_scale'/],
  ])('%#', async (h, req, message) => {
    await expect(p.predict(h, req)).rejects.toThrow(PredictError);
    await expect(p.predict(h, req)).rejects.toThrow(message);
  });
});
