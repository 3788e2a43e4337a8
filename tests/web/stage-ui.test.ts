// The stage's pure parts (issue 20): the first view's model and K, one-sentence messages, the
// scrubber's marks, the status line's controls, the read-out without ground truth, and the model
// card's merged findings and summary.
import { readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import type { Manifest, ModelEntry } from '../../web/src/contract/types';
import type { Prediction } from '../../web/src/predictor/types';
import { defaultLayout, FIRST_VIEW_K, stageModel, withStageDefaults } from '../../web/src/ui/app';
import { summarise, SUMMARY_CHARS } from '../../web/src/ui/messages';
import { describeControls, timelineMarks } from '../../web/src/ui/predict-controller';
import { ending, seconds } from '../../web/src/ui/prediction-panel';
import { readoutJson, stageReadout } from '../../web/src/ui/readout';
import { cardSummary, mergeFindings, type Finding } from '../../web/src/model-card/card';

const read = (p: string) => JSON.parse(readFileSync(new URL(p, import.meta.url), 'utf8'));
const manifest: Manifest = read('../../public/models/manifest.json');
const model = (over: Partial<ModelEntry>): ModelEntry => ({ ...manifest.models[0], ...over });

describe('the first view', () => {
  it('opens on the WAT model, else the first that draws K samples, else the first', () => {
    const wat = model({ id: 'w', method: 'wat', controls: [{ id: 'k', type: 'int', label: 'K', min: 1, max: 50, default: 10 }] });
    const lcp = model({ id: 'l', method: 'lcp_vae', controls: [{ id: 'k', type: 'int', label: 'K', min: 1, max: 50, default: 10 }] });
    const zero = model({ id: 'z', method: 'zero_velocity', controls: [] });
    expect(stageModel({ ...manifest, models: [zero, lcp, wat] }).id).toBe('w');
    expect(stageModel({ ...manifest, models: [zero, lcp] }).id).toBe('l');
    expect(stageModel({ ...manifest, models: [zero] }).id).toBe('z');
  });

  it(`a link without a model gets the stage model and K = ${FIRST_VIEW_K}; a link with one keeps the manifest's defaults`, () => {
    const entry = stageModel(manifest);
    const first = new Map(withStageDefaults([['seed', '3']], manifest));
    expect(first.get('model')).toBe(entry.id);
    if (entry.controls.some((c) => c.id === 'k')) expect(first.get('k')).toBe(String(FIRST_VIEW_K));
    expect(first.get('seed')).toBe('3');
    expect(new Map(withStageDefaults([['k', '7']], manifest)).get('k')).toBe('7');
    const linked: [string, string][] = [['model', manifest.models[0].id]];
    expect(withStageDefaults(linked, manifest)).toEqual(linked);
  });

  it('lays more than three samples out apart', () => {
    expect([1, 2, 3, 4, 5, 10].map(defaultLayout)).toEqual(['overlay', 'overlay', 'overlay', 'side', 'side', 'side']);
  });
});

describe('messages: one sentence, the rest behind a toggle', () => {
  it('keeps a short message whole and cuts a long one at a clause', () => {
    expect(summarise('The models could not be loaded.')).toEqual({ summary: 'The models could not be loaded.', details: null });
    const long = `Could not import: odd.bvh: unknown skeleton for joint map cmu-bvh: no source joint for root (tried ${'Hips, '.repeat(40)}Pelvis). The file's joints are: A, B.`;
    const s = summarise(long);
    expect(s.summary).toBe('Could not import: odd.bvh: unknown skeleton for joint map cmu-bvh.');
    expect(s.details).toBe(long);
    const two = 'A link asks for a clip this site does not have. Showing another one instead.';
    expect(summarise(two)).toEqual({ summary: 'A link asks for a clip this site does not have.', details: two });
    expect(summarise('x'.repeat(300)).summary.length).toBeLessThanOrEqual(SUMMARY_CHARS + 1);
  });
});

describe('what the stage says of a prediction', () => {
  const fps = 30;
  const p = {
    k: 3, frames: 6, joints: 1, futures: new Float32Array(3 * 6 * 3), lengths: Int32Array.from([6, 4, 2]), notes: [],
    samples: [
      { length: 6, stopped: false, segments: [{ start: 0, length: 6, stopped: false }] },
      { length: 4, stopped: true, segments: [{ start: 0, length: 4, stopped: true }] },
      { length: 2, stopped: false, segments: [{ start: 0, length: 2 }], cut: { frame: 1, reason: 'cut: out of bounds' as const, detail: 'a bone is far off' } },
    ],
  } satisfies Prediction;

  it('marks the history\'s end and each stop or cut at the sample\'s last frame, a cut apart from a stop', () => {
    const t = timelineMarks(10, p, fps);
    expect(t.origin).toBe(10);
    expect(t.marks.map((m) => [m.sample, m.kind, m.frame])).toEqual([[1, 'stop', 13], [2, 'cut', 11]]);
    expect(ending(p.samples[2])).toBe(' · cut (out of bounds)');
    expect(ending(p.samples[1])).toBe(' · stopped');
    expect(ending(p.samples[0])).toBe(' · never stopped');
    expect([29, 30, 45].map((f) => seconds(f, fps))).toEqual(['0.97 s', '1.00 s', '1.50 s']);
  });

  it('names the controls in the manifest\'s order', () => {
    const entry = model({ controls: [
      { id: 'k', type: 'int', label: 'Samples (K)', default: 10 }, { id: 'actions', type: 'actions', label: 'Actions', default: ['walk'] },
      { id: 'refine', type: 'bool', label: 'Refine', default: true }, { id: 'sigma_scale', type: 'number', label: 'Sigma', default: 1 },
    ] });
    expect(describeControls(entry, { k: 5, actions: ['walk', 'run_jog'], refine: false, sigma_scale: 0.5 }))
      .toBe('K = 5, actions = walk → run jog, refine = off, sigma scale = 0.5');
  });

  it('gives no ADE or FDE when the ground truth does not cover the futures, and per-sample numbers over each sample\'s own frames', () => {
    const skeleton = { joints: ['root', 'right_ankle', 'right_toe', 'left_ankle', 'left_toe'], parents: [-1, 0, 0, 0, 0] };
    const J = 5;
    const pose = (y: number) => [0, 1, 0, 0.1, y, 0, 0.2, y, 0, -0.1, y, 0, -0.2, y, 0];
    const history = Float32Array.from([...pose(0), ...pose(0)]);
    const futures = Float32Array.from([...pose(0), ...pose(-0.1), ...pose(0), ...pose(0)]);
    const q = { k: 2, frames: 2, joints: J, futures, lengths: Int32Array.from([2, 1]), notes: [],
      samples: [{ length: 2, stopped: false, segments: [] }, { length: 1, stopped: true, segments: [] }] } satisfies Prediction;
    const short = stageReadout(q, history, Float32Array.from(pose(0)), skeleton);
    expect(short.covered).toBe(false);
    expect(short.best).toBeUndefined();
    expect(short.samples.map((s) => s.footBelowFloor)).toEqual([0.5, 0]); // sample 2 is 1 frame long: its held pose is not counted
    const full = stageReadout(q, history, Float32Array.from([...pose(0), ...pose(0), ...pose(0)]), skeleton);
    expect(full.covered).toBe(true);
    expect(full.best!.world.ade).toBe(0);
    expect(JSON.parse(readoutJson(full, { model: 'm' })).best_of_k.world).toEqual({ ade: 0, fde: 0 });
    expect(JSON.parse(readoutJson(short, { model: 'm' })).best_of_k).toBeNull();
  });
});

describe('the model card', () => {
  it('merges statements that repeat per model into one per table, and keeps the others', () => {
    const f = (text: string, verdict: Finding['verdict'] = 'can'): Finding => ({ verdict, text, source: 'results.json, table t' });
    const merged = mergeFindings([
      f('A draws different futures for one history: diversity 0.3 m (test split).'),
      f('Odd statement.', 'unknown'),
      f('B draws different futures for one history: diversity 0.1 m (test split).'),
      f('A draws different futures for one history: diversity 0.5 m (training histories).'),
      f('Z draws a single future: diversity 0 (test split).', 'cannot'),
    ]);
    expect(merged.map((m) => m.text)).toEqual([
      'Different futures for one history (diversity; test split): A 0.3 m, B 0.1 m.',
      'Odd statement.',
      'Different futures for one history (diversity; training histories): A 0.5 m.',
      'A single future (diversity 0; test split): Z.',
    ]);
  });

  it('has a summary of at most five lines, results.json\'s own when it writes one', () => {
    const index = read('../../public/clips/index.json');
    const results = read('../../public/results.json');
    const lines = cardSummary(results, manifest, index);
    expect(lines.length).toBeGreaterThan(2);
    expect(lines.length).toBeLessThanOrEqual(5);
    expect(cardSummary({ ...results, summary: ['one', 'two'] }, manifest, index)).toEqual(['one', 'two']);
    expect(cardSummary(null, null, index).length).toBeGreaterThan(0);
  });
});
