// JSON export of what is shown: clip documents that validate against the contract and read back
// (through the page's own clip reader) to the same joint positions.
import { describe, expect, it } from 'vitest';
import { parseJson, validate } from '../../web/src/contract/validate';
import { motionFromDoc } from '../../web/src/motion/clip';
import { clipDocuments, clipJson } from '../../web/src/export/clip-json';
import type { Shown } from '../../web/src/export/shown';
import { shownWithSamples } from './helpers/dropped';

function maxDiff(a: Float32Array, b: Float32Array): number {
  expect(a.length).toBe(b.length);
  let w = 0;
  a.forEach((v, i) => { w = Math.max(w, Math.abs(v - b[i])); });
  return w;
}

function expectedSample(s: Shown, i: number): Float32Array {
  const out = new Float32Array(s.history.positions.length + s.futures[i].positions.length);
  out.set(s.history.positions);
  out.set(s.futures[i].positions, s.history.positions.length);
  return out;
}

describe('JSON export follows the clip contract', () => {
  it('K futures -> an array of clips, each the history then one future, read back exactly', async () => {
    const s = await shownWithSamples(3);
    const text = clipJson(s);
    const docs = parseJson(text, 'export.json') as unknown[];
    expect(docs).toHaveLength(3);
    docs.forEach((raw, i) => {
      const doc = validate(raw, 'clip', `export.json[${i}]`);
      expect(doc.name).toBe(`walk.sample_${i + 1}`);
      expect(doc.split.test).toEqual([[s.history.frames, s.history.frames + s.futures[i].frames]]);
      expect(doc.source).toMatchObject({ dataset: 'motion-futures prediction', file: 'walk', model: 'regression-gru', sample: i + 1, start: 12, history_frames: 10 });
      const m = motionFromDoc(doc);
      expect(m.frames).toBe(s.history.frames + s.futures[i].frames);
      // shortest float32 decimals read back as the very same float32 values
      expect(maxDiff(m.positions, expectedSample(s, i))).toBe(0);
    });
  });

  it('the selected future -> one clip document', async () => {
    const s = await shownWithSamples(3, 2);
    const doc = validate(parseJson(clipJson(s), 'one.json'), 'clip', 'one.json');
    expect(doc.name).toBe('walk.sample_3');
    expect(maxDiff(motionFromDoc(doc).positions, expectedSample(s, 0))).toBe(0);
  });

  it('a broken Shown is refused with a message, not a half-written file', async () => {
    const s = await shownWithSamples(1);
    const bad = { ...s, history: { ...s.history, positions: s.history.positions.map((v, i) => (i === 5 ? NaN : v)) } };
    expect(() => clipDocuments(bad)).toThrow('export: a position is not a finite number');
  });
});
