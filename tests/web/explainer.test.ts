// The explainer's own arithmetic around the predictors' functions: DCT approximation against
// smoothness() (Eq. 4), the join of two clips, PCA, cloud separation, keypose rebuilding and
// label statistics.
import { readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { motionFromDoc, window as clipWindow } from '../../web/src/motion/clip';
import { facingAngle } from '../../web/src/motion/facing';
import { Prng } from '../../web/src/rng/prng';
import { tintColour } from '../../web/src/viewer/palette';
import { smoothness } from '../../web/src/sampling/dct-smoothness';
import { extractKeyposes } from '../../web/src/sampling/keyposes';
import { mpjpe, rebuildFromKeyposes } from '../../web/src/explainer/keypose-fit';
import { entropyBits, sequenceStats, topIndices } from '../../web/src/explainer/label-stats';
import { pca2, separation } from '../../web/src/explainer/pca';
import { coordinate, dctApproximation, joinWindows } from '../../web/src/explainer/transition';

const clip = (name: string) => motionFromDoc(JSON.parse(readFileSync(new URL(`../../public/clips/${name}.json`, import.meta.url), 'utf8')));

describe('DCT approximation (WAT Eq. 4)', () => {
  const x = Float64Array.from({ length: 20 }, (_, i) => Math.sin(i / 3) + (i >= 10 ? 0.4 : 0));

  it('all bases reproduce the series; one basis gives its mean', () => {
    dctApproximation(x, 20).forEach((v, i) => expect(v).toBeCloseTo(x[i], 12));
    const mean = x.reduce((a, b) => a + b, 0) / x.length;
    dctApproximation(x, 1).forEach((v) => expect(v).toBeCloseTo(mean, 12));
  });

  it('its mean squared residual is the predictor\'s L_smooth for one coordinate', () => {
    for (const m of [1, 3, 5, 12]) {
      const approx = dctApproximation(x, m);
      const residual = x.reduce((s, v, i) => s + (v - approx[i]) ** 2, 0) / x.length;
      expect(smoothness(x.subarray(0, 10), x.subarray(10), 10, 1, m)).toBeCloseTo(residual, 12);
    }
  });

  it('more bases never raise the residual', () => {
    let last = Infinity;
    for (let m = 1; m < 20; m++) {
      const l = smoothness(x.subarray(0, 10), x.subarray(10), 10, 1, m);
      expect(l).toBeLessThanOrEqual(last + 1e-15);
      last = l;
    }
  });
});

describe('joining two clips', () => {
  const walk = clip('deepmimic_walk');
  const punch = clip('deepmimic_punch');
  const l = 10;
  const z = joinWindows(clipWindow(walk, walk.frames - l, l), clipWindow(punch, 0, l), l, walk.skeleton);

  it('faces +z on both sides of the join and keeps each side\'s poses (rotation only)', () => {
    expect(facingAngle(z, l - 1, walk.skeleton)).toBeCloseTo(0, 9);
    expect(facingAngle(z, l, walk.skeleton)).toBeCloseTo(0, 9);
    const s = walk.joints * 3;
    const height = (a: ArrayLike<number>, f: number, j: number) => a[f * s + j * 3 + 1];
    expect(height(z, l, 3)).toBeCloseTo(punch.positions[3 * 3 + 1], 6); // y is unchanged by a turn about y
  });

  it('a jump at the join costs more than captured frames do', () => {
    const s = walk.joints * 3;
    const joined = smoothness(z.subarray(0, l * s), z.subarray(l * s), l, s, 5);
    const captured = clipWindow(walk, walk.frames - 2 * l, 2 * l);
    expect(joined).toBeGreaterThan(smoothness(captured.subarray(0, l * s), captured.subarray(l * s), l, s, 5));
    expect(coordinate(z, 2 * l, walk.joints, 0, 1)).toHaveLength(2 * l);
  });
});

describe('PCA and separation', () => {
  const prng = new Prng(5);
  const d = 6;
  const n = 2000;
  // Spread 3 along (1, 1, 0, ...)/sqrt 2, 1 along e_3, 0.1 elsewhere.
  const pts = new Float64Array(n * d);
  for (let i = 0; i < n; i++) {
    const [a, b] = [3 * prng.normal(), prng.normal()];
    for (let j = 0; j < d; j++) pts[i * d + j] = 0.1 * prng.normal();
    pts[i * d] += a / Math.SQRT2;
    pts[i * d + 1] += a / Math.SQRT2;
    pts[i * d + 3] += b;
  }

  it('finds the two directions of largest variance', () => {
    const p = pca2(pts, n, d);
    expect(Math.abs(p.axes[0][0] + p.axes[0][1]) / Math.SQRT2).toBeCloseTo(1, 2);
    expect(Math.abs(p.axes[1][3])).toBeCloseTo(1, 2);
    expect(p.explained[0]).toBeGreaterThan(p.explained[1]);
    const dot = p.axes[0].reduce((s, v, j) => s + v * p.axes[1][j], 0);
    expect(Math.abs(dot)).toBeLessThan(1e-6);
    const proj = p.project(pts, n);
    // The first component's variance is at least the variance along the true direction, and close to it.
    const varX = proj.filter((_, i) => i % 2 === 0).reduce((s, v) => s + v * v, 0) / (n - 1);
    const along = Array.from({ length: n }, (_, i) => (pts[i * d] + pts[i * d + 1]) / Math.SQRT2);
    const m = along.reduce((a, b) => a + b, 0) / n;
    const varTrue = along.reduce((a, v) => a + (v - m) ** 2, 0) / (n - 1);
    expect(varX).toBeGreaterThanOrEqual(varTrue - 1e-9);
    expect(varX / varTrue).toBeLessThan(1.01);
  });

  it('separation: about 0 for one distribution, the shift over the spread for two', () => {
    const a = Float64Array.from({ length: n * 2 }, () => prng.normal());
    const b = Float64Array.from({ length: n * 2 }, () => prng.normal());
    expect(separation(a, b, n, 2)).toBeLessThan(0.1);
    const shifted = b.map((v, i) => (i % 2 === 0 ? v + 4 : v));
    expect(separation(a, shifted, n, 2)).toBeCloseTo(4 / Math.SQRT2, 1);
  });

  it('rejects a shape that does not fit', () => {
    expect(() => pca2(new Float64Array(5), 2, 3)).toThrow(RangeError);
  });
});

describe('keyposes, rebuilt', () => {
  const m = clip('deepmimic_dance_a');

  it('every frame a keypose rebuilds the clip exactly; fewer keyposes, more error', () => {
    const all = Array.from({ length: m.frames }, (_, i) => i);
    expect(mpjpe(rebuildFromKeyposes(m.positions, m.joints, all), m.positions, m.joints)).toBeCloseTo(0, 6);
    const errors = [0.1, 0.3, 1.0].map((t) => mpjpe(rebuildFromKeyposes(m.positions, m.joints, extractKeyposes(m.positions, m.frames, m.joints, t)), m.positions, m.joints));
    expect(errors[0]).toBeLessThan(errors[1]);
    expect(errors[1]).toBeLessThan(errors[2]);
  });

  it('the rebuilt motion passes through every keypose', () => {
    const keys = extractKeyposes(m.positions, m.frames, m.joints, 0.3);
    const r = rebuildFromKeyposes(m.positions, m.joints, keys);
    const s = m.joints * 3;
    for (const k of keys) for (let i = 0; i < s; i++) expect(r[k * s + i]).toBeCloseTo(m.positions[k * s + i], 5);
  });
});

describe('label statistics', () => {
  it('entropy of a uniform distribution over n labels is log2 n', () => {
    expect(entropyBits(new Float64Array(8).fill(1 / 8))).toBeCloseTo(3, 12);
    expect(entropyBits([1, 0, 0])).toBe(0);
  });

  it('top indices, ties by index; distinct labels and constant sequences', () => {
    expect(topIndices([0.1, 0.5, 0.5, 0.2], 3)).toEqual([1, 2, 3]);
    expect(sequenceStats([[3, 3, 3], [3, 4], []])).toEqual({ distinct: 2, constant: 1 });
  });
});

describe('model card (numbers from results.json)', async () => {
  const { dataSummary, findings, classifierCaveats, cardColumns } = await import('../../web/src/model-card/card');
  const { parseResults } = await import('../../web/src/results/data');
  const read = (p: string) => JSON.parse(readFileSync(new URL(p, import.meta.url), 'utf8'));
  const index = read('../../public/clips/index.json');
  const results = parseResults(read('../../public/results.json'));

  it('sums the clips: about 40 s, train and test parts within the whole', () => {
    const d = dataSummary(index);
    const frames = index.clips.reduce((s: number, c: { frames: number }) => s + c.frames, 0);
    expect(d.seconds).toBeCloseTo(frames / index.fps, 9);
    expect(d.trainSeconds + d.testSeconds).toBeLessThanOrEqual(d.seconds + 1e-9);
    expect(d.testSeconds).toBeGreaterThan(0);
    expect(() => dataSummary({ ...index, clips: [] })).toThrow(/no clips/);
  });

  it('every finding quotes numbers that are in results.json, with their source', () => {
    const all = findings(results);
    expect(all.some((f) => f.verdict === 'can')).toBe(true);
    for (const f of all) expect(f.source).toMatch(/^results\.json/);
    // a claim's status is carried over as it is
    for (const c of results.claims) {
      const f = all.find((x) => x.source === `results.json, claim ${c.id}`)!;
      expect(f.text).toContain(`${c.status} here`);
      expect(f.verdict).toBe(c.status === 'holds' ? 'can' : c.status === 'fails' ? 'cannot' : 'unknown');
    }
  });

  it('compares against zero-velocity in the direction the numbers say', () => {
    const t = { ...results.tables[0], id: 'synthetic', title: 'Synthetic', truth: true, horizon_frames: 150, windows: 3, columns: ['mpjpe_h_best'],
      rows: [
        { id: 'zero-velocity', label: 'Zero-velocity', kind: 'model' as const, group: 'baselines', note: '', notes: [], values: { mpjpe_h_best: { mean: 200, std: 0, n: 1 } } },
        { id: 'a', label: 'Model A', kind: 'model' as const, group: 'a', note: '', notes: [], values: { mpjpe_h_best: { mean: 150, std: 0, n: 1 } } },
        { id: 'b', label: 'Model B', kind: 'model' as const, group: 'b', note: '', notes: [], values: { mpjpe_h_best: { mean: 250, std: 0, n: 1 } } },
      ] };
    // older results without paired verdicts: the unpaired fallback
    const all = findings({ ...results, tables: [t], claims: [], skipped: [], verdicts: undefined });
    expect(all.find((f) => f.text.startsWith('Model A'))!.verdict).toBe('can');
    expect(all.find((f) => f.text.startsWith('Model B'))!.verdict).toBe('cannot');
    expect(all.find((f) => f.text.startsWith('Model B'))!.text).toContain('250 mm against 200 mm');
    expect(cardColumns(t)).toEqual(['mpjpe_h_best']);
  });

  it('names the classifiers and the test groups they miss', () => {
    const lines = classifierCaveats(results);
    expect(lines.length).toBe(Object.keys(results.classifiers).filter((k) => !k.endsWith('_shuffled')).length);
    for (const [id, c] of Object.entries(results.classifiers)) {
      if (id.endsWith('_shuffled')) continue;
      for (const [g, r] of Object.entries(c.test_groups)) if (r.accuracy === 0) expect(lines.join(' ')).toContain(g.replace(/_/g, ' '));
    }
  });
});

describe('model card: staleness and failure modes', async () => {
  const { failureModes, staleModels } = await import('../../web/src/model-card/card');
  const { parseResults } = await import('../../web/src/results/data');
  const read = (p: string) => JSON.parse(readFileSync(new URL(p, import.meta.url), 'utf8'));
  const index = read('../../public/clips/index.json');
  const manifest = read('../../public/models/manifest.json');
  const results = parseResults(read('../../public/results.json'));

  it('flags a served model whose hash results.json did not measure', () => {
    const same = { ...manifest, models: manifest.models.filter((m: { id: string; hash: string }) => results.models[m.id] === m.hash) };
    expect(staleModels(results, same)).toEqual([]);
    const changed = { ...manifest, models: [{ ...manifest.models[0], hash: 'sha256:0123456789abcdef' }] };
    expect(staleModels(results, changed)[0].problem).toMatch(/0123456789ab/);
    const unknown = { ...manifest, models: [{ ...manifest.models[0], id: 'not-evaluated' }] };
    expect(staleModels(results, unknown)[0].problem).toMatch(/not in results\.json/);
  });

  it('failure modes quote results.json, and leave out what it does not have', () => {
    const without = failureModes({ ...results, tables: [] }, index, manifest);
    expect(without.some((t) => /Slowing down|Moving too fast|Feet slide|Standing still/.test(t))).toBe(false);
    expect(failureModes(null, index, null).length).toBeGreaterThan(0);
  });
});

describe('model card: Evaluation v3 (a results document from the harness: tests/fixtures/results_v3_tiny.json)', async () => {
  const { cardGaps, dataFacts, failureChecks, findings, horizonFrames, longestTable, paperOf, projectBibtex } = await import('../../web/src/model-card/card');
  const { parseResults } = await import('../../web/src/results/data');
  const { fmt } = await import('../../web/src/results/format');
  const read = (p: string) => JSON.parse(readFileSync(new URL(p, import.meta.url), 'utf8'));
  const index = read('../../public/clips/index.json');
  const manifest = read('../../public/models/manifest.json');
  const doc = parseResults(read('../fixtures/results_v3_tiny.json'));

  it('finds data for every section of the page, and says which section finds none', () => {
    expect(cardGaps(doc, index, manifest)).toEqual([]);
    expect(failureChecks(doc, index, manifest).missing).toEqual([]);
    // a failure-mode section whose table is missing, or a data section without the data, fails the check
    expect(cardGaps({ ...doc, tables: [] }, index, manifest).join(' ')).toMatch(/Known failure modes: results\.json has no a held-out table/);
    expect(cardGaps({ ...doc, data: { ...doc.data!, per_action: undefined } }, index, manifest).join(' ')).toMatch(/The data: results\.json has no data\.per_action/);
    expect(cardGaps({ ...doc, verdicts: undefined }, index, manifest).join(' ')).toMatch(/Against the baselines/);
    const noSpeed = { ...doc, tables: doc.tables.map((t) => ({ ...t, columns: t.columns.filter((c) => !c.startsWith('speed_ratio')) })) };
    expect(cardGaps(noSpeed, index, manifest).join(' ')).toMatch(/speed ratios in table heldout_5s/);
    expect(cardGaps(null, index, manifest)).not.toEqual([]);
    expect(longestTable(doc)!.id).toBe('heldout_5s');
  });

  it('takes the data section from results.json (people, takes and seconds, train and test), not from the served clips', () => {
    const facts = dataFacts(doc)!;
    const d = doc.data!;
    expect(facts.actions.map((a) => a.action)).toEqual(Object.keys(d.per_action!));
    const text = facts.lines.join(' ');
    expect(text).toContain(`${d.heldout_people.length} people (subjects ${d.heldout_people.join(', ')}) give ${d.heldout_takes} takes`);
    expect(text).toContain(`Training: ${d.train_people_list!.length} other performers`);
    expect(text).toContain(`give ${d.train_takes} takes (${d.train_seconds.toFixed(0)} s)`);
    expect(text).not.toMatch(/\(\d+ others are trained on\)/);
    expect(dataFacts(null)).toBeNull();
  });

  it('compares with standing still on the paired numbers of its own verdict, with their count', () => {
    const all = findings(doc);
    for (const v of doc.verdicts!.filter((x) => x.baseline === 'zero-velocity' && x.a_paired !== null)) {
      const title = doc.tables.find((t) => t.id === v.table)!.title;
      const where = `(${title.charAt(0).toLowerCase()}${title.slice(1)}).`;
      const f = all.find((x) => x.text.includes('than standing still') && x.text.endsWith(where)
        && x.text.startsWith(doc.tables.flatMap((t) => t.rows).find((r) => r.id === v.row)!.label));
      expect(f, `${v.row} ${v.table}`).toBeDefined();
      expect(f!.text).toContain(`${fmt(v.a_paired, 'm')} m against ${fmt(v.b_paired!, 'm')} m for zero-velocity on the same ${v.items} windows`);
    }
    // a claim part quotes the paired values, never a row's own mean over other windows
    for (const c of doc.claims) {
      const f = all.find((x) => x.source === `results.json, claim ${c.id}`)!;
      for (const p of c.parts.filter((x) => x.a_paired !== undefined && x.kind !== 'trend')) expect(f.text).toContain(`on the same ${p.items} items`);
    }
  });

  it('names each served model\'s paper and its default horizon, and cites the data as it is', () => {
    expect(paperOf('wat_transformer')).toMatch(/^Weakly-supervised Action Transition Learning for Stochastic Human Motion Prediction \(Mao/);
    expect(paperOf('wat_transformer')).not.toContain('wat_transformer');
    expect(paperOf('keyposes')).toMatch(/^Long Term Motion Prediction Using Keyposes/);
    expect(paperOf('zero_velocity')).toBe('baseline (no paper)');
    const zero = manifest.models.find((m: { id: string }) => m.id === 'zero-velocity');
    expect(horizonFrames(zero, manifest.fps)).toBe(60);           // its horizon control's default, 2 s
    const wat = manifest.models.find((m: { id: string }) => m.id === 'wat-rnn');
    expect(horizonFrames(wat, manifest.fps)).toBe(wat.params.future_frames);
    expect(projectBibtex('1.0')).toContain('CMU motion capture');
    expect(projectBibtex('1.0')).not.toContain('on DeepMimic motion capture');
  });
});

describe('capture and the text alternative of the 3D view', async () => {
  const { captureFileName, captionText, pickWebmType } = await import('../../web/src/ui/capture');
  const { viewSummary } = await import('../../web/src/ui/view-summary');

  it('names files and captions by what is shown', () => {
    const info = { model: 'Keyposes', clip: 'walker walk/forward', seed: 3, selected: 1, k: 5, start: 0, historyFrames: 30 };
    expect(captureFileName(info, 'png')).toBe('motion-futures.walker-walk-forward.Keyposes.seed-3.sample-2.png');
    expect(captionText(info)).toBe('motion futures · Keyposes · walker walk/forward, history frames 0–29 · K = 5 · seed 3 · sample #2 selected');
    expect(captureFileName({}, 'webm')).toBe('motion-futures.webm');
  });

  it('records the first WebM type the browser supports, or says none', () => {
    expect(pickWebmType((t) => t === 'video/webm;codecs=vp8')).toBe('video/webm;codecs=vp8');
    expect(pickWebmType(() => false)).toBeNull();
  });

  it('summarises model, K, actions and lengths', () => {
    const p = { k: 2, lengths: Int32Array.from([30, 45]), samples: [{ segments: [{ action: 'walk' }, { action: 'punch' }] }, { segments: [] }] };
    const text = viewSummary({ clip: 'walker_walk_forward', fps: 30, selected: 1,
      prediction: { model: 'WAT', start: 0, historyFrames: 10, p: p as never } });
    expect(text).toContain('WAT: 2 futures, 1.00 s to 1.50 s long, actions walk then punch.');
    expect(text).toContain('Future #2 is selected (1.50 s).');
    expect(viewSummary({ clip: null, fps: 30, selected: null })).toMatch(/pick a clip/);
  });
});

describe('palette: samples differ by more than hue', () => {
  it('neighbouring samples differ in lightness on both sides', () => {
    const lum = ([r, g, b]: number[]) => 0.2126 * r + 0.7152 * g + 0.0722 * b;
    for (const side of ['left', 'right'] as const) {
      for (let s = 0; s < 9; s++) {
        const a = lum(tintColour(side, { role: 'prediction', sample: s }));
        const b = lum(tintColour(side, { role: 'prediction', sample: s + 1 }));
        expect(Math.abs(a - b), `${side} ${s}/${s + 1}`).toBeGreaterThan(0.04);
      }
    }
  });
});
