// The guards' shared vectors (issue 19): bone projection, the envelope's measures and warnings, and
// where a future first breaks a bound, TypeScript against what Python wrote.
import { readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import type { ClipIndex } from '../../web/src/contract/types';
import { boneLengths, projectLengths } from '../../web/src/motion/bones';
import { handedness, swapLeftRight } from '../../web/src/motion/handedness';
import { bodyScale, rescale, scaleAnchor } from '../../web/src/predictor/canonical';
import { checkEnvelope, measure, type Envelope, type TempoPoses } from '../../web/src/predictor/envelope';
import { warningsFor } from '../../web/src/predictor/history';
import { firstBadFrame } from '../../web/src/predictor/guard';
import { readVector, tolerance, worstDiff } from './helpers/vectors';

const skeleton = (JSON.parse(readFileSync(new URL('../../public/clips/index.json', import.meta.url), 'utf8')) as ClipIndex).skeleton;
type P = number[][][];

describe('bone lengths and their projection match Python', () => {
  const v = readVector<{ cases: { clip: string; motion: P; lengths: number[]; bone_lengths: number[][]; projected: P }[] }>('bones');
  for (const c of v.cases) {
    it(`${c.clip}: lengths and projection within the file's tolerance`, () => {
      const m = Float64Array.from(c.motion.flat(2));
      expect(worstDiff(boneLengths(m, c.motion.length, skeleton), c.bone_lengths.flat())).toBeLessThanOrEqual(tolerance(v));
      const projected = projectLengths(m, c.motion.length, c.lengths, skeleton);
      expect(worstDiff(projected, c.projected.flat(2))).toBeLessThanOrEqual(tolerance(v));
      // and the projection does what it says: every bone takes its given length
      const got = boneLengths(projected, c.motion.length, skeleton);
      got.forEach((l, i) => expect(Math.abs(l - c.lengths[i % c.lengths.length])).toBeLessThan(1e-9));
    });
  }
  const scales = readVector<{ scales: { clip: string; factor: number; motion: P; body_scale: number; anchor: number[]; model_size: P }[] }>('bones').scales;
  for (const c of scales) {
    it(`${c.clip} scaled ${c.factor}: its body scale and the body at the model's size`, () => {
      const m = Float64Array.from(c.motion.flat(2));
      const scale = bodyScale(m, c.motion.length, skeleton);
      expect(Math.abs(scale - c.body_scale)).toBeLessThanOrEqual(tolerance(v));
      const anchor = scaleAnchor(m, c.motion.length, skeleton.joints.length);
      expect(worstDiff(anchor, c.anchor)).toBeLessThanOrEqual(tolerance(v));
      expect(worstDiff(rescale(m, 1 / scale, anchor), c.model_size.flat(2))).toBeLessThanOrEqual(Math.max(tolerance(v), 1e-6));
    });
  }
});

describe('the training envelope matches Python', () => {
  const v = readVector<{ fps: number; envelope: Envelope;
    cases: { clip: string; change: string; world: P; canonical: P; measure: Record<string, number | null>; warnings: string[];
      handedness: number; swapped_handedness: number; history_warnings: string[] }[] }>('envelope');
  for (const c of v.cases) {
    it(`${c.clip}, ${c.change}: quantities within the tolerance, warnings exactly`, () => {
      const canon = Float64Array.from(c.canonical.flat(2));
      const got = measure(canon, c.canonical.length, v.fps, skeleton, v.envelope.tempo_poses as TempoPoses);
      expect(Object.keys(got)).toEqual(Object.keys(c.measure));
      for (const [q, value] of Object.entries(c.measure)) {
        if (value === null) expect(got[q]).toBeNull();
        else expect(Math.abs((got[q] as number) - value)).toBeLessThanOrEqual(tolerance(v));
      }
      expect(checkEnvelope(canon, c.canonical.length, v.fps, skeleton, v.envelope).map((w) => w.quantity)).toEqual(c.warnings);
    });
    it(`${c.clip}, ${c.change}: handedness and the predictor's history warnings, in order`, () => {
      const world = Float32Array.from(c.world.flat(2));
      const frames = c.world.length;
      expect(Math.abs(handedness(world, frames, skeleton).score - c.handedness)).toBeLessThanOrEqual(tolerance(v));
      expect(Math.abs(handedness(swapLeftRight(world, frames, skeleton), frames, skeleton).score - c.swapped_handedness))
        .toBeLessThanOrEqual(tolerance(v));
      expect(warningsFor(world, frames, v.fps, skeleton, v.envelope).map((w) => w.quantity)).toEqual(c.history_warnings);
    });
  }
  it('a history raised by 0.7 m is named by its root height, with value and range', () => {
    const c = v.cases.find((x) => x.change === 'raised 0.7 m')!;
    const [w] = checkEnvelope(Float64Array.from(c.canonical.flat(2)), c.canonical.length, v.fps, skeleton, v.envelope);
    expect(w.quantity).toBe('root_height');
    expect(w.message).toMatch(/root height is 1\.\d\d m, outside what this model was trained on \(0\.80-1\.00 m\)/);
  });
});

describe('the first out-of-bounds frame matches Python exactly', () => {
  const v = readVector<{ cases: { clip: string; change: string; history: P; future: P; nan_at: number[] | null; first_bad: number | null }[] }>('guard');
  for (const c of v.cases) {
    it(`${c.clip}, ${c.change}: ${c.first_bad === null ? 'no bad frame' : `frame ${c.first_bad}`}`, () => {
      const f = Float64Array.from(c.future.flat(2));
      if (c.nan_at) f[(c.nan_at[0] * skeleton.joints.length + c.nan_at[1]) * 3 + c.nan_at[2]] = NaN;
      const bad = firstBadFrame(f, c.future.length, Float64Array.from(c.history.flat(2)), c.history.length, skeleton);
      expect(bad?.frame ?? null).toBe(c.first_bad);
    });
  }
});
