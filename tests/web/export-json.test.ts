// JSON export of what is shown: clip documents that validate against the contract and read back
// (through the page's own clip reader) to the same joint positions.
import { describe, expect, it } from 'vitest';
import { parseJson, validate } from '../../web/src/contract/validate';
import { motionFromDoc } from '../../web/src/motion/clip';
import { clipDocuments, clipJson } from '../../web/src/export/clip-json';
import type { Shown } from '../../web/src/export/shown';
import { droppedWalk, shownWithSamples } from './helpers/dropped';

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
  it('K futures -> an array of clips, each the history then one future, read back exactly, then the ground truth', async () => {
    const s = await shownWithSamples(3);
    const text = clipJson(s);
    const docs = parseJson(text, 'export.json') as unknown[];
    expect(docs).toHaveLength(4);
    const truth = validate(docs.pop(), 'clip', 'export.json[3]');
    expect(truth.name).toBe('walk.ground_truth');
    expect(truth.action).toBe('ground truth');
    expect(truth.source).toMatchObject({ dataset: 'motion-futures ground truth', file: 'walk', start: 12, history_frames: 10 });
    expect(truth.source).not.toHaveProperty('sample');
    const m = droppedWalk();
    const J = s.joints;
    // the history then the clip's own next frames, as far as the longest future
    const want = m.positions.slice(12 * J * 3, (12 + s.history.frames + s.truth!.frames) * J * 3);
    expect(s.truth!.frames).toBe(Math.min(m.frames - 12 - s.history.frames, Math.max(...s.futures.map((f) => f.frames))));
    expect(maxDiff(motionFromDoc(truth).positions, want)).toBe(0);
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

  it('the selected future -> its clip and the ground truth; without a truth, one clip document', async () => {
    const s = await shownWithSamples(3, 2);
    const docs = (parseJson(clipJson(s), 'two.json') as unknown[]).map((d, i) => validate(d, 'clip', `two.json[${i}]`));
    expect(docs.map((d) => d.name)).toEqual(['walk.sample_3', 'walk.ground_truth']);
    expect(maxDiff(motionFromDoc(docs[0]).positions, expectedSample(s, 0))).toBe(0);
    const doc = validate(parseJson(clipJson({ ...s, truth: undefined }), 'one.json'), 'clip', 'one.json');
    expect(doc.name).toBe('walk.sample_3');
  });

  it('a broken Shown is refused with a message, not a half-written file', async () => {
    const s = await shownWithSamples(1);
    const bad = { ...s, history: { ...s.history, positions: s.history.positions.map((v, i) => (i === 5 ? NaN : v)) } };
    expect(() => clipDocuments(bad)).toThrow('export: a position is not a finite number');
  });
});
