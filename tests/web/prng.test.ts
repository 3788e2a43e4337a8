import { describe, expect, it } from 'vitest';
import { Prng } from '../../web/src/rng/prng';
import { readVector, tolerance, worstDiff } from './helpers/vectors';

const vector = readVector<{ cases: { seed: number; u32: number[]; normals: number[] }[] }>('prng');

describe('shared PRNG matches the Python vector', () => {
  for (const c of vector.cases) {
    it(`seed ${c.seed}: first 1000 uniforms exactly`, () => {
      const r = new Prng(c.seed);
      const got = Array.from({ length: c.u32.length }, () => r.nextU32());
      expect(got).toEqual(c.u32);
      const u = new Prng(c.seed);
      for (const x of c.u32) expect(u.uniform()).toBe(x / 4294967296);
    });
    it(`seed ${c.seed}: first 1000 normals within the file's tolerance`, () => {
      expect(worstDiff(new Prng(c.seed).normals(c.normals.length), c.normals)).toBeLessThanOrEqual(tolerance(vector));
    });
  }

  it('rejects seeds outside 0..2^32-1', () => {
    expect(() => new Prng(-1)).toThrow(/seed/);
    expect(() => new Prng(1.5)).toThrow(/seed/);
    expect(() => new Prng(2 ** 32)).toThrow(/seed/);
  });
});
