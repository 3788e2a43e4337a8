// Issue 29 items 2 and 7, the pure parts: compare mode's permalink and rows (web/src/ui/compare.ts,
// web/src/share/url-state.ts, web/src/viewer/layout.ts), and the search for the nearest history start
// a method accepts (web/src/ui/start-search.ts), run with the predictor the site runs on a clip whose
// first frames hold a body three times the model's size (refused: predictor/history.ts SCALE_LIMITS),
// the rest the clip as it is (accepted).
import { readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import type { ClipIndex } from '../../web/src/contract/types';
import { PredictError } from '../../web/src/predictor/types';
import { decodeState, encodeState, type ShareState } from '../../web/src/share/url-state';
import type { Motion } from '../../web/src/motion/clip';
import type { Prediction } from '../../web/src/predictor/types';
import { compareTracks, MAX_COMPARED, parseCompare, rowControls, rowStart, shortLabel } from '../../web/src/ui/compare';
import { buildRequest } from '../../web/src/ui/request-builder';
import { candidateStarts, MAX_TRIES, nearestAccepted } from '../../web/src/ui/start-search';
import { layoutTracks } from '../../web/src/viewer/layout';
import { loadManifest, nodePredictor } from './helpers/models';

const manifest = loadManifest();
const ids = manifest.models.map((m) => m.id);
const model = (id: string) => manifest.models.find((m) => m.id === id)!;

describe('compare mode in the permalink', () => {
  it('keeps known models in order, once, and names the unknown ones', () => {
    const r = parseCompare('wat-rnn, nope ,lcp-vae,wat-rnn', manifest.models);
    expect(r.ids).toEqual(['wat-rnn', 'lcp-vae']);
    expect(r.problems).toHaveLength(1);
    expect(r.problems[0]).toMatch(/compares 'nope', which this site does not serve/);
  });

  it('is off, with a sentence, when fewer than two known models remain', () => {
    const r = parseCompare('wat-rnn,nope', manifest.models);
    expect(r.ids).toEqual([]);
    expect(r.problems.join(' ')).toMatch(/needs two models this site serves; the link names only wat-rnn/);
    expect(parseCompare(ids.join(','), manifest.models).ids).toHaveLength(MAX_COMPARED);
  });

  it('round-trips through a link, the link model first', () => {
    const entry = model('wat-rnn');
    const controls = Object.fromEntries(entry.controls.map((c) => [c.id, c.default as never]));
    const state: ShareState = { version: '1', model: 'wat-rnn', hash: 'ab12', clip: 'cmu_10_04', start: 3, seed: 7, controls,
      compare: ['wat-rnn', 'lcp-vae'] };
    const pairs = encodeState(state, manifest);
    expect(pairs).toContainEqual(['compare', 'wat-rnn,lcp-vae']);
    expect(decodeState(pairs, manifest, '1').state.compare).toEqual(['wat-rnn', 'lcp-vae']);
    // a compare list that leaves out the link's model gets it first
    const d = decodeState([['model', 'lcp-vae'], ['compare', 'wat-rnn,keyposes']], manifest, '1');
    expect(d.state.compare).toEqual(['lcp-vae', 'wat-rnn', 'keyposes']);
    expect(d.problems).toEqual([]);
    expect(() => encodeState({ ...state, compare: ['lcp-vae', 'wat-rnn'] }, manifest)).toThrow(/the link's model first/);
    // an unknown id is named, not a blank page: the rest still compare
    const bad = decodeState([['model', 'wat-rnn'], ['compare', 'wat-rnn,lcp-vea,keyposes']], manifest, '1');
    expect(bad.state.compare).toEqual(['wat-rnn', 'keyposes']);
    expect(bad.problems.map((p) => p.text).join(' ')).toMatch(/'lcp-vea'/);
  });

  it('gives each row the page K and horizon within its own range, and its own history end', () => {
    const c = rowControls(model('lcp-vae'), { k: 5, horizon: 9 });
    expect(c.k).toBe(5);
    expect(c.horizon).toBe(model('lcp-vae').controls.find((s) => s.id === 'horizon')!.max);
    expect(rowControls(model('regression-gru'), { k: 5 }).k).toBeUndefined();   // deterministic: K = 1
    expect(buildRequest(model('regression-gru'), rowControls(model('regression-gru'), { k: 5 }), 1, 30).k).toBe(1);
    expect(rowStart(40, 10, 30)).toBe(20);
    expect(rowStart(5, 10, 30)).toBeNull();
  });

  it('puts every row on one timeline: each history ends where all futures start, each figure named by its model', () => {
    const J = manifest.skeleton.joints.length;
    const frames = 60;
    const m = { name: 'c', frames, joints: J, fps: 30, positions: Float32Array.from({ length: frames * J * 3 }, (_, i) => i % 7) } as unknown as Motion;
    const pred = (k: number, len: number) => ({ k, frames: len, joints: J, lengths: Array(k).fill(len), futures: new Float32Array(k * len * J * 3),
      samples: Array.from({ length: k }, () => ({ stopped: false, segments: [] })) }) as unknown as Prediction;
    const a = model('wat-rnn');
    const b = model('keyposes');
    const na = a.params.history_frames;
    const nb = b.params.history_frames;
    const end = 40;
    const { tracks, origin } = compareTracks(m, [
      { entry: a, start: end - na, controls: {}, plantFeet: true, prediction: pred(2, 15) },
      { entry: b, start: end - nb, controls: {}, plantFeet: true, prediction: pred(2, 12) },
      { entry: model('lcp-vae'), start: 0, controls: {}, plantFeet: true, error: 'refused' },
    ]);
    expect(origin).toBe(Math.max(na, nb));
    const histories = tracks.filter((t) => t.role === 'history');
    expect(histories.map((t) => [t.group, t.startFrame + t.frames])).toEqual([[0, origin], [1, origin]]);
    expect(tracks.filter((t) => t.role === 'prediction').every((t) => t.startFrame === origin)).toBe(true);
    expect(new Set(tracks.filter((t) => t.group === 1).map((t) => t.groupLabel))).toEqual(new Set([shortLabel(b)]));
    expect(tracks.some((t) => t.group === 2)).toBe(false);   // a row without futures draws nothing
    // the truth after the shared history end, the same in both rows
    const truth = tracks.filter((t) => t.role === 'truth');
    expect(truth.map((t) => t.frames)).toEqual([15, 12]);
    expect(Array.from(truth[0].positions.subarray(0, 12 * J * 3))).toEqual(Array.from(truth[1].positions));
  });

  it('names each row by the model\'s short name: no description after a colon or in a parenthesis of several words', () => {
    expect(shortLabel({ label: 'WAT (RNN): action sequences' })).toBe('WAT (RNN)');
    expect(shortLabel({ label: 'WAT (Transformer): action sequences' })).toBe('WAT (Transformer)');
    expect(shortLabel({ label: 'LCP-VAE (learned conditional prior)' })).toBe('LCP-VAE');
    expect(shortLabel({ label: 'Keyposes (keypose classification)' })).toBe('Keyposes');
    expect(shortLabel({ label: 'Zero-velocity (baseline)' })).toBe('Zero-velocity (baseline)');
    expect(shortLabel({ label: '(two words)' })).toBe('(two words)');   // never an empty name
    // every served model: short enough for a figure label ("<name> #10 · closest to truth" over a figure)
    for (const m of manifest.models) expect(shortLabel(m).length, m.label).toBeLessThanOrEqual(24);
  });

  it('lays out one row per method side by side, one column per method overlaid', () => {
    const tracks = [0, 1].flatMap((group) => [
      { role: 'history' as const, group }, { role: 'prediction' as const, sample: 0, group }, { role: 'prediction' as const, sample: 1, group },
    ]);
    const side = layoutTracks(tracks, 'side');
    expect(side.rows).toBe(2);
    expect(side.cols).toBe(2);
    const row = (track: number) => Math.floor(side.placements.find((p) => p.track === track && !p.shared)!.cell / side.cols);
    expect([row(1), row(2), row(4), row(5)]).toEqual([0, 0, 1, 1]);
    // each history is drawn in its own row's cells only
    for (const h of [0, 3]) {
      const cells = side.placements.filter((p) => p.track === h).map((p) => Math.floor(p.cell / side.cols));
      expect(new Set(cells)).toEqual(new Set([h / 3]));
    }
    const over = layoutTracks(tracks, 'overlay', { spacing: 2 });
    expect(new Set(over.placements.filter((p) => tracks[p.track].group === 0).map((p) => p.x)).size).toBe(1);
    expect(over.placements[0].x).not.toBe(over.placements[3].x);
  });
});

describe('the nearest start a method accepts', () => {
  it('orders a clip\'s starts by distance, within MAX_TRIES', () => {
    expect(candidateStarts(5, 9)).toEqual([6, 4, 7, 3, 8, 2, 9, 1, 0]);
    const many = candidateStarts(100, 400);
    expect(many.length).toBeLessThanOrEqual(MAX_TRIES + 2);
    expect(many).toContain(0);
    expect(many).toContain(400);
    expect(many.every((s, i) => i === 0 || Math.abs(s - 100) >= Math.abs(many[i - 1] - 100))).toBe(true);
    expect(candidateStarts(0, -1)).toEqual([]);
  });

  it('stops at the first accepted start, or says none', async () => {
    const tried: number[] = [];
    const found = await nearestAccepted([6, 4, 7], async (s) => { tried.push(s); return s === 4 ? 'accepted' : 'refused'; });
    expect(found).toBe(4);
    expect(tried).toEqual([6, 4]);
    expect(await nearestAccepted([1, 2], async () => 'refused')).toBeNull();
  });

  const keyposes = manifest.models.find((m) => m.method === 'keyposes');
  it.runIf(keyposes)('finds, with the site\'s predictor, where a giant start of a clip gives way to one Keyposes accepts', async () => {
    const entry = keyposes!;
    const n = entry.params.history_frames;
    const index: ClipIndex = JSON.parse(readFileSync(new URL('../../public/clips/index.json', import.meta.url), 'utf8'));
    const clip = index.clips.find((c) => c.name === index.default?.clip)!;
    const doc = JSON.parse(readFileSync(new URL(`../../public/clips/${clip.file}`, import.meta.url), 'utf8')) as { positions: number[][][] };
    const joints = doc.positions[0].length;
    const stride = joints * 3;
    const giant = 2 * n;   // the first 2n frames: the body at 3x (about the origin)
    const frames = Math.min(doc.positions.length, giant + 3 * n);
    const positions = new Float32Array(frames * stride);
    for (let f = 0; f < frames; f++) positions.set(doc.positions[f].flat().map((v) => (f < giant ? 3 * v : v)), f * stride);
    const p = nodePredictor(manifest, entry.id);
    const req = { ...buildRequest(entry, Object.fromEntries(entry.controls.map((c) => [c.id, c.default as never])), 0, manifest.fps), k: 1 };
    const verdict = async (s: number) => {
      try {
        await p.predict({ positions: positions.slice(s * stride, (s + n) * stride), frames: n, joints }, req);
        return 'accepted' as const;
      } catch (e) {
        if (e instanceof PredictError) return 'refused' as const;
        throw e;
      }
    };
    expect(await verdict(0)).toBe('refused');   // a body 3 times the model's size
    const found = await nearestAccepted(candidateStarts(0, frames - n), verdict);
    expect(found).not.toBeNull();
    expect(found!).toBeGreaterThan(0);
    expect(await verdict(found!)).toBe('accepted');
    // nearer starts on the stride were refused
    for (const s of candidateStarts(0, frames - n).filter((s) => s < found!)) expect(await verdict(s)).toBe('refused');
  }, 120_000);
});
