// The stage's realism measures (web/src/metrics/realism.ts): by hand, then against the Python vector
// contract/vectors/metrics.json (export/eval/realism/mpjpe.py, skating.py) within the file's tolerance.
import { describe, expect, it } from 'vitest';
import { readFileSync } from 'node:fs';
import { adeFde, apd, apdFactor, worldPoses } from '../../web/src/metrics/readout';
import {
  contactSpeeds, footSkating, medianContactSpeed, mpjpeCm, mpjpeCmPerSample, poseSpreadCm,
} from '../../web/src/metrics/realism';
import type { ClipIndex } from '../../web/src/contract/types';
import { readVector, tolerance, worstDiff } from './helpers/vectors';

const index = JSON.parse(readFileSync(new URL('../../public/clips/index.json', import.meta.url), 'utf8')) as ClipIndex;
const skeleton = index.skeleton;
const J = skeleton.joints.length;

/** [frames, J, 3] with every joint at y = 1, the named foot joints at the given (x, y) per frame. */
function feet(frames: number, placed: Record<string, [number, number][]>): Float64Array {
  const m = new Float64Array(frames * J * 3);
  for (let i = 1; i < m.length; i += 3) m[i] = 1;
  for (const [name, xy] of Object.entries(placed)) {
    const j = skeleton.joints.indexOf(name);
    xy.forEach(([x, y], f) => { m[(f * J + j) * 3] = x; m[(f * J + j) * 3 + 1] = y; });
  }
  return m;
}

describe('realism measures by hand', () => {
  it('MPJPE in cm: the mean per-joint distance, best of K each on its own, futures cut to the truth', () => {
    const truth = new Float64Array(2 * 2 * 3);
    // frame 0: joints 5 and 0 m off; frame 1: 1 and 1; a third frame past the truth
    const s = [3, 4, 0, 0, 0, 0, /* */ 0, 1, 0, 0, 1, 0, /* */ 9, 9, 9, 9, 9, 9];
    const per = mpjpeCmPerSample(s, 1, truth, 2, false);
    expect(per.ade[0]).toBeCloseTo(175, 10);
    expect(per.fde[0]).toBeCloseTo(100, 10);
    const late = [0, 0, 0, 0, 0, 0, 0.3, 0.3, 0.3, 0.3, 0.3, 0.3];
    const early = [1, 1, 1, 1, 1, 1, 0, 0, 0, 0, 0, 0];
    const best = mpjpeCm([...late, ...early], 2, truth, 2, false);
    expect(best.ade).toBeCloseTo(Math.sqrt(0.27) * 50, 10);
    expect(best.fde).toBe(0);
    const shifted = [2, 0, 0, 2, 0, 0, 2, 0, 0, 2, 0, 0]; // the whole body 2 m along x
    expect(mpjpeCm(shifted, 1, truth, 2, false).ade).toBeCloseTo(200, 10);
    expect(mpjpeCm(shifted, 1, truth, 2, true)).toEqual({ ade: 0, fde: 0 });
    expect(() => mpjpeCm(s.slice(0, 6), 1, truth, 2, false)).toThrow(/fewer than/);
  });

  it('the whole-pose ADE is sqrt(18) times the per-joint error when every joint is off alike', () => {
    const truth = Float64Array.from({ length: J * 3 }, (_, i) => Math.sin(i));
    const off = truth.map((v, i) => (i % 3 === 1 ? v + 0.05 : v)); // every joint 5 cm up
    expect(mpjpeCm(off, 1, truth, J, false).ade).toBeCloseTo(5, 10);
    expect(adeFde(off, 1, truth, J, false).ade).toBeCloseTo(Math.sqrt(18) * 0.05, 12);
  });

  it("the read-out's sentence holds: APD is at least sqrt(18 x frames) times the pose spread (equal when every joint is off alike)", () => {
    // K = 3 futures of 30 frames, random poses (a fixed LCG): the bound is Cauchy-Schwarz, so it holds for any
    let x = 12345;
    const rand = () => { x = (Math.imul(x, 1103515245) + 12345) >>> 0; return x / 2 ** 32 - 0.5; };
    const T = 30;
    const futures = Float64Array.from({ length: 3 * T * J * 3 }, rand);
    const spread = poseSpreadCm(futures, 3, J).overFrames / 100;
    expect(apdFactor(T)).toBeCloseTo(Math.sqrt(18 * T), 12);
    expect(apd(worldPoses(futures, J), 3)).toBeGreaterThan(apdFactor(T) * spread);
    // two samples whose every root-relative joint is 5 cm apart at every frame: equality, far from sqrt(18) alone
    const a = Float64Array.from({ length: T * J * 3 }, (_, i) => (i % (J * 3) < 3 ? 0 : Math.sin(i)));
    const b = a.map((v, i) => (i % 3 === 1 && i % (J * 3) >= 3 ? v + 0.05 : v));
    const pair = Float64Array.from([...a, ...b]);
    expect(poseSpreadCm(pair, 2, J).overFrames).toBeCloseTo(5 * (J - 1) / J, 10);
    expect(apd(worldPoses(pair, J), 2)).toBeCloseTo(apdFactor(T) * (poseSpreadCm(pair, 2, J).overFrames / 100) * Math.sqrt(J / (J - 1)), 10);
  });

  it('pose spread: the mean over pairs of the mean per-joint root-relative distance, last frame and over frames', () => {
    // one joint (the root), two frames; heights 0 0 | 1 2 | 3 4: pairs per frame (1, 2), (3, 4), (2, 2)
    const s = [0, 0, 0, 0, 0, 0, /* */ 0, 1, 0, 0, 2, 0, /* */ 0, 3, 0, 0, 4, 0];
    const spread = poseSpreadCm(s, 3, 1);
    expect(spread.last).toBeCloseTo((8 / 3) * 100, 10);
    expect(spread.overFrames).toBeCloseTo((7 / 3) * 100, 10);
    expect(poseSpreadCm([0, 1, 0, 5, 1, 0], 2, 1)).toEqual({ last: 0, overFrames: 0 }); // 5 m aside: the same pose
    expect(poseSpreadCm(s.slice(0, 6), 1, 1)).toEqual({ last: 0, overFrames: 0 });
  });

  it('foot skating: a planted foot reads 0, a sliding one its speed; both frames within the band', () => {
    const planted: [number, number][] = [[0.5, 0], [0.5, 0], [0.5, 0]];
    const sliding: [number, number][] = [[0, 0.01], [0.02, 0.01], [0.04, 0.01]]; // 0.6 m/s
    const m = feet(3, { left_toe: planted, right_toe: sliding });
    const speeds = Array.from(contactSpeeds(m, skeleton));
    [0, 0, 0.6, 0.6].forEach((v, i) => expect(speeds[i]).toBeCloseTo(v, 12));
    expect(medianContactSpeed(speeds)).toBeCloseTo(0.3, 12);
    const lifting: [number, number][] = [[0, 0.01], [0.1, 0.02], [0.2, 0.05], [0.3, 0.03]]; // 0.03: not within
    const lift = Array.from(contactSpeeds(feet(4, { left_toe: lifting }), skeleton));
    expect(lift.length).toBe(1);
    expect(lift[0]).toBeCloseTo(3, 12);
    expect(medianContactSpeed(contactSpeeds(feet(4, {}), skeleton))).toBeNaN();
  });

  it('the joint lower at t is followed to t + 1 through a heel-toe roll', () => {
    const m = feet(2, { left_ankle: [[0, 0], [0.01, 0.02]], left_toe: [[0.2, 0.02], [0.2, 0]] });
    const speeds = contactSpeeds(m, skeleton);
    expect(speeds.length).toBe(1);
    expect(speeds[0]).toBeCloseTo(0.3, 12); // not the 6 m/s of the ankle-to-toe distance
  });

  it('footSkating takes one median per sample', () => {
    const planted: [number, number][] = [[0.5, 0], [0.5, 0], [0.5, 0]];
    const sliding: [number, number][] = [[0, 0.01], [0.02, 0.01], [0.04, 0.01]];
    const a = feet(3, { left_toe: planted, right_toe: planted });
    const b = feet(3, { left_toe: sliding, right_toe: sliding });
    const per = Array.from(footSkating([...a, ...b, ...feet(3, {})], 3, skeleton));
    expect(per[0]).toBe(0);
    expect(per[1]).toBeCloseTo(0.6, 12);
    expect(per[2]).toBeNaN();
  });
});

