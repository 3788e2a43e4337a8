// Planted feet (web/src/predictor/foot-plant.ts): the shared vector's planted futures within its
// tolerance, and the properties that make it safe to run on every prediction.
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import { FOOT_JOINTS, FULL, NONE, contactWeight, plantFeet } from '../../web/src/predictor/foot-plant';
import { loadManifest } from './helpers/models';
import { readVector, tolerance, worstDiff } from './helpers/vectors';

interface Case { clip: string; present: number[][]; futures: number[][][][]; planted: number[][][][] }
const vector = readVector<{ cases: Case[] }>('foot_plant');
const skeleton = loadManifest().skeleton;
const J = skeleton.joints.length;
const feet = FOOT_JOINTS.map((n) => skeleton.joints.indexOf(n));

function planted(c: Case): Float32Array {
  const out = Float32Array.from(c.futures.flat(3));
  plantFeet(c.present.flat(), out, c.futures.length, c.futures[0].length, skeleton);
  return out;
}

describe('planted feet', () => {
  it('has cases from served clips', () => {
    expect(vector.cases.length).toBeGreaterThanOrEqual(2);
  });

  for (const c of vector.cases) {
    it(`${c.clip}: reproduces the Python result within the vector's tolerance`, () => {
      expect(worstDiff(planted(c), c.planted.flat(3))).toBeLessThanOrEqual(tolerance(vector));
    });

    it(`${c.clip}: keeps heights and root-relative poses, and stops the slide of a planted foot`, () => {
      const before = Float32Array.from(c.futures.flat(3));
      const after = planted(c);
      const k = c.futures.length;
      const t = c.futures[0].length;
      let slideBefore = 0;
      let slideAfter = 0;
      for (let i = 0; i < k; i++) {
        for (let f = 0; f < t; f++) {
          const o = (i * t + f) * J * 3;
          for (let j = 0; j < J; j++) {
            expect(after[o + j * 3 + 1]).toBe(before[o + j * 3 + 1]);
            expect(after[o + j * 3] - after[o]).toBeCloseTo(before[o + j * 3] - before[o], 5);
            expect(after[o + j * 3 + 2] - after[o + 2]).toBeCloseTo(before[o + j * 3 + 2] - before[o + 2], 5);
          }
          if (f === 0) continue;
          for (const j of feet) {   // a joint fully planted at both frames
            const p = o - J * 3 + j * 3;
            if (before[p + 1] > FULL || before[o + j * 3 + 1] > FULL) continue;
            slideBefore += Math.hypot(before[o + j * 3] - before[p], before[o + j * 3 + 2] - before[p + 2]);
            slideAfter += Math.hypot(after[o + j * 3] - after[p], after[o + j * 3 + 2] - after[p + 2]);
          }
        }
      }
      expect(slideBefore).toBeGreaterThan(0);
      expect(slideAfter).toBeLessThan(0.25 * slideBefore);
    });
  }

  it('leaves a body in the air and a body standing still where they are', () => {
    fc.assert(fc.property(fc.float({ min: Math.fround(NONE + 0.01), max: 2, noNaN: true }), fc.float({ min: -1, max: 1, noNaN: true }),
      (lift, step) => {
        const present = new Float64Array(J * 3);
        for (let j = 0; j < J; j++) present[j * 3 + 1] = lift + j * 0.01;   // every joint above the ramp
        const frames = 3;
        const futures = new Float32Array(frames * J * 3);
        for (let f = 0; f < frames; f++) {
          for (let j = 0; j < J * 3; j++) futures[f * J * 3 + j] = present[j] + (j % 3 === 0 ? step * (f + 1) : 0);
        }
        const copy = futures.slice();
        plantFeet(present, futures, 1, frames, skeleton);
        expect(Array.from(futures)).toEqual(Array.from(copy));          // in the air: the method's own root
        const still = new Float32Array(frames * J * 3);
        for (let f = 0; f < frames; f++) still.set(Float32Array.from(present).map((v, i) => (i % 3 === 1 ? 0 : v)), f * J * 3);
        const held = still.slice();
        plantFeet(still.subarray(0, J * 3), still, 1, frames, skeleton);
        expect(Array.from(still)).toEqual(Array.from(held));             // on the floor, not moving: stays
      }));
  });

  it('weighs contact by a ramp from FULL to NONE', () => {
    expect(contactWeight(FULL - 0.01)).toBe(1);
    expect(contactWeight((FULL + NONE) / 2)).toBeCloseTo(0.5, 12);
    expect(contactWeight(NONE + 0.001)).toBe(0);
  });
});
