// Importing a dropped BVH: what comes out, and a named MotionImportError for each kind of bad input.
import { readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import type { ClipIndex } from '../../web/src/contract/types';
import { checkBvh, importBvh, motionName, MotionImportError, type ImportProblem } from '../../web/src/motion/bvh';

const root = new URL('../../', import.meta.url);
const read = (rel: string) => readFileSync(new URL(rel, root), 'utf8');
const skeleton = (JSON.parse(read('public/clips/index.json')) as ClipIndex).skeleton;
const walk = read('tests/fixtures/walk.bvh');

function fails(text: string, problem: ImportProblem, message: string | RegExp, options: Record<string, unknown> = {}): void {
  let caught: unknown;
  try {
    importBvh(text, 'take.bvh', { skeleton, ...options });
  } catch (err) {
    caught = err;
  }
  expect(caught).toBeInstanceOf(MotionImportError);
  const e = caught as MotionImportError;
  expect(e.problem).toBe(problem);
  expect(e.message.startsWith('take.bvh: ') || problem === 'bad-joint-map').toBe(true);
  if (typeof message === 'string') expect(e.message).toContain(message);
  else expect(e.message).toMatch(message);
}

describe('a dropped BVH becomes a Motion', () => {
  it('on the project skeleton at 30 Hz, marked as a dropped file without ground truth', () => {
    const m = importBvh(walk, 'My Walk 01.bvh', { skeleton });
    expect(m.name).toBe('my_walk_01');
    expect(m.fps).toBe(30);
    expect(m.frames).toBe(46);
    expect(m.joints).toBe(18);
    expect(m.skeleton.joints).toEqual(skeleton.joints);
    expect(m.positions.length).toBe(46 * 18 * 3);
    expect(m.positions.every(Number.isFinite)).toBe(true);
    expect(m.role).toBe('test');
    expect(m.test).toEqual([[0, 46]]);
    expect(m.origin).toMatchObject({ kind: 'dropped-file', file: 'My Walk 01.bvh', format: 'bvh', sourceFrames: 151, jointMap: 'cmu-bvh', groundTruth: false });
    expect(m.origin.sourceFps).toBeCloseTo(100, 6);
  });

  it('names are contract clip names', () => {
    expect(motionName('C:\\mocap\\Walk Fast.BVH')).toBe('walk_fast');
    expect(motionName('__.bvh')).toBe('dropped');
  });

  it('a user joint map can rename joints or set the up axis', () => {
    const zup = read('tests/fixtures/walk_zup.bvh');
    const a = importBvh(zup, 'z.bvh', { skeleton, jointMap: { up: 'z' } });
    const b = importBvh(walk, 'w.bvh', { skeleton });
    let worst = 0;
    a.positions.forEach((v, i) => { worst = Math.max(worst, Math.abs(v - b.positions[i])); });
    expect(worst).toBeLessThan(1e-5);
  });
});

describe('bad input is named', () => {
  it('not a BVH at all', () => {
    fails('{"format": "motion-futures/clip"}', 'not-bvh', 'take.bvh: not a BVH file (it must start with a line "HIERARCHY")');
    fails('', 'not-bvh', 'not a BVH file');
    fails('\u0000\u0001PNG', 'not-bvh', 'not a BVH file');
  });

  it('a truncated file', () => {
    fails(walk.split('\n').slice(0, 60).join('\n'), 'not-bvh', 'the file ends where');
    fails(walk.slice(0, 2000), 'not-bvh', /line 78: expected "OFFSET x y z" \(three numbers\), found "OFF"/);
    fails(walk.slice(0, walk.length - 500), 'not-bvh', /"Frames: 151" but the file has 149 frame lines \(truncated\?\)/);
  });

  it('broken lines name the line', () => {
    fails(walk.replace('OFFSET 0.000000 -7.440945 0.000000', 'OFFSET 0.000000 -7.440945'), 'not-bvh', /take\.bvh: line 16: expected "OFFSET x y z"/);
    fails(walk.replace('Frame Time: 0.010000', 'Frame Time: -1'), 'not-bvh', 'Frame Time must be positive');
    fails(walk.replace(/\n0 15\.9449 0 /, '\n0 15.9449 NaN '), 'not-bvh', '"NaN" is not a finite number');
    fails(walk.replace('CHANNELS 3 Zrotation Yrotation Xrotation', 'CHANNELS 3 Zrotation Yrotation Wrotation'), 'not-bvh', 'unknown channel "Wrotation"');
  });

  it('an unknown skeleton lists what is missing and what the file has', () => {
    fails(read('tests/fixtures/unknown_skeleton.bvh'), 'unknown-skeleton',
      /take\.bvh: unknown skeleton for joint map cmu-bvh: no source joint for root .*The file's joints are: J0, J1, J2/);
  });

  it('too few frames', () => {
    fails(read('tests/fixtures/short.bvh'), 'too-few-frames', 'take.bvh: too few frames: 3 at 120 Hz is 1 at 30 Hz, and a history needs at least 10');
    fails(walk, 'too-few-frames', 'a history needs at least 60', { minFrames: 60 });
    const none = walk.slice(0, walk.indexOf('Frames:')) + 'Frames: 0\nFrame Time: 0.01\n';
    fails(none, 'too-few-frames', 'the file has none');
  });

  it('a bad joint map', () => {
    fails(walk, 'bad-joint-map', 'field up: must be "y" or "z"', { jointMap: { up: 'x' } });
    fails(walk, 'bad-joint-map', "unknown field 'joint'", { jointMap: { joint: {} } });
    fails(walk, 'bad-joint-map', 'a joint map is a JSON object', { jointMap: [1, 2] });
  });

  it('files too large for the page', () => {
    fails(walk.replace('Frames: 151', 'Frames: 100001'), 'too-large', 'more than this reader takes (100000)');
    fails(walk.replace('Frame Time: 0.010000', 'Frame Time: 1e300'), 'too-large', 'longer than an hour');
  });

  it('the grammar check reads the fixtures as Python does', () => {
    const o = checkBvh(walk, 'walk.bvh');
    expect(o.frames).toBe(151);
    expect(o.channels).toBe(78);
    expect(o.names).toContain('Head/end');
    expect(o.names.filter((_, i) => o.endSite[i]).length).toBe(5);
  });
});
