// The Results page's pure parts: number formatting, plot geometry, and the results.json check
// (run on the committed public/results.json too).
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';
import { parseResults, ResultsError } from '../../web/src/results/data';
import { cell, extent, fmt, histogramBars, linearScale, niceTicks } from '../../web/src/results/format';

const RESULTS = fileURLToPath(new URL('../../public/results.json', import.meta.url));

describe('formatting', () => {
  it('gives each size its digits', () => {
    expect(fmt(1234.5)).toBe('1235');
    expect(fmt(12.345)).toBe('12.3');
    expect(fmt(0.12345)).toBe('0.123');
    expect(fmt(0.00012345)).toBe('1.2e-4');
    expect(fmt(0)).toBe('0');
    expect(fmt(66.666, '%')).toBe('66.7');
    expect(fmt(null)).toBe('—');
    expect(fmt(Number.NaN)).toBe('—');
  });

  it('writes mean ± std, or the mean alone when the std is 0', () => {
    expect(cell({ mean: 0.5, std: 0.02, n: 9 })).toBe('0.500 ± 0.020');
    expect(cell({ mean: 0.5, std: 0, n: 1 })).toBe('0.500');
    // one run still has the take bootstrap's spread
    expect(cell({ mean: 0.5, std: 0.03, n: 1, seed_std: 0, boot_std: 0.03 })).toBe('0.500 ± 0.030');
    expect(cell(undefined)).toBe('—');
  });
});

describe('plot geometry', () => {
  it('picks round ticks covering the range', () => {
    expect(niceTicks(0, 1, 5)).toEqual([0, 0.2, 0.4, 0.6, 0.8, 1]);
    expect(niceTicks(3, 97, 5)).toEqual([0, 20, 40, 60, 80, 100]);
    expect(niceTicks(2, 2)).toEqual([2, 2.2, 2.4, 2.6, 2.8, 3]);
  });

  it('maps the tick range onto pixels, flipped for y', () => {
    const y = linearScale(0, 1, 300, 20);
    expect(y(0)).toBe(300);
    expect(y(1)).toBe(20);
    expect(y(0.5)).toBe(160);
    expect(y.ticks[0]).toBe(0);
  });

  it('pads the extent of mean ± std', () => {
    const [lo, hi] = extent([{ mean: 1, std: 0.5, n: 2 }, { mean: 3, std: 0, n: 1 }], 0.1);
    expect(lo).toBeCloseTo(0.25);
    expect(hi).toBeCloseTo(3.25);
  });

  it('draws histogram bars scaled to the tallest', () => {
    const bars = histogramBars([1, 4, 0], [0, 10, 20, 30], 30, 40);
    expect(bars.map((b) => b.height)).toEqual([10, 40, 0]);
    expect(bars.map((b) => b.x)).toEqual([0, 10, 20]);
    expect(bars[1]).toMatchObject({ count: 4, from: 10, to: 20 });
    expect(() => histogramBars([1, 2], [0, 10], 30, 40)).toThrow(/2 counts need 3 edges/);
  });
});

describe('results.json', () => {
  it('rejects a wrong document with a message naming the problem', () => {
    expect(() => parseResults(null)).toThrow(ResultsError);
    expect(() => parseResults({ format: 'other' })).toThrow(/format must be "motion-futures\/results"/);
    expect(() => parseResults({ format: 'motion-futures/results', version: 1, tables: 3 })).toThrow(/field tables must be a list/);
    const bad = { format: 'motion-futures/results', version: 1, tables: [{ id: 't', rows: [], columns: ['nope'] }],
      claims: [], sanity: [], skipped: [], classifiers: {}, columns: {} };
    expect(() => parseResults(bad)).toThrow(/table t has unknown column nope/);
  });

  it('accepts the committed results, with every table stating horizon, history and K', () => {
    const doc = parseResults(JSON.parse(readFileSync(RESULTS, 'utf8')));
    expect(doc.tables.length).toBeGreaterThan(0);
    for (const t of doc.tables) {
      expect(t.horizon_frames).toBeGreaterThan(0);
      if (t.truth) expect(t.history_frames).toBeGreaterThan(0);
      expect(t.k).toBeGreaterThan(0);
    }
    const statuses = ['holds', 'fails', 'inconclusive', 'no difference', 'insufficient data', 'unusable', 'not evaluated', 'by construction'];
    expect(doc.claims.every((c) => statuses.includes(c.status))).toBe(true);
  });

  it('tables back claims only on held-out people, and each held-out table has the copying baselines', () => {
    const doc = parseResults(JSON.parse(readFileSync(RESULTS, 'utf8')));
    const inSample = new Set(doc.tables.filter((t) => t.in_sample).map((t) => t.id));
    for (const t of doc.tables) expect(t.source === 'test' || t.in_sample).toBe(true);
    for (const c of doc.claims) for (const p of c.parts) expect(inSample.has(p.table)).toBe(false);
    for (const t of doc.tables.filter((x) => x.source === 'test' && x.truth)) {
      const ids = new Set(t.rows.filter((r) => r.values).map((r) => r.id));
      expect(ids.has('nearest-window') && ids.has('repeat-cycle-60')).toBe(true);
    }
    expect(doc.summary!.length).toBeGreaterThan(0);
    expect(doc.summary!.length).toBeLessThanOrEqual(5);
  });
});

