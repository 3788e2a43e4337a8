// Canonical windows and the root channel: TypeScript reproduces the Python vector, both ways.
import { describe, expect, it } from 'vitest';
import { readFileSync } from 'node:fs';
import { facingAngle } from '../../web/src/motion/facing';
import { canonicalise, joinRoot, place, rootRelative, splitRoot } from '../../web/src/predictor/canonical';
import type { ClipIndex } from '../../web/src/contract/types';
import { readVector, tolerance, worstDiff } from './helpers/vectors';

const vector = readVector<{
  cases: { clip: string; at_frame: number; window: number[][][]; placement: { angle: number; x: number; z: number };
    canonical: number[][][]; placed_back: number[][][] }[];
}>('facing');
const tol = tolerance(vector);
const index = JSON.parse(readFileSync(new URL('../../public/clips/index.json', import.meta.url), 'utf8')) as ClipIndex;
const j = index.skeleton.joints.length;

describe('canonical windows and the root channel match the Python vector', () => {
  for (const c of vector.cases) {
    it(`${c.clip}: canonical window, placement and the way back within the file's tolerance`, () => {
      const flat = Float64Array.from(c.window.flat(2));
      const { canonical, placement } = canonicalise(flat, c.at_frame, index.skeleton);
      expect(Math.abs(placement.angle - c.placement.angle)).toBeLessThanOrEqual(tol);
      expect(Math.abs(placement.x - c.placement.x)).toBeLessThanOrEqual(tol);
      expect(Math.abs(placement.z - c.placement.z)).toBeLessThanOrEqual(tol);
      expect(worstDiff(canonical, c.canonical.flat(2))).toBeLessThanOrEqual(tol);
      const back = place(canonical, j, placement);
      expect(worstDiff(back, c.placed_back.flat(2))).toBeLessThanOrEqual(tol);
      expect(worstDiff(back, flat)).toBeLessThan(1e-9);                 // the round trip
      // the chosen frame faces +z with its root above the origin
      expect(Math.abs(facingAngle(canonical, c.at_frame, index.skeleton))).toBeLessThan(1e-9);
      expect(Math.hypot(canonical[c.at_frame * j * 3], canonical[c.at_frame * j * 3 + 2])).toBeLessThan(1e-9);
    });
  }

  it('splits a travelling pose into the root channel and a root-relative pose, and joins it back', () => {
    const world = Float64Array.from({ length: 2 * j * 3 }, (_, i) => (i % 3 === 1 ? 1 : 0) + (i * 0.37) % 1.3);
    const split = splitRoot(world, j, 0.5, -2);
    expect(split[0]).toBeCloseTo(world[0] - 0.5, 12);
    expect(split[3]).toBeCloseTo(world[3] - world[0], 12);                // joint 1 relative to the root
    expect(split[4]).toBe(world[4]);                                       // heights are kept
    expect(worstDiff(joinRoot(split, j, 0.5, -2), world)).toBeLessThan(1e-12);
    const poses = rootRelative(split, j);
    expect([poses[0], poses[2], poses[j * 3], poses[j * 3 + 2]]).toEqual([0, 0, 0, 0]);
  });
});
