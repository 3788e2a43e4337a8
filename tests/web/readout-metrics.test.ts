import { describe, expect, it } from 'vitest';
import { readFileSync } from 'node:fs';
import {
  adeFde, adeFdePerSample, apd, boneLengthError, boneLengths, footBelowFloor, meanBoneLengths, worldPoses,
} from '../../web/src/metrics/readout';
import type { ClipIndex, Skeleton } from '../../web/src/contract/types';
import { readVector, tolerance, worstDiff } from './helpers/vectors';

const index = JSON.parse(readFileSync(new URL('../../public/clips/index.json', import.meta.url), 'utf8')) as ClipIndex;
const skeleton = index.skeleton;

/** [frames, joints, 3] flat, every joint at (x_t, y, 0). */
function motion(xs: number[], joints = 1, y = 0): Float64Array {
  const out = new Float64Array(xs.length * joints * 3);
  xs.forEach((x, t) => { for (let j = 0; j < joints; j++) { out[(t * joints + j) * 3] = x; out[(t * joints + j) * 3 + 1] = y; } });
  return out;
}

describe('read-out metrics by hand', () => {
  it('root-relative keeps height and drops the root\'s horizontal position', () => {
    expect(Array.from(worldPoses([1, 0.5, 2, 2, 1, 3], 2))).toEqual([0, 0.5, 0, 1, 1, 1]);
  });

  it('ADE and FDE: whole-pose distances, best of K each on its own, futures cut to the truth', () => {
    const s1 = [3, 4, 0, 0, 0, 0, 9, 9, 9]; // distances 5, 0 (third frame past the truth)
    const s2 = Array.from(motion([1, 1, 1])); // distances 1, 1
    const truth = new Float64Array(6);
    const per = adeFdePerSample([...s1, ...s2], 2, truth, 1, false);
    expect(Array.from(per.ade)).toEqual([2.5, 1]);
    expect(Array.from(per.fde)).toEqual([0, 1]);
    expect(adeFde([...s1, ...s2], 2, truth, 1, false)).toEqual({ ade: 1, fde: 0 });
    const moved = motion([5, 5], 2);
    expect(adeFde(moved, 1, motion([0, 0], 2), 2, false).ade).toBeCloseTo(5 * Math.SQRT2, 12);
    expect(adeFde(moved, 1, motion([0, 0], 2), 2, true)).toEqual({ ade: 0, fde: 0 });
    expect(() => adeFde(s1.slice(0, 3), 1, truth, 1, false)).toThrow(/fewer than/);
  });

  it('APD takes one norm over the whole sequence (not WAT Eq. 10)', () => {
    const y0 = [0, 0, 0, 0, 0, 0];
    const y1 = [3, 4, 0, 0, 0, 0];
    const y2 = [0, 0, 0, 6, 8, 0];
    expect(apd([...y0, ...y1, ...y2], 3)).toBeCloseTo((5 + 10 + Math.sqrt(125)) / 3, 12);
    expect(apd(y0, 1)).toBe(0);
  });

  it('bone length error relative to the history\'s mean lengths', () => {
    const chain: Skeleton = { joints: ['root', 'a', 'b'], parents: [-1, 0, 1] };
    const m = [0, 0, 0, 0, 1, 0, 0, 1, 2, /* */ 0, 0, 0, 0, 1.1, 0, 0, 1.1, 1.5];
    const lengths = boneLengths(m, chain);
    [1, 2, 1.1, 1.5].forEach((v, i) => expect(lengths[i]).toBeCloseTo(v, 12));
    const ref = meanBoneLengths(m, chain);
    expect(boneLengthError(m, ref, chain)).toBeCloseTo(2 / 21, 12);
    expect(() => boneLengthError(m, [1, 0], chain)).toThrow(/positive/);
  });

  it('feet more than the depth below the floor', () => {
    const j = skeleton.joints.length;
    const m = new Float64Array(4 * j * 3).fill(1);
    const at = (f: number, name: string) => (f * j + skeleton.joints.indexOf(name)) * 3 + 1;
    for (let f = 0; f < 4; f++) for (const n of ['right_ankle', 'right_toe', 'left_ankle', 'left_toe']) m[at(f, n)] = 0;
    m[at(1, 'left_toe')] = -0.05;
    m[at(2, 'right_ankle')] = -0.03; // exactly the depth: on the floor
    m[at(3, 'right_toe')] = -0.031;
    m[at(0, 'root')] = -5; // not a foot
    expect(footBelowFloor(m, skeleton)).toBe(0.5);
    expect(footBelowFloor(m, skeleton, 0.1)).toBe(0);
  });
});

interface Errors { ade: number; fde: number; ade_per_sample: number[]; fde_per_sample: number[] }
interface Case {
  k: number; frames: number; truth_frames: number; joints: number;
  history: number[][][]; futures: number[][][][]; truth: number[][][];
  world: Errors; root_relative: Errors; apd: number;
  reference_bone_lengths: number[]; bone_length_error: number[]; depth: number; foot_below_floor: number[];
}

const vector = readVector<{ cases: Case[] }>('metrics');
const tol = tolerance(vector);

describe('read-out metrics match the Python vector', () => {
  for (const c of vector.cases) {
    it(`K = ${c.k}, ${c.frames} frames against ${c.truth_frames}: every metric within the file's tolerance`, () => {
      expect(c.joints).toBe(skeleton.joints.length);
      const futures = Float64Array.from(c.futures.flat(3));
      const truth = Float64Array.from(c.truth.flat(2));
      for (const [relative, want] of [[false, c.world], [true, c.root_relative]] as const) {
        const per = adeFdePerSample(futures, c.k, truth, c.joints, relative);
        expect(worstDiff(per.ade, want.ade_per_sample)).toBeLessThanOrEqual(tol);
        expect(worstDiff(per.fde, want.fde_per_sample)).toBeLessThanOrEqual(tol);
        const best = adeFde(futures, c.k, truth, c.joints, relative);
        expect(worstDiff([best.ade, best.fde], [want.ade, want.fde])).toBeLessThanOrEqual(tol);
      }
      expect(Math.abs(apd(futures, c.k) - c.apd)).toBeLessThanOrEqual(tol);
      const reference = meanBoneLengths(Float64Array.from(c.history.flat(2)), skeleton);
      expect(worstDiff(reference, c.reference_bone_lengths)).toBeLessThanOrEqual(tol);
      const bone = c.futures.map((f) => boneLengthError(Float64Array.from(f.flat(2)), c.reference_bone_lengths, skeleton));
      expect(worstDiff(bone, c.bone_length_error)).toBeLessThanOrEqual(tol);
      // a share of frames is a count: exact
      expect(c.futures.map((f) => footBelowFloor(Float64Array.from(f.flat(2)), skeleton, c.depth))).toEqual(c.foot_below_floor);
    });
  }
});
