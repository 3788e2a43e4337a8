// TypeScript retargets the fixture BVH files (read by three.js's BVHLoader) to the positions Python
// wrote into contract/vectors/retarget.json, and the T-pose to the pose computed by hand.
import { readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import type { ClipIndex } from '../../web/src/contract/types';
import { bvhPoints, importBvh } from '../../web/src/motion/bvh';
import { loadJointMap } from '../../web/src/motion/joint-map';
import { resamplePoints, retarget } from '../../web/src/motion/retarget';
import { readVector, tolerance, worstDiff } from './helpers/vectors';

const root = new URL('../../', import.meta.url);
const read = (rel: string) => readFileSync(new URL(rel, root), 'utf8');
const vector = readVector<{ cases: { file: string; joint_map: unknown; frames: number; positions: number[][][] }[] }>('retarget');
const skeleton = (JSON.parse(read('public/clips/index.json')) as ClipIndex).skeleton;

describe('retargeting matches the Python vector', () => {
  for (const c of vector.cases) {
    it(`${c.file} with ${JSON.stringify(c.joint_map)}: positions within the file's tolerance`, () => {
      const m = importBvh(read(c.file), c.file, { skeleton, jointMap: c.joint_map ?? undefined });
      expect(m.frames).toBe(c.frames);
      const worst = worstDiff(m.positions, c.positions.flat(2));
      console.info(`retarget vector ${c.file}: max |TS - Python| = ${worst.toExponential(2)} m`);
      expect(worst).toBeLessThanOrEqual(tolerance(vector));
    });
  }
});

describe('retargeting by hand', () => {
  it('the T-pose: every bone keeps its source direction and takes the project length', () => {
    const m = importBvh(read('tests/fixtures/tpose.bvh'), 'tpose.bvh', { skeleton });
    const J = skeleton.joints;
    const at = (name: string) => Array.from(m.positions.slice(J.indexOf(name) * 3, J.indexOf(name) * 3 + 3));
    const len = (name: string) => Math.hypot(...skeleton.offsets![J.indexOf(name)]);
    // legs straight down from the hips (right at -x), toe forward-down (0, -6, 12)/sqrt(180)
    const toeDrop = len('right_toe') * 6 / Math.sqrt(180);
    const rootY = len('right_knee') + len('right_ankle') + toeDrop;
    expect(at('root')[1]).toBeCloseTo(rootY, 6);
    expect(at('right_hip')[0]).toBeCloseTo(-len('right_hip'), 6);
    expect(at('right_ankle')[1]).toBeCloseTo(toeDrop, 6);
    expect(at('left_toe')[1]).toBeCloseTo(0, 6);
    expect(at('left_toe')[2]).toBeCloseTo(len('left_toe') * 12 / Math.sqrt(180), 6);
    expect(at('head')[1]).toBeCloseTo(rootY + len('chest') + len('neck') + len('head'), 6);
    // arms out along -x / +x past the shoulders
    expect(at('right_wrist')[0] - at('right_elbow')[0]).toBeCloseTo(-len('right_wrist'), 6);
    expect(m.frames).toBe(12);
    expect(m.role).toBe('test');
    expect(m.origin.groundTruth).toBe(false);
  });

  it('the bent knee points the shin backwards (-z)', () => {
    const m = importBvh(read('tests/fixtures/knee.bvh'), 'knee.bvh', { skeleton });
    const J = skeleton.joints;
    const p = (name: string, c: number) => m.positions[J.indexOf(name) * 3 + c];
    const shin = Math.hypot(...skeleton.offsets![J.indexOf('right_ankle')]);
    expect(p('right_ankle', 2) - p('right_knee', 2)).toBeCloseTo(-shin, 6);
    expect(p('right_ankle', 1) - p('right_knee', 1)).toBeCloseTo(0, 6);
  });

  it('units do not matter: the walk in centimetres gives the same positions', () => {
    const text = read('tests/fixtures/walk.bvh');
    const src = bvhPoints(text, 'walk.bvh');
    const map = loadJointMap('cmu-bvh', skeleton.joints);
    const a = retarget(src, map, skeleton, 'walk');
    const cm = { ...src, points: src.points.map((v) => v * 5.644) };
    const b = retarget(cm, map, skeleton, 'walk');
    let worst = 0;
    a.positions.forEach((v, i) => { worst = Math.max(worst, Math.abs(v - b.positions[i])); });
    expect(worst).toBeLessThan(1e-12);
  });

  it('resampling is linear in time', () => {
    const src = Float64Array.from({ length: 11 * 3 }, (_, i) => Math.sin(i));
    const out = resamplePoints(src, 11, 3, 0.01);
    expect(out.frames).toBe(4);
    // t = 2/30 s = frame 6.667 of the 100 Hz source
    const u = (2 / 30) / 0.01;
    const i = Math.floor(u);
    expect(out.points[2 * 3 + 1]).toBeCloseTo(src[i * 3 + 1] * (1 - (u - i)) + src[(i + 1) * 3 + 1] * (u - i), 12);
  });
});

describe('frames out of a rounded Frame Time (issue 30; the same cases as tests/export/test_retarget.py)', () => {
  const cases: [number, number, number][] = [
    [31, 0.0333333, 31], [138, 0.0333333, 138], [8, 1 / 120, 2], [11, 0.01, 4], [41, 1 / 120, 11],
    [5, 0.0333, 4], [31, 0.033, 30], [20001, 0.033333, 20000],
  ];
  for (const [frames, frameTime, expected] of cases) {
    it(`${frames} frames ${frameTime} s apart -> ${expected} at 30 Hz`, () => {
      expect(resamplePoints(new Float64Array(frames * 3), frames, 3, frameTime).frames).toBe(expected);
    });
  }

  it('the last frame past the end by the rounding is the source\'s last frame', () => {
    const src = Float64Array.from({ length: 31 * 3 }, (_, i) => i);
    const out = resamplePoints(src, 31, 3, 0.0333333);
    expect(Array.from(out.points.slice(30 * 3))).toEqual(Array.from(src.slice(30 * 3)));
  });
});