interface CmErrors { ade: number; fde: number; ade_per_sample: number[]; fde_per_sample: number[] }
interface Case {
  k: number; frames: number; truth_frames: number; joints: number;
  futures: number[][][][]; truth: number[][][];
  mpjpe_cm: { world: CmErrors; root_relative: CmErrors };
  pose_spread_cm: { last: number; over_frames: number };
  fps: number; band: number; foot_skating: (number | null)[];
}

const vector = readVector<{ cases: Case[] }>('metrics');
const tol = tolerance(vector);

describe('realism measures match the Python vector', () => {
  it('has a case whose feet are planted, lifted and sliding', () => {
    const feetCase = vector.cases[vector.cases.length - 1];
    expect(feetCase.foot_skating.every((v) => v !== null)).toBe(true);
    const [planted, half, sliding] = feetCase.foot_skating as number[];
    expect(planted).toBeLessThan(0.1);
    expect(sliding).toBeGreaterThan(0.8);
    expect(half).toBeGreaterThan(planted);
  });

  for (const c of vector.cases) {
    it(`K = ${c.k}, ${c.frames} frames against ${c.truth_frames}: cm errors, spread and skating within the file's tolerance`, () => {
      expect(c.joints).toBe(J);
      const futures = Float64Array.from(c.futures.flat(3));
      const truth = Float64Array.from(c.truth.flat(2));
      for (const [relative, want] of [[false, c.mpjpe_cm.world], [true, c.mpjpe_cm.root_relative]] as const) {
        const per = mpjpeCmPerSample(futures, c.k, truth, c.joints, relative);
        expect(worstDiff(per.ade, want.ade_per_sample)).toBeLessThanOrEqual(tol);
        expect(worstDiff(per.fde, want.fde_per_sample)).toBeLessThanOrEqual(tol);
        const best = mpjpeCm(futures, c.k, truth, c.joints, relative);
        expect(worstDiff([best.ade, best.fde], [want.ade, want.fde])).toBeLessThanOrEqual(tol);
      }
      const spread = poseSpreadCm(futures, c.k, c.joints);
      expect(worstDiff([spread.last, spread.overFrames], [c.pose_spread_cm.last, c.pose_spread_cm.over_frames]))
        .toBeLessThanOrEqual(tol);
      const skating = Array.from(footSkating(futures, c.k, skeleton, c.fps, c.band));
      // whether a sample touched the floor at all is a decision: exact
      expect(skating.map((v) => Number.isNaN(v))).toEqual(c.foot_skating.map((v) => v === null));
      const touched = c.foot_skating.map((v, i) => [v, skating[i]] as const).filter(([v]) => v !== null);
      expect(worstDiff(touched.map(([, got]) => got), touched.map(([v]) => v as number))).toBeLessThanOrEqual(tol);
    });
  }
});
