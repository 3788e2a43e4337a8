// Fuzzing the BVH import path: whatever the text, importBvh returns a valid Motion or throws a
// MotionImportError with a message naming the file; it never hangs, crashes with another error,
// returns NaNs, or makes three.js log to the console (which the page would show as a problem).
import { readFileSync } from 'node:fs';
import fc from 'fast-check';
import { afterAll, beforeAll, describe, expect, it, vi } from 'vitest';
import type { ClipIndex } from '../../web/src/contract/types';
import { importBvh, MAX_BYTES, MotionImportError } from '../../web/src/motion/bvh';

const root = new URL('../../', import.meta.url);
const read = (rel: string) => readFileSync(new URL(rel, root), 'utf8');
const skeleton = (JSON.parse(read('public/clips/index.json')) as ClipIndex).skeleton;
const walk = read('tests/fixtures/walk.bvh');
const knee = read('tests/fixtures/knee.bvh');
const lines = walk.split('\n');

let outcomes = { motions: 0, errors: 0 };
const consoleSpies: ReturnType<typeof vi.spyOn>[] = [];
beforeAll(() => {
  for (const level of ['error', 'warn', 'log'] as const) consoleSpies.push(vi.spyOn(console, level));
});
afterAll(() => {
  console.info(`fuzz outcomes: ${outcomes.motions} motions, ${outcomes.errors} named errors`);
});

/** The property every input must satisfy. */
function importsCleanly(text: string): void {
  let m;
  try {
    m = importBvh(text, 'fuzz.bvh', { skeleton });
  } catch (err) {
    if (!(err instanceof MotionImportError)) throw new Error(`not a MotionImportError: ${(err as Error)?.stack ?? err}`);
    if (!err.message.startsWith('fuzz.bvh: ') || err.message.length < 20) throw new Error(`unhelpful message: ${err.message}`);
    outcomes.errors++;
    return;
  }
  outcomes.motions++;
  if (m.frames < 10 || m.positions.length !== m.frames * 18 * 3) throw new Error(`bad shape ${m.frames}`);
  for (const v of m.positions) if (!Number.isFinite(v)) throw new Error('non-finite position');
  for (const spy of consoleSpies) if (spy.mock.calls.length) throw new Error(`console output: ${spy.mock.calls[0]}`);
}

const RUNS = 300;

describe('fuzzing the BVH import', () => {
  it('truncated files', () => {
    fc.assert(fc.property(fc.integer({ min: 0, max: walk.length }), (n) => importsCleanly(walk.slice(0, n))), { numRuns: RUNS });
  });

  it('shuffled, dropped and duplicated lines', () => {
    const idx = fc.integer({ min: 0, max: lines.length - 1 });
    const edit = fc.oneof(
      fc.tuple(idx, idx).map(([a, b]) => { const l = lines.slice(); [l[a], l[b]] = [l[b], l[a]]; return l; }),
      idx.map((a) => lines.filter((_, i) => i !== a)),
      fc.tuple(idx, idx).map(([a, b]) => { const l = lines.slice(); l.splice(b, 0, lines[a]); return l; }),
      fc.shuffledSubarray(lines.slice(0, 120), { minLength: 0, maxLength: 120 }).map((head) => head.concat(lines.slice(120))),
    );
    fc.assert(fc.property(edit, (l) => importsCleanly(l.join('\n'))), { numRuns: RUNS });
  });

  it('single tokens replaced by anything', () => {
    const tokens = knee.split(/(\s+)/);
    const junk = fc.oneof(fc.string({ maxLength: 12 }), fc.constantFrom('NaN', 'Infinity', '-0', '1e308', '1e-320', '{', '}', 'End', 'Site', 'JOINT', 'ROOT', 'MOTION', '\u00a0', '\ufeff', '9'.repeat(400)),
      fc.double().map(String));
    fc.assert(fc.property(fc.integer({ min: 0, max: tokens.length - 1 }), junk, (i, s) => {
      const t = tokens.slice();
      t[i] = s;
      importsCleanly(t.join(''));
    }), { numRuns: RUNS });
  });

  it('arbitrary text, and BVH-like text built from its keywords', () => {
    fc.assert(fc.property(fc.string({ maxLength: 400, unit: 'grapheme' }), (s) => importsCleanly(s)), { numRuns: RUNS });
    const words = fc.constantFrom('HIERARCHY', 'ROOT a', 'JOINT b', 'End Site', '{', '}', 'OFFSET 0 1 0', 'CHANNELS 3 Xrotation Yrotation Zrotation',
      'CHANNELS 6 Xposition Yposition Zposition Zrotation Yrotation Xrotation', 'MOTION', 'Frames: 2', 'Frames: 99999', 'Frame Time: 0.01', '0 0 0', '1 2 3 4 5 6');
    fc.assert(fc.property(fc.array(words, { maxLength: 60 }), (w) => importsCleanly(['HIERARCHY', ...w].join('\n'))), { numRuns: RUNS });
  });

  it('huge files: a long take imports, oversized ones are refused by name', () => {
    const head = walk.slice(0, walk.indexOf('MOTION'));
    const frame = lines[lines.indexOf('Frame Time: 0.010000') + 1];
    const frames = 30_000; // 5 minutes at 100 Hz
    const t0 = performance.now();
    const big = `${head}MOTION\nFrames: ${frames}\nFrame Time: 0.010000\n${`${frame}\n`.repeat(frames)}`;
    const m = importBvh(big, 'big.bvh', { skeleton });
    console.info(`huge BVH: ${(big.length / 2 ** 20).toFixed(1)} MB, ${frames} frames -> ${m.frames} frames in ${(performance.now() - t0).toFixed(0)} ms`);
    expect(m.frames).toBe(Math.floor((frames - 1) * 0.01 * 30 + 1e-9) + 1);
    expect(() => importBvh(`${head}MOTION\nFrames: 5000000\nFrame Time: 0.01\n${frame}\n`, 'big.bvh', { skeleton })).toThrow(/more than this reader takes/);
    expect(() => importBvh('HIERARCHY\n' + ' '.repeat(MAX_BYTES), 'big.bvh', { skeleton })).toThrow(/MB is larger than this page reads/);
  });
});
