// Drawing a label with a temperature: TypeScript reproduces Python's draws and margins.
import { describe, expect, it } from 'vitest';
import { Prng } from '../../web/src/rng/prng';
import { sampleIndex, softmax } from '../../web/src/sampling/temperature';
import { readVector, tolerance } from './helpers/vectors';

const vector = readVector<{ sampling: { logits: number[]; temperature: number; u: number; index: number; margin: number }[] }>('keyposes');

describe('softmax(logits / T) and drawing from it', () => {
  it.each(vector.sampling.map((c, i) => [i, c] as const))('Python case %i: index exactly, margin within the file\'s tolerance', (_, c) => {
    const { index, margin } = sampleIndex(Float32Array.from(c.logits), c.temperature, c.u);
    expect(index).toBe(c.index);
    expect(Math.abs(margin - c.margin)).toBeLessThanOrEqual(tolerance(vector));
  });

  it('a lower temperature concentrates the distribution on the largest logit', () => {
    const logits = [1, 2, 0.5, 1.8];
    const cold = softmax(logits, 0.05);
    const hot = softmax(logits, 1.5);
    expect(cold[1]).toBeGreaterThan(0.98);
    expect(hot[1]).toBeLessThan(0.4);
    expect(cold.reduce((a, b) => a + b, 0)).toBeCloseTo(1, 12);
  });

  it('draw frequencies follow the probabilities (shared PRNG, 20000 draws)', () => {
    const logits = [0.2, -1, 1.1, 0.4];
    const p = softmax(logits, 0.7);
    const counts = [0, 0, 0, 0];
    const rng = new Prng(5);
    for (let i = 0; i < 20000; i++) counts[sampleIndex(logits, 0.7, rng.uniform()).index]++;
    counts.forEach((c, i) => expect(Math.abs(c / 20000 - p[i])).toBeLessThan(0.015));
  });

  it('the margin is the distance to the nearest inner CDF bound', () => {
    // p = [0.5, 0.5] at any temperature for equal logits: the one inner bound is 0.5.
    expect(sampleIndex([0, 0], 1, 0.2)).toEqual({ index: 0, margin: 0.3 });
    expect(sampleIndex([0, 0], 1, 0.9).index).toBe(1);
    expect(sampleIndex([0, 0], 1, 0.9).margin).toBeCloseTo(0.4, 12);
    expect(sampleIndex([3], 1, 0.5)).toEqual({ index: 0, margin: Infinity });
  });

  it('rejects a temperature of 0 or below', () => {
    expect(() => softmax([1, 2], 0)).toThrow(/temperature must be positive/);
    expect(() => softmax([1, 2], -0.3)).toThrow(/temperature must be positive/);
  });
});
