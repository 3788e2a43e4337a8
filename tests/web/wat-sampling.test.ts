// The reparameterised Gaussian shared by the VAE predictors (web/src/sampling/gaussian.ts).
import { describe, expect, it } from 'vitest';
import { Prng } from '../../web/src/rng/prng';
import { reparameterise, sampleGaussian } from '../../web/src/sampling/gaussian';

describe('z = mu + exp(logvar / 2) * eps with the shared PRNG', () => {
  it('draws eps row-major (sample, then dimension) from the generator', () => {
    const mu = Float32Array.from([1, -2, 0.5, 0, 3, 1]);         // 2 samples x 3 dims
    const logvar = Float32Array.from([0, Math.log(4), -2, 1, 0, 0]);
    const z = sampleGaussian(new Prng(11), mu, logvar, 2, 3);
    const eps = new Prng(11).normals(6);
    for (let i = 0; i < 6; i++) {
      expect(z[i]).toBe(Math.fround(mu[i] + Math.exp(logvar[i] / 2) * eps[i]));
    }
    expect(z[1]).toBeCloseTo(-2 + 2 * eps[1], 5);                   // logvar = log 4 -> sigma 2
  });

  it('shares a single mu row across samples and scales the spread', () => {
    const mu = Float32Array.from([0.25, -1]);
    const logvar = Float32Array.from([0, 0]);
    const eps = Float64Array.from([1, 2, -1, 0.5, 0, 3]);
    expect(Array.from(reparameterise(mu, logvar, eps, 3, 2, 2))).toEqual(
      [2.25, 3, -1.75, 0, 0.25, 5].map(Math.fround));
  });

  it('rejects mismatched sizes with a clear message', () => {
    expect(() => reparameterise(new Float32Array(3), new Float32Array(3), new Float64Array(4), 2, 2)).toThrow(/mu\/logvar of 3\/3 values/);
    expect(() => reparameterise(new Float32Array(2), new Float32Array(2), new Float64Array(3), 2, 2)).toThrow(/3 normals for 2 x 2/);
  });
});
