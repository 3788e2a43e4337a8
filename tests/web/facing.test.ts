import { describe, expect, it } from 'vitest';
import { readFileSync } from 'node:fs';
import { canonicalise, facingAngle } from '../../web/src/motion/facing';
import type { ClipIndex } from '../../web/src/contract/types';

const vector = JSON.parse(readFileSync(new URL('../../contract/vectors/facing.json', import.meta.url), 'utf8')) as {
  cases: { clip: string; at_frame: number; window: number[][][]; angle: number; canonical: number[][][] }[];
};
const index = JSON.parse(readFileSync(new URL('../../public/clips/index.json', import.meta.url), 'utf8')) as ClipIndex;

describe('canonical facing matches the Python vector', () => {
  for (const c of vector.cases) {
    it(`${c.clip}: angle and rotated window to 1e-9`, () => {
      const flat = Float64Array.from(c.window.flat(2));
      const { canonical, angle } = canonicalise(flat, c.at_frame, index.skeleton);
      expect(Math.abs(angle - c.angle)).toBeLessThan(1e-9);
      const want = c.canonical.flat(2);
      let worst = 0;
      want.forEach((v, i) => { worst = Math.max(worst, Math.abs(canonical[i] - v)); });
      expect(worst).toBeLessThan(1e-9);
      // and the chosen frame now faces +z
      expect(Math.abs(facingAngle(canonical, c.at_frame, index.skeleton))).toBeLessThan(1e-9);
    });
  }
});
