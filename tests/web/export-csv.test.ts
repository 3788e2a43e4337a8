// CSV export of what is shown (long format) parses back to the positions; numbers are shortest float32.
import { describe, expect, it } from 'vitest';
import { CSV_HEADER, csvText } from '../../web/src/export/csv';
import { float32Text } from '../../web/src/export/shown';
import { shownWithSamples } from './helpers/dropped';

function maxDiff(a: Float32Array, b: Float32Array): number {
  expect(a.length).toBe(b.length);
  let w = 0;
  a.forEach((v, i) => { w = Math.max(w, Math.abs(v - b[i])); });
  return w;
}

describe('CSV export', () => {
  it('long format: figure, frame, time, joint, x, y, z; rows parse back to the positions', async () => {
    const s = await shownWithSamples(2);
    const lines = csvText(s).trimEnd().split('\n');
    expect(lines[0]).toBe(CSV_HEADER);
    const J = s.joints;
    expect(lines.length - 1).toBe(J * (s.history.frames + s.futures[0].frames + s.futures[1].frames));
    const back: Record<string, number[]> = {};
    for (const row of lines.slice(1)) {
      const [figure, frame, time, joint, x, y, z] = row.split(',');
      expect(Number(time)).toBeCloseTo(Number(frame) / 30, 6);
      expect(s.skeleton.joints).toContain(joint);
      (back[figure] ??= []).push(Number(x), Number(y), Number(z));
    }
    expect(Object.keys(back)).toEqual(['history', 'sample_1', 'sample_2']);
    expect(maxDiff(Float32Array.from(back.history), s.history.positions)).toBe(0);
    expect(maxDiff(Float32Array.from(back.sample_2), s.futures[1].positions)).toBe(0);
    // futures' frames continue after the history
    expect(lines[1 + J * s.history.frames].startsWith(`sample_1,${s.history.frames},`)).toBe(true);
  });

  it('numbers are the shortest decimals of their float32 values', () => {
    expect(float32Text(0.1)).toBe('0.1');
    expect(float32Text(Math.fround(1 / 3))).toBe('0.33333334');
    expect(float32Text(-0)).toBe('0');
    expect(float32Text(1e-7)).toBe('1e-7');
  });
});
