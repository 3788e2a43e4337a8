import { describe, expect, it } from 'vitest';
import { Prng, rowNormals, streams } from '../../web/src/rng/prng';
import { readVector, tolerance, worstDiff } from './helpers/vectors';

const vector = readVector<{ cases: { seed: number; u32: number[]; normals: number[] }[] }>('prng');
// The per-sample streams are pinned where the predictor's sampling is (the lcp vector).
const lcp = readVector<{ streams: { seed: number; count: number; u32: number[][] }[] }>('lcp');

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

  for (const c of lcp.streams) {
    it(`seed ${c.seed}: the first draws of ${c.count} per-sample streams exactly (jumps of 2^64)`, () => {
      expect(streams(c.seed, c.count).map((g) => Array.from({ length: c.u32[0].length }, () => g.nextU32()))).toEqual(c.u32);
    });
  }

  it('streams nest, stream 0 is the seed itself, and rowNormals draws one row per stream', () => {
    const firsts = (k: number) => streams(7, k).map((g) => g.nextU32());
    const big = firsts(12);
    for (const k of [0, 1, 5]) expect(firsts(k)).toEqual(big.slice(0, k));
    expect(big[0]).toBe(new Prng(7).nextU32());
    expect(new Set(big).size).toBe(12);
    expect(rowNormals(new Prng(3), 4, 6)).toEqual(new Prng(3).normals(24));
    expect(rowNormals(streams(3, 4), 4, 6).subarray(12, 18)).toEqual(streams(3, 3)[2].normals(6));
    expect(() => rowNormals(streams(3, 3), 4, 6)).toThrow(/3 streams for 4 samples/);
    expect(() => streams(7, -1)).toThrow(/stream count/);
  });

  it('rejects seeds outside 0..2^32-1', () => {
    expect(() => new Prng(-1)).toThrow(/seed/);
    expect(() => new Prng(1.5)).toThrow(/seed/);
    expect(() => new Prng(2 ** 32)).toThrow(/seed/);
  });
});
