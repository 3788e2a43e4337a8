import { describe, expect, it } from 'vitest';
import { readFileSync } from 'node:fs';
import { Prng } from '../../web/src/rng/prng';

const vector = JSON.parse(readFileSync(new URL('../../contract/vectors/prng.json', import.meta.url), 'utf8')) as {
  cases: { seed: number; u32: number[]; normals: number[] }[];
};

describe('shared PRNG matches the Python vector', () => {
  for (const c of vector.cases) {
    it(`seed ${c.seed}: first 1000 uniforms exactly`, () => {
      const r = new Prng(c.seed);
      const got = Array.from({ length: c.u32.length }, () => r.nextU32());
      expect(got).toEqual(c.u32);
      const u = new Prng(c.seed);
      for (const x of c.u32) expect(u.uniform()).toBe(x / 4294967296);
    });
    it(`seed ${c.seed}: first 1000 normals to 1e-12`, () => {
      const got = new Prng(c.seed).normals(c.normals.length);
      let worst = 0;
      c.normals.forEach((v, i) => { worst = Math.max(worst, Math.abs(got[i] - v)); });
      expect(worst).toBeLessThan(1e-12);
    });
  }

  it('rejects seeds outside 0..2^32-1', () => {
    expect(() => new Prng(-1)).toThrow(/seed/);
    expect(() => new Prng(1.5)).toThrow(/seed/);
    expect(() => new Prng(2 ** 32)).toThrow(/seed/);
  });
});
