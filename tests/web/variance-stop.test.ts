// WAT Eq. 8 in TypeScript reproduces the Python vector (contract/vectors/variance_stop.json).
import { describe, expect, it } from 'vitest';
import { firstStop, varianceCurve } from '../../web/src/sampling/variance-stop';
import { readVector, tolerance, worstDiff } from './helpers/vectors';

interface Case {
  name: string; q: number; delta: number; min_frames: number; max_frames: number; frames: number[][][];
  curve: number[]; length: number; stopped: boolean; margin: number;
}
const vector = readVector<{ cases: Case[] }>('variance_stop');
const tol = tolerance(vector);

describe('variance stopping (WAT Eq. 8) matches Python', () => {
  for (const c of vector.cases) {
    it(`${c.name}: length and stopped exactly, curve and margin within the file's tolerance`, () => {
      const coords = c.frames[0].length * 3;
      const curve = varianceCurve(c.frames.flat(2), c.frames.length, coords, c.q);
      expect(worstDiff(curve, c.curve)).toBeLessThanOrEqual(tol);
      const stop = firstStop(curve, c.delta, c.min_frames, c.max_frames);
      expect(stop.length).toBe(c.length);
      expect(stop.stopped).toBe(c.stopped);
      expect(Math.abs(stop.margin - c.margin)).toBeLessThanOrEqual(tol);
    });
  }

  it('covers stopping, stopping at T_min and never stopping', () => {
    expect(vector.cases.some((c) => c.stopped && c.length > c.min_frames)).toBe(true);
    expect(vector.cases.some((c) => c.stopped && c.length === c.min_frames)).toBe(true);
    expect(vector.cases.some((c) => !c.stopped && c.length === c.max_frames)).toBe(true);
  });

  it('a held pose has zero variance and stops at the first tested window', () => {
    const frames = new Float64Array(12 * 6).fill(0.5);
    const curve = varianceCurve(frames, 12, 6, 5);
    expect(Array.from(curve).every((v) => v === 0)).toBe(true);
    expect(firstStop(curve, 1e-3, 4, 12)).toEqual({ length: 4, stopped: true, margin: 1e-3 });
  });

  it('rejects too few frames with a clear message', () => {
    expect(() => varianceCurve(new Float64Array(9), 3, 3, 5)).toThrow(/at least q=5 frames/);
  });
});
