// The keyposes vector family: TypeScript extraction, labels, pruning, duration classes, proximity
// softmax and interpolation reproduce what Python wrote (contract/vectors/keyposes.json).
import { describe, expect, it } from 'vitest';
import { readFileSync } from 'node:fs';
import type { ClipIndex } from '../../web/src/contract/types';
import { interpolateKeyposes } from '../../web/src/sampling/keypose-interpolation';
import {
  durationClass, extractKeyposes, faceForward, frameErrors, labelDistribution, nearestCentre, proximity, prune,
} from '../../web/src/sampling/keyposes';
import { readVector, tolerance } from './helpers/vectors';

type P = number[][][];
const vector = readVector<{
  extraction: { clip: string; threshold: number; positions: P; keyposes: number[]; errors: number[] }[];
  labelling: { centres: P; raw: P; values: P; proximity: number[][]; labels: number[]; label_margins: number[];
    distributions: { temperature: number; p: number[][] }[] };
  pruning: { labels: number[]; keep: number[] }[];
  durations: { bounds: number[]; cases: [number, number][] };
  interpolation: { present: number[][]; keyposes: P; durations: number[]; frames: number; future: P }[];
}>('keyposes');
const tol = tolerance(vector);
const skeleton = (JSON.parse(readFileSync(new URL('../../public/clips/index.json', import.meta.url), 'utf8')) as ClipIndex).skeleton;
const J = skeleton.joints.length;

function worst(got: ArrayLike<number>, want: number[]): number {
  expect(got.length).toBe(want.length);
  let w = 0;
  want.forEach((v, i) => { w = Math.max(w, Math.abs(got[i] - v)); });
  return w;
}

describe('keypose extraction matches Python', () => {
  for (const c of vector.extraction) {
    it(`${c.clip} at ${c.threshold} m: keyposes exactly, frame errors within the file's tolerance`, () => {
      const pos = Float64Array.from(c.positions.flat(2));
      expect(extractKeyposes(pos, c.positions.length, J, c.threshold)).toEqual(c.keyposes);
      expect(worst(frameErrors(pos, J, 0, c.positions.length - 1), c.errors)).toBeLessThanOrEqual(tol);
    });
  }

  it('the first and last frames are always keyposes, and a lower threshold never gives fewer', () => {
    const c = vector.extraction[2];
    const pos = Float64Array.from(c.positions.flat(2));
    const n = c.positions.length;
    const coarse = extractKeyposes(pos, n, J, 0.6);
    const fine = extractKeyposes(pos, n, J, 0.1);
    expect(coarse[0]).toBe(0);
    expect(coarse[coarse.length - 1]).toBe(n - 1);
    for (const f of coarse) expect(fine).toContain(f);
    expect(() => extractKeyposes(pos, n, J, 0)).toThrow(/threshold must be positive/);
  });
});

describe('labels, pruning and duration classes match Python', () => {
  const l = vector.labelling;
  const centres = Float64Array.from(l.centres.flat(2));
  const k = l.centres.length;
  it('facing each pose forward', () => {
    expect(worst(faceForward(Float64Array.from(l.raw.flat(2)), l.raw.length, skeleton), l.values.flat(2))).toBeLessThanOrEqual(tol);
  });
  it('nearest centre: labels exactly, margins within the file\'s tolerance', () => {
    const { labels, margins } = nearestCentre(Float64Array.from(l.values.flat(2)), l.values.length, centres, k, J);
    expect(labels).toEqual(l.labels);
    expect(worst(margins, l.label_margins)).toBeLessThanOrEqual(tol);
  });
  it('proximity and the label distribution (softmax with temperature)', () => {
    const values = Float64Array.from(l.values.flat(2));
    expect(worst(proximity(values, l.values.length, centres, k, J), l.proximity.flat())).toBeLessThanOrEqual(tol);
    for (const d of l.distributions) {
      const p = labelDistribution(values, l.values.length, centres, k, J, d.temperature);
      expect(worst(p, d.p.flat())).toBeLessThanOrEqual(tol);
    }
  });
  it.each(vector.pruning.map((c) => [c.labels.join(','), c] as const))('prune %s', (_, c) => {
    expect(prune(c.labels)).toEqual(c.keep);
  });
  it('duration classes', () => {
    for (const [d, cls] of vector.durations.cases) expect(durationClass(d, vector.durations.bounds)).toBe(cls);
    expect(() => durationClass(0, vector.durations.bounds)).toThrow(/at least 1 frame/);
  });
});

describe('interpolation from the present pose matches Python', () => {
  for (const [i, c] of vector.interpolation.entries()) {
    it(`case ${i}: within the file's tolerance, starting next to the present and reaching each keypose on time`, () => {
      const present = Float64Array.from(c.present.flat());
      const keys = Float64Array.from(c.keyposes.flat(2));
      const out = interpolateKeyposes(present, keys, c.durations, c.frames);
      expect(worst(out, c.future.flat(2))).toBeLessThanOrEqual(tol);
      const s = J * 3;
      const t = c.durations[0];
      if (t <= c.frames) expect(worst(out.subarray((t - 1) * s, t * s), c.keyposes[0].flat())).toBeLessThan(1e-12);
    });
  }
});