describe('claim parts', async () => {
  const { partText } = await import('../../web/src/results/render');
  const doc = { columns: { ade: { label: 'ADE', unit: 'm', better: 'lower' } } } as unknown as Parameters<typeof partText>[0];
  const base = { table: 'heldout_2s', a: 'wat-rnn', b: 'zero-velocity', metric: 'ade', metric_b: 'ade', direction: 'less', missing: [],
    a_value: { mean: 0.7, std: 0.03, n: 3 }, b_value: { mean: 0.8, std: 0.05, n: 1 }, difference: -0.1, bar: 0.04, people: 6, takes: 19, items: 70 };

  it('state both rows on the items both predict, the count, the bar, p and Holm, the people and takes and the status', () => {
    const t = partText(doc, { ...base, status: 'holds', a_paired: 0.7, b_paired: 0.8, p: 0.001, p_holm: 0.02 });
    expect(t).toBe('wat-rnn 0.700 vs zero-velocity 0.800 (ADE, heldout_2s; on the 70 items both predict, 6 people, 19 takes; difference -0.100, 2σ 0.040, p 1.0e-3, Holm-adjusted 0.020): holds');
  });

  it('never print a row\'s own mean beside the other\'s when it predicted fewer windows; an unusable part says what the data would say', () => {
    const t = partText(doc, { ...base, status: 'unusable', data_status: 'inconclusive', a_paired: 0.65, b_paired: 0.82, items: 40, reason: 'the classifier failed its check' });
    expect(t).toContain('wat-rnn 0.650 vs zero-velocity 0.820 (ADE, heldout_2s; on the 40 items both predict');
    expect(t).not.toContain('0.700');
    expect(t).toMatch(/: unusable; the data would say: inconclusive \(the classifier failed its check\)$/);
  });
});

describe('Evaluation v3 on the page (a results document from the harness: tests/fixtures/results_v3_tiny.json)', async () => {
  const { rulesText, statusClass } = await import('../../web/src/results/render');
  const { windowsText, rowLabel } = await import('../../web/src/results/rows');
  const { beatenLine, verdictGrid, verdictText, labelFor } = await import('../../web/src/results/verdicts');
  const doc = parseResults(JSON.parse(readFileSync(fileURLToPath(new URL('../fixtures/results_v3_tiny.json', import.meta.url)), 'utf8')));

  it('prints every verdict beside its own paired numbers and their count', () => {
    const { lines } = verdictGrid(doc);
    const shown = lines.flatMap((l) => l.cells).filter((v) => v !== null);
    expect(shown.length).toBe(doc.verdicts!.length);
    for (const v of doc.verdicts!) {
      const text = verdictText(doc, v);
      if (v.a_paired === null) { expect(text).toMatch(/no windows both predict$/); continue; }
      expect(text).toContain(`(${v.status}): ${fmt(v.a_paired, 'm')} m against ${fmt(v.b_paired, 'm')} m on the same ${v.items} windows`);
    }
  });

  it('says plainly which served learned models beat each baseline, counting no baseline or ablation', () => {
    const line = beatenLine(doc, 'zero-velocity')!;
    expect(line.startsWith('No served learned model is shown to beat zero-velocity at 1 s or 2 s')).toBe(true);
    const one = { ...doc, verdicts: doc.verdicts!.map((v) => (v.row === 'keyposes' && v.table === 'heldout_2s' && v.baseline === 'zero-velocity' ? { ...v, status: 'holds' } : v)) };
    expect(beatenLine(one, 'zero-velocity')).toMatch(/^Shown to beat zero-velocity .*: Keyposes \(T = 0\.3, refined: served\) at 2 s; not shown/);
    const learned = new Set(doc.served_learned!.map((r) => labelFor(doc, r)));
    expect(learned.has('Zero-velocity')).toBe(false);
    expect(beatenLine(doc, 'regression-gru')).not.toContain('Regression GRU,');   // never against itself
  });

  it('states the rules with the document\'s own minimums, Holm and the comparison counts, and "no difference" has its badge', () => {
    const text = rulesText(doc);
    expect(text).toContain(`fewer than ${doc.min_people} held-out people or ${doc.min_takes} held-out takes`);
    expect(text).toContain(`${doc.comparisons!.claims} claim parts; ${doc.comparisons!.copying} copying comparisons`);
    expect(text).toContain('Holm');
    expect(rulesText({ ...doc, min_people: undefined, min_takes: undefined })).not.toMatch(/fewer than \d/);   // no assumed numbers
    expect(statusClass('no difference')).toBe('status-nodifference');
    expect(new Set(['holds', 'fails', 'inconclusive', 'no difference', 'unusable'].map(statusClass)).size).toBe(5);
  });

  it('gives a refusing row its refusal rate and marks a row that does not predict', () => {
    const t = doc.tables.find((x) => x.id === 'heldout_2s')!;
    const kp = t.rows.find((r) => r.id === 'keyposes')!;
    expect(windowsText(kp, t)).toBe(`${kp.items}/${t.items} (${fmt(100 * kp.refused!.items / t.items!, '%')}% refused)`);
    expect(windowsText(t.rows.find((r) => r.id === 'oracle')!, t)).toBe(`${t.items}/${t.items}`);
    expect(rowLabel({ ...kp, flag: 'the output guard cuts 66% of its samples' })).toBe(`${kp.label} — does not predict: the output guard cuts 66% of its samples`);
  });
});
