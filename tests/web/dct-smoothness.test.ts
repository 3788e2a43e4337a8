// WAT Eq. 4 in TypeScript reproduces the Python vector (contract/vectors/dct_smoothness.json).
import { describe, expect, it } from 'vitest';
import { readFileSync } from 'node:fs';
import { dctBasis, smoothness } from '../../web/src/sampling/dct-smoothness';

interface Case { name: string; l: number; m: number; tail: number[][][]; head: number[][][]; smoothness: number }
const vector = JSON.parse(readFileSync(new URL('../../contract/vectors/dct_smoothness.json', import.meta.url), 'utf8')) as {
  basis: { frames: number; bases: number; d: number[][] }; cases: Case[];
};

describe('DCT smoothness (WAT Eq. 4) matches Python', () => {
  it('the orthonormal DCT-II basis to 1e-12', () => {
    const { frames, bases, d } = vector.basis;
    const got = dctBasis(frames, bases);
    d.flat().forEach((v, i) => expect(Math.abs(got[i] - v)).toBeLessThan(1e-12));
  });

  for (const c of vector.cases) {
    it(`${c.name}: to 1e-6`, () => {
      const coords = c.tail[0].length * 3;
      const got = smoothness(c.tail.flat(2), c.head.flat(2), c.l, coords, c.m);
      expect(Math.abs(got - c.smoothness)).toBeLessThan(1e-6 * Math.max(1, Math.abs(c.smoothness)));
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
