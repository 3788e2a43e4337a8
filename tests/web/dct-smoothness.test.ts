// WAT Eq. 4 in TypeScript reproduces the Python vector (contract/vectors/dct_smoothness.json).
import { describe, expect, it } from 'vitest';
import { dctBasis, smoothness } from '../../web/src/sampling/dct-smoothness';
import { readVector, tolerance, worstDiff } from './helpers/vectors';

interface Case { name: string; l: number; m: number; tail: number[][][]; head: number[][][]; smoothness: number }
const vector = readVector<{ basis: { frames: number; bases: number; d: number[][] }; cases: Case[] }>('dct_smoothness');
const tol = tolerance(vector);

describe('DCT smoothness (WAT Eq. 4) matches Python', () => {
  it('the orthonormal DCT-II basis', () => {
    const { frames, bases, d } = vector.basis;
    expect(worstDiff(dctBasis(frames, bases), d.flat())).toBeLessThanOrEqual(tol);
  });

  for (const c of vector.cases) {
    it(`${c.name}: within the file's tolerance`, () => {
      const coords = c.tail[0].length * 3;
      const got = smoothness(c.tail.flat(2), c.head.flat(2), c.l, coords, c.m);
      expect(Math.abs(got - c.smoothness)).toBeLessThanOrEqual(tol);
    });
  }

  it('a hard cut is rougher than the real motion it joins', () => {
    const cut = vector.cases.find((c) => c.name.startsWith('hard cut'))!;
    const walk = vector.cases.find((c) => c.name.startsWith('walk'))!;
    expect(cut.smoothness).toBeGreaterThan(10 * walk.smoothness);
  });

  it('rejects mismatched sizes with a clear message', () => {
    expect(() => smoothness([0, 0, 0], [0, 0], 1, 3, 1)).toThrow(/tail 3 and head 2 values/);
    expect(() => dctBasis(4, 5)).toThrow(/bases <= frames/);
  });
});
