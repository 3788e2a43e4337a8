import { describe, expect, it } from 'vitest';
import { readFileSync } from 'node:fs';
import { canonicalise, facingAngle } from '../../web/src/motion/facing';
import type { ClipIndex } from '../../web/src/contract/types';
import { readVector, tolerance, worstDiff } from './helpers/vectors';

const vector = readVector<{
  cases: { clip: string; at_frame: number; window: number[][][]; angle: number; canonical: number[][][] }[];
}>('facing');
const tol = tolerance(vector);
const index = JSON.parse(readFileSync(new URL('../../public/clips/index.json', import.meta.url), 'utf8')) as ClipIndex;

describe('canonical facing matches the Python vector', () => {
  for (const c of vector.cases) {
    it(`${c.clip}: angle and rotated window within the file's tolerance`, () => {
      const flat = Float64Array.from(c.window.flat(2));
      const { canonical, angle } = canonicalise(flat, c.at_frame, index.skeleton);
      expect(Math.abs(angle - c.angle)).toBeLessThanOrEqual(tol);
      expect(worstDiff(canonical, c.canonical.flat(2))).toBeLessThanOrEqual(tol);
      // and the chosen frame now faces +z
      expect(Math.abs(facingAngle(canonical, c.at_frame, index.skeleton))).toBeLessThan(1e-9);
    });
  }
});
