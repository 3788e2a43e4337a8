// A dropped ASF + AMC pair: TypeScript reads the text of contract/vectors/asf.json to the same points and
// retargeted positions Python wrote, names bad files as export/data/asf_amc.py does, and reads CMU take
// 05_02 to the same legs and root as the cgspeed BVH of that take.
import { readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import type { ClipIndex } from '../../web/src/contract/types';
import { asfAmcPoints, asfAmcSource, CMU_FPS, importAsfAmc, parseAmc, parseAsf, skeletonWarning } from '../../web/src/motion/asf-amc';
import { bvhPoints, importBvh, MotionImportError, type ImportProblem } from '../../web/src/motion/bvh';
import { ASF_AMC_MAPS, BUILTIN_MAPS, BVH_MAPS, loadJointMap } from '../../web/src/motion/joint-map';
import { readVector, tolerance, worstDiff } from './helpers/vectors';

const root = new URL('../../', import.meta.url);
const read = (rel: string) => readFileSync(new URL(rel, root), 'utf8');
const skeleton = (JSON.parse(read('public/clips/index.json')) as ClipIndex).skeleton;

interface AsfCase {
  name: string; asf_file: string; amc_file: string; fps: number; asf: string; amc: string;
  names: string[]; frames: number; points: number[][][]; retargeted_frames: number; positions: number[][][];
}
const vector = readVector<{ cases: AsfCase[] }>('asf');

describe('ASF/AMC matches the Python vector', () => {
  for (const c of vector.cases) {
    it(`${c.name}: points and retargeted positions within the file's tolerance`, () => {
      const src = asfAmcSource(c.asf, c.amc, c.asf_file, c.amc_file, c.fps);
      expect(src.names).toEqual(c.names);
      expect(src.frames).toBe(c.frames);
      const points = worstDiff(src.points, c.points.flat(2));
      const m = importAsfAmc(c.asf, c.amc, c.asf_file, c.amc_file, { skeleton, fps: c.fps });
      expect(m.frames).toBe(c.retargeted_frames);
      const positions = worstDiff(m.positions, c.positions.flat(2));
      console.info(`asf vector ${c.name}: max |TS - Python| points ${points.toExponential(2)} m, `
        + `retargeted ${positions.toExponential(2)} m (tolerance ${tolerance(vector)})`);
      expect(points).toBeLessThanOrEqual(tolerance(vector));
      expect(positions).toBeLessThanOrEqual(tolerance(vector));
      expect(m.origin).toMatchObject({ kind: 'dropped-file', file: c.amc_file, format: 'asf-amc', sourceFrames: c.frames, sourceFps: c.fps, jointMap: 'cmu-asf', groundTruth: false });
    });
  }
});

// The hand-made skeleton and motion of tests/export/test_asf_amc.py (tests/fixtures/tiny.asf, .amc), with the same expectations.
const fixture = (name: string) => readFileSync(new URL(`../fixtures/${name}`, import.meta.url), 'utf8');
const ASF = fixture('tiny.asf');

const AMC = fixture('tiny.amc');

// By hand, in file units; points are root, thigh end, shin end, arm end (see the Python test for why).
const EXPECTED = [
  [[0, 0, 0], [0, -9, 0], [0, -13.5, 0], [2, 0, 0]],
  [[1, 2, 3], [1, -7, 3], [1, -11.5, 3], [1, 2, 1]],
  [[0, 0, 0], [0, -9, 0], [-4.5, -9, 0], [2, 0, 0]],
  [[0, 0, 0], [-9, 0, 0], [-13.5, 0, 0], [0, 0, -2]],
];
const UNIT = 0.0254 / 0.45;

function caught(f: () => unknown): MotionImportError {
  let err: unknown;
  try {
    f();
  } catch (e) {
    err = e;
  }
  expect(err).toBeInstanceOf(MotionImportError);
  return err as MotionImportError;
}

describe('forward kinematics', () => {
  it('the hand-made skeleton by hand', () => {
    const asf = parseAsf(ASF, 'tiny.asf');
    const amc = parseAmc(AMC, asf, 'tiny.amc');
    expect(asf.names).toEqual(['root', 'thigh', 'shin', 'arm']);
    expect(amc.frames).toBe(4);
    expect(amc.degrees).toBe(true);
    const got = asfAmcPoints(asf, amc, 1 / 120).points;
    expect(worstDiff(got, EXPECTED.flat(2).map((v) => v * UNIT))).toBeLessThan(1e-12);
  });

  it('radians, inches, CRLF, blank lines and any bone order per frame', () => {
    const half = String(Math.PI / 2);
    const asf = parseAsf(ASF.replace('length 0.45', 'length 1').replace('angle deg', 'angle rad').replace('axis 0 0 90', `axis 0 0 ${half}`), 'inch.asf');
    expect(asf.metres).toBeCloseTo(0.0254, 15);
    let amc = AMC.replace(':DEGREES', ':RADIANS').replaceAll(' 90', ` ${half}`);
    amc = amc.replace('3\nroot 0 0 0 0 0 0\nthigh', '3\n\nthigh').replace(`shin ${half}\n`, `shin ${half}\nroot 0 0 0 0 0 0\n`);
    const got = asfAmcPoints(asf, parseAmc(amc.replaceAll('\n', '\r\n'), asf, 'rad.amc'), 1 / 120).points;
    expect(worstDiff(got, EXPECTED.flat(2).map((v) => v * 0.0254))).toBeLessThan(1e-12);
  });
});

describe('bad files are named as Python names them', () => {
  const asfCases: [(t: string) => string, string][] = [
    [(t) => `hello\n${t}`, 'x.asf: not an ASF file'],
    [(t) => t.slice(0, t.indexOf(':bonedata')), 'x.asf: no :bonedata'],
    [(t) => t.slice(0, t.indexOf(':hierarchy')), 'x.asf: no :hierarchy'],
    [(t) => t.replace('     length 4.5\n', ''), 'x.asf: line 27: the bone block has no "length"'],
    [(t) => t.replace('direction 0 -1 0\n     length 9', 'direction 0 -1\n     length 9'), 'x.asf: line 19: direction needs 3 numbers, found "0 -1"'],
    [(t) => t.replace('length 9', 'length nine'), 'line 20: length needs 1 number, found "nine"'],
    [(t) => t.replace('dof rx\n', 'dof tx\n'), 'line 33: dof "tx" is not supported'],
    [(t) => t.replace('axis 0 0 90  XYZ', 'axis 0 0 90  XYQ'), 'line 21: axis order "XYQ"'],
    [(t) => t.replace('thigh shin\n', 'thigh shine\n'), 'line 45: hierarchy names "shine", which is not a bone'],
    [(t) => t.replace('root thigh arm', 'root thigh'), 'x.asf: bone "arm" is not in :hierarchy'],
    [(t) => t.replace('name shin', 'name thigh'), 'line 27: bone name "thigh" appears twice'],
    [(t) => t.slice(0, t.lastIndexOf('  end\n:hierarchy')), 'bone block opened at line 35 has no "end"'],
    [(t) => t.replace('order TX TY TZ RX RY RZ', 'order TX TY TZ RX RY RW'), 'line 11: root order'],
    [(t) => t.replace('thigh shin\n', 'thigh shin\n    shin thigh\n'), 'x.asf: line 46: bone "thigh" has two parents (root and shin)'],
  ];
  for (const [edit, message] of asfCases) {
    it(`ASF: ${message}`, () => {
      const e = caught(() => parseAsf(edit(ASF), 'x.asf'));
      expect(e.problem).toBe('not-asf-amc');
      expect(e.message.startsWith('x.asf: ')).toBe(true);
      expect(e.message).toContain(message);
    });
  }

  const amcCases: [(t: string) => string, string][] = [
    [(t) => t.replace('shin 90', 'shin 90 0'), 'x.amc: line 15: bone "shin" needs 1 number, found "90 0"'],
    [(t) => t.replace('thigh 90 0 0', 'thigh 90 0 1.5.3'), 'line 14: bone "thigh" needs 3 numbers, found "90 0 1.5.3"'],
    [(t) => t.replace('thigh 90 0 0', 'thigh 90 0 nan'), 'line 14: bone "thigh" needs 3 numbers'],
    [(t) => t.replace('root 1 2 3 0 90 0', 'root 1 2 3 0 90'), 'line 9: the root needs 6 numbers'],
    [(t) => t.replace('shin 90', 'shine 90'), 'line 15: "shine" is not a bone with dofs in the ASF'],
    [(t) => t.replace('3\nroot', '5\nroot'), 'line 12: frame 5 follows frame 2 (frames must count up by one)'],
    [(t) => t.replace('thigh 90 0 0\n', ''), 'line 15: frame 3 (line 12) has no values for thigh'],
    [(t) => t.replace('shin 90\n', 'shin 90\nshin 90\n'), 'line 16: bone "shin" appears twice in frame 3'],
    [(t) => t.split('1\nroot')[0], 'x.amc: no frames'],
    [(t) => t.replace(':DEGREES', ':DEGREEZ'), 'line 3: unknown keyword ":DEGREEZ"'],
    [(t) => t.replace('1\nroot 0', 'root 0'), 'line 4: "root 0 0 0 0 0 0" comes before the first frame number'],
    [(t) => t.replace('\n4\n', '\n4.5\n'), 'line 16: "4.5" is not a bone with dofs in the ASF (frame numbers are whole numbers'],
    [(t) => t.replace('shin 0\n2', 'shin 0\narm 5\n2'), 'line 8: "arm" is not a bone with dofs in the ASF'],
  ];
  for (const [edit, message] of amcCases) {
    it(`AMC: ${message}`, () => {
      const e = caught(() => parseAmc(edit(AMC), parseAsf(ASF, 'tiny.asf'), 'x.amc'));
      expect(e.problem).toBe(message.includes('no frames') ? 'too-few-frames' : 'not-asf-amc');
      expect(e.message.startsWith('x.amc: ')).toBe(true);
      expect(e.message).toContain(message);
    });
  }

  it('AMC: more frames than the page reads (the same limit as a BVH)', () => {
    const frame = (f: number) => `${f}\nroot 0 0 0 0 0 0\nthigh 0 0 0\nshin 0\n`;
    const text = `:FULLY-SPECIFIED\n${Array.from({ length: 100_001 }, (_, f) => frame(f + 1)).join('')}`;
    const e = caught(() => parseAmc(text, parseAsf(ASF, 'tiny.asf'), 'long.amc'));
    expect(e.problem).toBe('too-large');
    expect(e.message).toBe('long.amc: line 400002: more frames than this reader takes (100000); cut the take shorter');
  });
});

describe('a dropped ASF/AMC pair', () => {
  const c = vector.cases.find((k) => k.name.startsWith('cmu'))!;
  const fails = (asf: string, amc: string, problem: ImportProblem, message: string | RegExp, options: Record<string, unknown> = {}) => {
    const e = caught(() => importAsfAmc(asf, amc, '05.asf', '05_02.amc', { skeleton, ...options }));
    expect(e.problem).toBe(problem);
    if (typeof message === 'string') expect(e.message).toContain(message);
    else expect(e.message).toMatch(message);
  };

  it('reads at CMU\'s 120 Hz unless told otherwise, as a dropped file without ground truth', () => {
    const m = importAsfAmc(c.asf, c.amc, '05.asf', 'My Take 05_02.amc', { skeleton });
    expect(CMU_FPS).toBe(120);
    expect(m.name).toBe('my_take_05_02');
    expect(m.fps).toBe(30);
    expect(m.frames).toBe(11);
    expect(m.role).toBe('test');
    expect(m.test).toEqual([[0, 11]]);
    expect(m.origin).toMatchObject({ file: 'My Take 05_02.amc', format: 'asf-amc', sourceFrames: 41, sourceFps: 120, jointMap: 'cmu-asf', groundTruth: false });
    const slow = importAsfAmc(c.asf, c.amc, '05.asf', '05_02.amc', { skeleton, fps: 60 });
    expect(slow.frames).toBe(21);
    fails(c.asf, c.amc, 'bad-values', '05_02.amc: the frame rate must be a positive number', { fps: 0 });
  });

  it('a truncated AMC names the line and what is missing', () => {
    const lines = c.amc.split('\n');
    // cut inside frame 41, after its root line: the bones after the root are missing
    const at = lines.indexOf('41');
    fails(c.asf, lines.slice(0, at + 2).join('\n'), 'not-asf-amc',
      `05_02.amc: line ${at + 2}: frame 41 (line ${at + 1}) has no values for lfemur, ltibia, lfoot ... `);
    // cut inside a line: too few numbers
    const half = lines.slice(0, at + 3).join('\n');
    fails(c.asf, half.slice(0, half.lastIndexOf(' ')), 'not-asf-amc', `05_02.amc: line ${at + 3}: bone "lowerback" needs 3 numbers, found "-18.2954 -1.27986"`);
  });

  it('a bone the ASF lacks and a value that is not a number', () => {
    fails(c.asf, c.amc.replace('\nlhumerus ', '\nlupperarm '), 'not-asf-amc', /^05_02\.amc: line 20: "lupperarm" is not a bone with dofs in the ASF$/);
    fails(c.asf, c.amc.replace('\nrtibia ', '\nrtibia x'), 'not-asf-amc', /^05_02\.amc: line 27: bone "rtibia" needs 1 number, found "x\S+"$/);
    fails(c.asf.replace('length 6.57749', 'length 6,57749'), c.amc, 'not-asf-amc', '05.asf: line 29: length needs 1 number, found "6,57749"');
    fails('', c.amc, 'not-asf-amc', '05.asf: not an ASF file');
  });

  it('too few frames, a too large file, a bad joint map and a skeleton the map does not know', () => {
    const frames = c.amc.split('\n');
    fails(c.asf, frames.slice(0, frames.indexOf('30')).join('\n'), 'too-few-frames', '05_02.amc: too few frames: 29 at 120 Hz is 8 at 30 Hz');
    fails(c.asf, `${c.amc}${' '.repeat(64 * 2 ** 20)}`, 'too-large', '05_02.amc: 64 MB is larger than this page reads');
    fails(c.asf, c.amc, 'bad-joint-map', 'field up: must be "y" or "z"', { jointMap: { up: 'x' } });
    fails(c.asf.replaceAll('lfemur', 'lthigh'), c.amc.replaceAll('lfemur', 'lthigh'), 'unknown-skeleton',
      /^05_02\.amc: unknown skeleton for joint map cmu-asf: no source joint for left_knee \(tried lfemur\)/);
    // a user's joint map on top of cmu-asf repairs it
    const m = importAsfAmc(c.asf.replaceAll('lfemur', 'lthigh'), c.amc.replaceAll('lfemur', 'lthigh'), '05.asf', '05_02.amc',
      { skeleton, jointMap: { joints: { left_knee: ['lthigh'] } }, jointMapName: 'mine.json' });
    expect(m.origin.jointMap).toBe('cmu-asf + mine.json');
    expect(worstDiff(m.positions, c.positions.flat(2))).toBeLessThanOrEqual(tolerance(vector));
  });
});

describe('the built-in joint maps', () => {
  it('cmu-asf and daz load like cmu-bvh and smpl; a BVH tries cmu-bvh, then daz', () => {
    expect(Object.keys(BUILTIN_MAPS).sort()).toEqual(['cmu-asf', 'cmu-bvh', 'daz', 'smpl']);
    for (const name of Object.keys(BUILTIN_MAPS)) expect(loadJointMap(name, skeleton.joints).name).toBe(name);
    expect(BVH_MAPS).toEqual(['cmu-bvh', 'daz']);
  });

  it('a Daz-style BVH retargets with the daz map', () => {
    const lines = read('data/cmu/data/papagina+Auto_Conditioned_RNN_motion/train_data_bvh/salsa/01.bvh').split('\n');
    const at = lines.findIndex((l) => l.startsWith('Frames:'));
    const cut = [...lines.slice(0, at), 'Frames:\t240', ...lines.slice(at + 1, at + 2 + 240)].join('\n');
    const m = importBvh(cut, 'salsa_01.bvh', { skeleton });
    expect(m.origin.jointMap).toBe('daz');
    expect(m.frames).toBeGreaterThan(10);
    expect(m.positions.every(Number.isFinite)).toBe(true);
    // a user's override still goes on top of the map that fits
    const o = importBvh(cut, 'salsa_01.bvh', { skeleton, jointMap: { joints: { chest: ['abdomen'] } }, jointMapName: 'mine.json' });
    expect(o.origin.jointMap).toBe('daz + mine.json');
  });
});

describe('take 05_02 read as cgspeed BVH and as ASF/AMC', () => {
  const entry = (JSON.parse(read('data/cmu/index.json')) as { take: string; file: string; asf: string; frames: number }[])
    .find((e) => e.take === '05_02')!;
  const asfText = read(`data/cmu/${entry.asf}`);
  const amcText = read(`data/cmu/${entry.file}`);
  const bvhText = read('data/cmu/crosscheck/05_02.bvh');
  const LEGS_AND_ROOT = ['root', 'right_hip', 'right_knee', 'right_ankle', 'right_toe', 'left_hip', 'left_knee', 'left_ankle', 'left_toe'];

  it('agree on the root and legs within 1 mm after retargeting (cmu-bvh and cmu-asf)', () => {
    const b = importBvh(bvhText, '05_02.bvh', { skeleton });
    const a = importAsfAmc(asfText, amcText, '05.asf', '05_02.amc', { skeleton });
    expect(b.origin.jointMap).toBe('cmu-bvh');
    expect(a.origin.jointMap).toBe('cmu-asf');
    expect(b.origin.sourceFrames).toBe(entry.frames + 1); // cgspeed's T-pose, dropped by the retargeting's rule
    expect(a.origin.sourceFrames).toBe(entry.frames);
    expect(a.frames).toBe(b.frames);
    const J = skeleton.joints;
    let legs = 0;
    let rest = 0;
    for (let f = 0; f < a.frames; f++) {
      for (let j = 0; j < J.length; j++) {
        for (let k = 0; k < 3; k++) {
          const i = (f * J.length + j) * 3 + k;
          const d = Math.abs(a.positions[i] - b.positions[i]);
          if (LEGS_AND_ROOT.includes(J[j])) legs = Math.max(legs, d);
          else rest = Math.max(rest, d);
        }
      }
    }
    console.info(`05_02 retargeted, ${a.frames} frames: max |ASF - BVH| root and legs ${legs.toExponential(2)} m, other joints ${rest.toExponential(2)} m`);
    expect(legs).toBeLessThan(1e-3);
  });

  it('and agree on the raw leg and root points in metres (BVH in 1/0.45 inch, its T-pose frame 0 dropped)', () => {
    const a = asfAmcSource(asfText, amcText, '05.asf', '05_02.amc');
    const b = bvhPoints(bvhText, '05_02.bvh');
    expect(b.frames - 1).toBe(a.frames);
    const pairs: [string, string][] = [
      ['root', 'Hips'], ['lhipjoint', 'LeftUpLeg'], ['rhipjoint', 'RightUpLeg'], ['lfemur', 'LeftLeg'], ['rfemur', 'RightLeg'],
      ['ltibia', 'LeftFoot'], ['rtibia', 'RightFoot'], ['lfoot', 'LeftToeBase'], ['rfoot', 'RightToeBase'],
    ];
    let worst = 0;
    for (const [p, q] of pairs) {
      const i = a.names.indexOf(p);
      const j = b.names.indexOf(q);
      for (let f = 0; f < a.frames; f++) {
        for (let k = 0; k < 3; k++) {
          const va = a.points[(f * a.names.length + i) * 3 + k];
          const vb = b.points[((f + 1) * b.names.length + j) * 3 + k] * UNIT;
          worst = Math.max(worst, Math.abs(va - vb));
        }
      }
    }
    console.info(`05_02 raw points: max |ASF - BVH| root and legs ${worst.toExponential(2)} m`);
    expect(worst).toBeLessThan(1e-3);
  });
});

describe('an ASF that does not fit its AMC (issue 30)', () => {
  it('another subject\'s skeleton is named, as export/data/sources.py names it', () => {
    expect(skeletonWarning('01.asf', '05_07.amc')).toBe('05_07.amc: moved by 01.asf, the skeleton of subject 01, but the take\'s name '
      + 'says subject 05: another subject\'s bone lengths and joint axes do not fit the motion (feet under the floor); use 05.asf');
    for (const [asf, amc] of [['05.asf', '05_07.amc'], ['dir/5.ASF', 'dir/05_07.amc'], ['tiny.asf', 'tiny.amc'], ['skeleton.asf', '05_07.amc'], ['16.asf', 'run.amc']]) {
      expect(skeletonWarning(asf, amc)).toBeNull();
    }
  });

  it('an import moved by another subject\'s ASF carries the warning; its own ASF imports with none', () => {
    const c = vector.cases.find((k) => k.name.startsWith('cmu'))!;
    expect(importAsfAmc(c.asf, c.amc, '05.asf', '05_02.amc', { skeleton }).origin.warnings).toEqual([]);
    const m = importAsfAmc(c.asf, c.amc, '16.asf', '05_02.amc', { skeleton });
    expect(m.origin.warnings).toEqual([skeletonWarning('16.asf', '05_02.amc')]);
    expect(m.frames).toBeGreaterThan(0);
  });

  it('an ASF/AMC pair is tried with the maps of contract/joint-maps/order.json', () => {
    const order = JSON.parse(read('contract/joint-maps/order.json')) as Record<string, string[]>;
    expect(ASF_AMC_MAPS).toEqual(order['asf-amc']);
    expect(BVH_MAPS).toEqual(order.bvh);
  });
});
