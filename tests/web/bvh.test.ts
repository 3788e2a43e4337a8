// Importing a dropped BVH: what comes out, and a named MotionImportError for each kind of bad input.
import { readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import type { ClipIndex } from '../../web/src/contract/types';
import { bvhPoints, checkBvh, importBvh, motionName, MotionImportError, type ImportProblem } from '../../web/src/motion/bvh';

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

describe('other rigs (issue 30)', () => {
  const SIX = ['HIERARCHY', 'ROOT Hips', '{', '  OFFSET 0 0 0', '  CHANNELS 6 Xposition Yposition Zposition Zrotation Yrotation Xrotation',
    '  JOINT Knee', '  {', '    OFFSET 0 -10 0', '    CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation',
    '    End Site', '    {', '      OFFSET 0 -5 0', '    }', '  }', '}', 'MOTION', 'Frames: 2', 'Frame Time: 0.5',
    '1 2 3 0 0 0 0 -10 0 0 0 0', '1 2 3 90 0 0 0 -7 4 0 0 0', ''].join('\n');

  it('position channels on a non-root joint replace its OFFSET (three.js adds them; bvh.ts takes it back out)', () => {
    const p = bvhPoints(SIX, 'six.bvh').points;  // [2 frames][3 points][3]
    const at = (f: number, j: number) => Array.from(p.slice((f * 3 + j) * 3, (f * 3 + j) * 3 + 3));
    expect(at(0, 0)).toEqual([1, 2, 3]);                       // the root still adds its channels to its OFFSET
    expect(at(0, 1)).toEqual([1, 2 - 10, 3]);                  // not 2 - 20
    [1 + 7, 2, 3 + 4].forEach((v, c) => expect(at(1, 1)[c]).toBeCloseTo(v, 5));   // (0, -7, 4) turned by Rz(90)
  });

  it('a rig with 6 channels on every joint keeps its bone lengths and its travel', () => {
    const text = read('tests/fixtures/six_channels.bvh');
    const outline = checkBvh(text, 'six_channels.bvh');
    expect(outline.jointChannels.filter((c) => c.length).every((c) => c.length === 6)).toBe(true);
    const src = bvhPoints(text, 'six_channels.bvh');
    const N = src.names.length;
    const offsets = [...text.matchAll(/OFFSET (\S+) (\S+) (\S+)/g)].map((m) => Math.hypot(Number(m[1]), Number(m[2]), Number(m[3])));
    expect(offsets.length).toBe(N);
    let worst = 0;
    for (let f = 0; f < src.frames; f++) {
      for (let j = 1; j < N; j++) {
        const a = (f * N + j) * 3;
        const b = (f * N + outline.parents[j]) * 3;
        const bone = Math.hypot(src.points[a] - src.points[b], src.points[a + 1] - src.points[b + 1], src.points[a + 2] - src.points[b + 2]);
        worst = Math.max(worst, Math.abs(bone - offsets[j]));
      }
    }
    console.info(`six_channels.bvh: max |bone - OFFSET| = ${worst.toExponential(2)} cm`);
    expect(worst).toBeLessThan(1e-4);   // cm; three.js keeps float32 tracks
    const travel = src.points[((src.frames - 1) * N) * 3 + 2] - src.points[2];
    expect(travel).toBeCloseTo(180, 2);   // 1.2 m/s for 1.5 s, not half of it
    // and it retargets to the same motion as walk.bvh (units do not matter)
    const six = importBvh(text, 'six.bvh', { skeleton });
    const three = importBvh(walk, 'walk.bvh', { skeleton });
    expect(six.frames).toBe(three.frames);
    expect(Math.max(...six.positions.map((v, i) => Math.abs(v - three.positions[i])))).toBeLessThan(1e-4);
  });

  it('a rounded Frame Time keeps the last frame', () => {
    const m = importBvh(read('tests/fixtures/frame_time_rounded.bvh'), 'rounded.bvh', { skeleton });
    expect(m.origin.sourceFrames).toBe(31);
    expect(m.frames).toBe(31);
  });

  it('a y-up file read with "up": "z" imports with a warning that names the fix; the right up has none', () => {
    const flat = importBvh(walk, 'walk.bvh', { skeleton, jointMap: { up: 'z' }, jointMapName: 'map.json' });
    expect(flat.origin.warnings.length).toBe(1);
    expect(flat.origin.warnings[0]).toMatch(/^walk\.bvh: does not look like a person standing upright with the joint map cmu-bvh \+ map\.json: /);
    expect(flat.origin.warnings[0]).toContain('the file looks y-up: it was read with "up": "z" and lies flat; set "up": "y" in the joint map');
    expect(flat.origin.warnings[0]).toContain('(bring-your-own.html#joint-maps)');
    expect(importBvh(walk, 'walk.bvh', { skeleton }).origin.warnings).toEqual([]);
    expect(importBvh(read('tests/fixtures/walk_zup.bvh'), 'z.bvh', { skeleton, jointMap: { up: 'z' } }).origin.warnings).toEqual([]);
    expect(importBvh(read('tests/fixtures/walk_zup.bvh'), 'z.bvh', { skeleton }).origin.warnings[0]).toContain('set "up": "z"');
  });

  it('an unknown skeleton names every map tried and every joint, and links the served guide', () => {
    const extra = Array.from({ length: 150 }, (_, i) => `Finger${String(i).padStart(3, '0')}`);
    const big = read('tests/fixtures/unknown_skeleton.bvh').replace('JOINT J1\n', `${extra.map((n) => `JOINT ${n}\n  {\n  OFFSET 0 0 0\n  CHANNELS 0\n  End Site\n  {\n  OFFSET 0 1 0\n  }\n  }\n`).join('')}JOINT J1\n`);
    let message = '';
    try { importBvh(big, 'big.bvh', { skeleton }); } catch (err) { message = (err as Error).message; }
    expect(message).toMatch(/^big\.bvh: unknown skeleton for joint map cmu-bvh: no source joint for root \(tried/);
    expect(message).toContain('Also tried joint map daz: no source joint for root, chest,');
    expect(message).toContain('Tried in this order: cmu-bvh, daz.');
    expect(message).toContain(extra.join(', '));
    expect(message).not.toContain('…');
    expect(message.endsWith('Give a joint map (bring-your-own.html#joint-maps)')).toBe(true);
    expect(message).not.toContain('docs/BRING_YOUR_OWN.md');
  });
});
