// Issue 29 items 1 and 8, pure parts: clip names a newcomer reads (ui/clip-name.ts), the permalink's
// stage view (selected sample, paused frame, layout) through share/url-state.ts, the read-out's numbers
// in cm and how they relate to the field's whole-pose ones, and the legend's limb swatches.
import { readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import type { ClipIndex, Manifest } from '../../web/src/contract/types';
import type { Prediction } from '../../web/src/predictor/types';
import {
  decodeState, encodeState, shortHash, stageModel, UrlStateError, validateState, type ShareState,
} from '../../web/src/share/url-state';
import { limbSwatches } from '../../web/src/ui/app';
import { clipShortTitle, clipTitle, motionTitle } from '../../web/src/ui/clip-name';
import { stageReadout } from '../../web/src/ui/readout';
import { mpjpeCm, poseSpreadCm } from '../../web/src/metrics/realism';
import { tintColour } from '../../web/src/viewer/palette';

const read = (p: string) => JSON.parse(readFileSync(new URL(p, import.meta.url), 'utf8'));
const index: ClipIndex = read('../../public/clips/index.json');
const manifest: Manifest = read('../../public/models/manifest.json');
const SPLIT = { test: 'held out', train: 'trained on', 'train+test': 'tail held out' } as const;

describe('clip names a newcomer reads', () => {
  it('the issue\'s example: cmu_10_04 is "walk · person 10 (held out) · take 4"', () => {
    const entry = index.clips.find((c) => c.name === 'cmu_10_04');
    expect(entry, 'the index serves cmu_10_04').toBeDefined();
    expect(clipTitle(entry!)).toBe('walk · person 10 (held out) · take 4');
  });

  it('every served clip: action first, then the person with the split, then the take; never the raw name', () => {
    for (const c of index.clips) {
      const t = clipTitle(c);
      const parts = t.split(' · ');
      expect(parts[0], c.name).toBe(c.action.replace(/_/g, ' '));
      expect(parts[1], c.name).toMatch(new RegExp(`\\(${SPLIT[c.role].replace(/[()]/g, '\\$&')}\\)$`));
      if (typeof c.subject === 'number' || /^\d+$/.test(String(c.subject ?? ''))) expect(parts[1], c.name).toBe(`person ${Number(c.subject)} (${SPLIT[c.role]})`);
      if (c.take) expect(parts[2], c.name).toBe(`take ${Number(c.take.split('_').pop())}`);
      expect(t, c.name).not.toContain('_');
      expect(t).not.toContain(c.name);
    }
  });

  it('the list\'s short form drops what its headings say (action, split): "person 10 · take 4"', () => {
    for (const c of index.clips) {
      const short = clipShortTitle(c);
      expect(short.length, c.name).toBeGreaterThan(0);
      for (const part of short.split(' · ')) expect(clipTitle(c), c.name).toContain(part);
      expect(short, c.name).not.toContain(c.action.replace(/_/g, ' ') + ' ·');
      if (c.take) expect(short, c.name).toBe(`person ${Number(c.subject)} · take ${Number(c.take.split('_').pop())}`);
    }
  });

  it('without the index\'s subject and take the name gives the same title; a dropped file keeps its name', () => {
    for (const c of index.clips) {
      const bare = motionTitle({ name: c.name, action: c.action, role: c.role });
      expect(bare, c.name).toBe(clipTitle(c));
    }
    expect(motionTitle({ name: 'My Walk', action: 'walk', role: 'test', origin: { kind: 'dropped-file', file: 'My Walk.bvh' } })).toBe('My Walk');
    expect(clipTitle({ name: 'someone_else', action: 'jump_turn', role: 'train' })).toBe('jump turn · (trained on) · someone else');
  });
});

describe('the permalink carries what the stage shows', () => {
  const entry = stageModel(manifest);
  const controls = Object.fromEntries(entry.controls.map((c) => [c.id, c.default])) as ShareState['controls'];
  const k = Number(controls.k ?? 1);
  const base: ShareState = { version: '0.1.0', model: entry.id, hash: shortHash(entry.hash), clip: 'cmu_10_04', start: 15, seed: 7, controls };

  it('selected sample (written from 1), paused frame and layout round-trip, each on its own', () => {
    const views: ShareState['view'][] = [
      { sample: k - 1, frame: 23, layout: 'overlay' }, { sample: 0 }, { frame: 0 }, { layout: 'side' }, {}, undefined];
    for (const view of views) {
      const pairs = encodeState({ ...base, view }, manifest);
      const q = new Map(pairs);
      if (view?.sample !== undefined) expect(q.get('sample')).toBe(String(view.sample + 1));
      else expect(q.has('sample')).toBe(false);
      const { state, problems } = decodeState(pairs, manifest, '0.1.0');
      expect(problems).toEqual([]);
      const back = view && Object.keys(view).length ? view : undefined;
      expect(state.view).toEqual(back);
      expect(state.seed).toBe(7);
      expect(state.start).toBe(15);
    }
  });

  it('a bad view value is named and left at the page default; a state with one does not encode', () => {
    const { state, problems } = decodeState([['model', entry.id], ['k', String(k)], ['sample', String(k + 1)], ['frame', '-3'], ['layout', 'grid']], manifest, '0.1.0');
    expect(state.view).toBeUndefined();
    expect(problems.map((p) => p.text).join(' ')).toMatch(new RegExp(`sample #${k + 1}.*${k} samples.*frame must be a frame number.*layout must be overlay or side`));
    expect(() => validateState({ ...base, view: { sample: k } }, manifest)).toThrow(UrlStateError);
    expect(() => validateState({ ...base, view: { frame: 1.5 } }, manifest)).toThrow(/frame/);
  });

  it('no model may call a control sample, frame or layout (the link keeps those names)', () => {
    for (const id of ['sample', 'frame', 'layout']) {
      const clash = { ...entry, controls: [...entry.controls, { id, type: 'int' as const, label: id, min: 0, max: 3, default: 0 }] };
      expect(() => encodeState({ ...base, controls: { ...controls, [id]: 0 } }, { ...manifest, models: [clash] }), id).toThrow(/reserve/);
    }
  });
});

describe('the read-out in cm', () => {
  const J = manifest.skeleton.joints.length;
  // Truth: a still pose; sample s is that pose with every joint raised by d_s (heights stay in
  // root-relative poses), so the per-joint distance is exactly d_s and the whole-pose one sqrt(J) d_s.
  const pose = Float32Array.from({ length: J * 3 }, (_, i) => (i % 3 === 1 ? 1 + (i / 3) * 0.05 : (i % 7) * 0.03));
  const frames = 4;
  const d = [0.1, 0.04, 0.25];
  const futures = new Float32Array(d.length * frames * J * 3);
  d.forEach((dist, s) => {
    for (let f = 0; f < frames; f++) {
      for (let c = 0; c < J * 3; c++) futures[((s * frames + f) * J * 3) + c] = pose[c] + (c % 3 === 1 ? dist : 0);
    }
  });
  const truth = new Float32Array(frames * J * 3);
  for (let f = 0; f < frames; f++) truth.set(pose, f * J * 3);
  const p = {
    k: d.length, frames, joints: J, futures, lengths: Int32Array.from(d, () => frames),
    samples: d.map(() => ({ length: frames, stopped: false, segments: [] })), notes: [],
  } as unknown as Prediction;
  const r = stageReadout(p, truth, truth, manifest.skeleton);

  it('leads with the per-joint error and the pose spread of realism.ts (the twins of export/eval/realism/mpjpe.py)', () => {
    const want = mpjpeCm(futures, d.length, truth, J, true);
    expect(r.bestPerJointCm!.ade).toBeCloseTo(want.ade, 9);
    expect(r.bestPerJointCm!.fde).toBeCloseTo(want.fde, 9);
    const spread = poseSpreadCm(futures, d.length, J);
    expect(r.spreadCm.overFrames).toBeCloseTo(spread.overFrames, 9);
    r.samples.forEach((s, i) => expect(s.perJointCm!.ade).toBeCloseTo(100 * d[i], 4));
    expect(r.bestPerJointCm!.ade).toBeCloseTo(100 * Math.min(...d), 4);
  });

  it('the field\'s whole-pose ADE is sqrt(joints) times the per-joint error when every moved joint is off alike', () => {
    for (let s = 0; s < d.length; s++) {
      const perJoint = r.samples[s].perJointCm!.ade / 100;
      expect(r.samples[s].rootRelative!.ade / perJoint).toBeCloseTo(Math.sqrt(J), 4);
    }
    expect(Math.sqrt(J)).toBeCloseTo(4.24, 2); // the "about 4.2 x" the read-out's sentence gives for 18 joints
  });
});

describe('the legend\'s limb swatches', () => {
  it('step through the left/right colours each sample on stage draws, and the clip\'s alone for a clip', () => {
    const css = (side: 'left' | 'right', role: 'prediction' | 'clip', sample = 0) =>
      `rgb(${tintColour(side, { role, sample }).map((v) => Math.round(v * 255)).join(' ')})`;
    const five = limbSwatches('prediction', 5);
    for (let i = 0; i < 5; i++) {
      expect(five.left).toContain(css('left', 'prediction', i));
      expect(five.right).toContain(css('right', 'prediction', i));
    }
    expect(five.left).not.toContain(css('left', 'prediction', 5));
    expect(limbSwatches('clip', 0)).toEqual({ left: css('left', 'clip'), right: css('right', 'clip') });
  });
});
