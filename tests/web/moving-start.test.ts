// The stage's opening history skips a take's standing start (web/src/motion/moving-start.ts).
import { readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import type { ClipDoc, ClipIndex } from '../../web/src/contract/types';
import { movingStart } from '../../web/src/motion/moving-start';

const J = 2;
/** A take of `still` motionless frames, then `moving` frames at 1 cm per frame along x. */
function take(still: number, moving: number): Float32Array {
  const out = new Float32Array((still + moving) * J * 3);
  for (let f = 0; f < still + moving; f++) {
    const x = Math.max(0, f - still) * 0.01;
    for (let j = 0; j < J; j++) out[(f * J + j) * 3] = x;
  }
  return out;
}

describe('movingStart', () => {
  it('a take moving from its first frame opens at its start', () => {
    expect(movingStart(take(0, 120), 120, J, 30)).toBe(0);
  });

  it('a standing start of 40 frames is skipped, to within one step of where one second moves half the median', () => {
    // one second from s holds (s + 30 - 40) moving steps; half the median speed needs 15 of them: s >= 25
    expect(movingStart(take(40, 120), 160, J, 30)).toBe(27);
  });

  it('never moves back before `from`, and a still take stays at `from`', () => {
    expect(movingStart(take(0, 120), 120, J, 30, 9)).toBe(9);
    expect(movingStart(take(90, 0), 90, J, 30, 4)).toBe(4);
  });

  it('the served default walk opens once it walks', () => {
    const read = (rel: string) => readFileSync(new URL(`../../public/clips/${rel}`, import.meta.url), 'utf8');
    const index = JSON.parse(read('index.json')) as ClipIndex;
    const d = index.default!;
    const doc = JSON.parse(read(`${d.clip}.json`)) as ClipDoc;
    const start = movingStart(Float32Array.from(doc.positions.flat(2)), doc.positions.length, doc.positions[0].length, index.fps, d.start);
    expect(start).toBeGreaterThanOrEqual(d.start);
    expect(start).toBeLessThan(doc.positions.length / 3);
  });
});
