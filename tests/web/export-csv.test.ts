// CSV export of what is shown (long format) parses back to the positions, the ground truth's rows too;
// numbers are shortest float32.
import { describe, expect, it } from 'vitest';
import { CSV_HEADER, csvText } from '../../web/src/export/csv';
import { float32Text } from '../../web/src/export/shown';
import { droppedWalk, shownWithSamples } from './helpers/dropped';

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
    const truth = s.truth!;
    const m = droppedWalk();
    // the clip's frames after the history, as far as the longest future
    expect(truth.frames).toBe(Math.min(m.frames - 12 - s.history.frames, Math.max(s.futures[0].frames, s.futures[1].frames)));
    expect(truth.frames).toBeGreaterThan(0);
    expect(lines.length - 1).toBe(J * (s.history.frames + s.futures[0].frames + s.futures[1].frames + truth.frames));
    const back: Record<string, number[]> = {};
    for (const row of lines.slice(1)) {
      const [figure, frame, time, joint, x, y, z] = row.split(',');
      expect(Number(time)).toBeCloseTo(Number(frame) / 30, 6);
      expect(s.skeleton.joints).toContain(joint);
      (back[figure] ??= []).push(Number(x), Number(y), Number(z));
    }
    expect(Object.keys(back)).toEqual(['history', 'sample_1', 'sample_2', 'ground_truth']);
    expect(maxDiff(Float32Array.from(back.history), s.history.positions)).toBe(0);
    expect(maxDiff(Float32Array.from(back.sample_2), s.futures[1].positions)).toBe(0);
    // the ground truth is the clip's own frames after the history (shownWithSamples: history from frame 12)
    const from = (12 + s.history.frames) * J * 3;
    expect(maxDiff(Float32Array.from(back.ground_truth), m.positions.slice(from, from + truth.frames * J * 3))).toBe(0);
    // futures' and the truth's frames continue after the history
    expect(lines[1 + J * s.history.frames].startsWith(`sample_1,${s.history.frames},`)).toBe(true);
    expect(lines.find((l) => l.startsWith('ground_truth,'))!.startsWith(`ground_truth,${s.history.frames},`)).toBe(true);
  });

  it('a Shown without a ground truth exports no ground-truth rows', async () => {
    const s = await shownWithSamples(1);
    const rows = csvText({ ...s, truth: undefined }).trimEnd().split('\n');
    expect(rows.some((r) => r.startsWith('ground_truth,'))).toBe(false);
    expect(rows.length - 1).toBe(s.joints * (s.history.frames + s.futures[0].frames));
  });

  it('numbers are the shortest decimals of their float32 values', () => {
    expect(float32Text(0.1)).toBe('0.1');
    expect(float32Text(Math.fround(1 / 3))).toBe('0.33333334');
    expect(float32Text(-0)).toBe('0');
    expect(float32Text(1e-7)).toBe('1e-7');
  });
});
