// WAT (RNN) in a real Chromium: compose a 3-action sequence, predict K = 10 futures from a history of
// the test split, and read each sample's length, its segments' smoothness (flagged above the
// manifest's threshold) and the variance curves with delta and T_min marked; bad input is named.
import { writeFile } from 'node:fs/promises';
import { afterAll, beforeAll, describe, expect, inject, it } from 'vitest';
import type { Page } from 'playwright-core';
import type { WatParams } from '../../web/src/predictor/wat';
import type { BrowserSession } from './browser';
import { defaultHistory, index } from './data';
import { compose, failed, NO_PROBLEMS, openPredictPage, predicted, servedModel, stageShot, waiting } from './predict-page';

const baseUrl = inject('baseUrl');
const entry = servedModel('wat-rnn');
const params = entry.params as unknown as WatParams;
/** Walk, punch, jump when the model knows those actions, else its first three (the manifest's). */
const WANTED = ['walk', 'punch', 'jump'];
const SEQUENCE = WANTED.every((a) => params.actions.includes(a)) ? WANTED : params.actions.slice(0, 3);
const pretty = (a: string) => a.replace(/_/g, ' ');


describe('WAT (RNN) in the browser', () => {
  let session: BrowserSession;
  let page: Page;

  beforeAll(async () => {
    session = await openPredictPage(baseUrl);
    page = session.page;
  });
  afterAll(async () => { await session?.close(); });

  it('asks for the action a newly picked clip shows, until the user composes a sequence', async () => {
    const chips = () => page.locator('.action-chip').allTextContents();
    const asChips = (seq: string[]) => seq.map((a, i) => `${i + 1}. ${pretty(a)}×`);
    const pick = async (name: string) => {
      await page.locator(`[data-clip="${name}"]`).click();
      await page.waitForSelector(`body[data-current-clip="${name}"][data-clip-status="ready"]`, { state: 'attached' });
    };
    const home = defaultHistory().clip;
    // a held-out clip of another action the model knows (a dance, a kick, ...)
    const other = index.clips.find((c) => c.role === 'test' && c.action !== home.action && params.actions.includes(c.action))!;
    expect(other, 'a test clip of a second known action').toBeTruthy();
    await page.locator('#model-select').selectOption('wat-rnn');
    expect(params.actions).toContain(home.action);
    expect(await chips()).toEqual(asChips([home.action]));
    await pick(other.name);
    expect(await chips()).toEqual(asChips([other.action]));
    // another model starts from its default sequence, which then follows the clip too
    const transformer = servedModel('wat-transformer');
    await page.locator('#model-select').selectOption(transformer.id);
    const knows = (transformer.params as unknown as WatParams).actions.includes(other.action);
    const fallback = (transformer.controls.find((c) => c.type === 'actions')?.default ?? []) as string[];
    expect(await chips()).toEqual(asChips(knows ? [other.action] : fallback));
    await page.locator('#model-select').selectOption('wat-rnn');
    // a composed sequence is the user's: a new clip leaves it
    const composed = [home.action, other.action];
    await compose(page, composed);
    await pick(home.name);
    expect(await chips()).toEqual(asChips(composed));
    expect(session.problems.pageErrors).toEqual([]);
  });

  it(`predicts K = 10 futures for ${SEQUENCE.join(' -> ')} from a test-split history`, async () => {
    await page.locator('#model-select').selectOption('wat-rnn');
    // the default history is on a test part
    expect(await page.locator('.history-note').textContent()).toMatch(/test part/);
    await page.locator('#control-k').fill('10');
    await compose(page, SEQUENCE);
    expect(await page.locator('.action-chip').allTextContents()).toEqual(SEQUENCE.map((a, i) => `${i + 1}. ${pretty(a)}×`));
    await waiting(page);
    await page.locator('#predict').click();
    await predicted(page);

    const d = await page.evaluate(() => ({ ...document.body.dataset }));
    expect(d.predictionModel).toBe('wat-rnn');
    expect(d.predictionK).toBe('10');
    const lengths = d.predictionLengths!.split(',').map(Number);
    expect(lengths).toHaveLength(10);
    const { min_frames: tMin, delta } = params.stop;
    const tMax = params.future_frames;
    expect(lengths.every((l) => l >= 3 * tMin && l <= 3 * tMax)).toBe(true);

    // what the worker returned: three segments per sample, in order, their lengths adding up
    const samples = await page.evaluate(() => window.motionFutures!.predictor.last!.prediction.samples);
    for (const [i, s] of samples.entries()) {
      expect(s.segments.map((g) => g.action)).toEqual(SEQUENCE);
      expect(s.segments.reduce((c, g) => c + g.length, 0)).toBe(lengths[i]);
      for (const g of s.segments) expect(g.flagged).toBe(g.smoothness! > params.smoothness.flag_threshold);
    }

    // the read-out: one row per sample, each with its three segments' length and smoothness
    expect(await page.locator('.sample-item').count()).toBe(10);
    const rows = await page.locator('.sample-item').first().locator('.segment-list li').allTextContents();
    expect(rows).toHaveLength(3);
    rows.forEach((r, j) => expect(r).toMatch(new RegExp(`^${pretty(SEQUENCE[j])} · [0-9.]+ s · smoothness [0-9.]+e[-+][0-9]+ m²`)));
    const flaggedRows = samples.reduce((c, s) => c + s.segments.filter((g) => g.flagged).length, 0);
    expect(await page.locator('.segment-flagged').count()).toBe(flaggedRows);

    // the variance plot: one curve per sample, delta and T_min marked
    const plot = page.locator('figure.curve svg.curve-plot');
    expect(await plot.locator('path').count()).toBe(10);
    expect(await plot.locator('.plot-label').allTextContents()).toEqual(expect.arrayContaining(['delta', 'T_min']));
    expect(await plot.locator('.plot-level').count()).toBe(1);
    expect(await plot.locator('.plot-mark').count()).toBeGreaterThanOrEqual(1);
    expect(await plot.locator('circle.plot-transition').count()).toBe(10 * (SEQUENCE.length - 1));   // each sample's 2 transitions
    expect(await page.locator('figure.curve figcaption').textContent()).toMatch(/Eq\. 8/);
    expect(delta).toBeGreaterThan(0);

    await stageShot(session, page, 'wat-rnn.png', 40, 0.008);
    // the read-out and the plot (below the fold of the page)
    await writeFile('/tmp/wat-rnn-futures.png', await session.screenshot('wat-rnn-futures.png', page.locator('[data-section="prediction"]')));
    expect(session.problems).toEqual(NO_PROBLEMS);
  });

  it('an empty action sequence is named, not predicted', async () => {
    await page.locator('.control-actions button', { hasText: 'Clear' }).click();
    await waiting(page);
    await page.locator('#predict').click();
    await failed(page);
    expect(await page.locator('.predict-status').textContent()).toMatch(/the action sequence is empty/);
    session.resetProblems();
  });

  it('K outside 1-50 is named, not predicted', async () => {
    await compose(page, [SEQUENCE[0]]);
    await page.locator('#control-k').fill('60');
    await waiting(page);
    await page.locator('#predict').click();
    await failed(page);
    expect(await page.locator('.predict-status').textContent()).toMatch(/K must be an integer from 1 to 50, got 60/);
    // and a valid K predicts again
    await page.locator('#control-k').fill('3');
    await waiting(page);
    await page.locator('#predict').click();
    await predicted(page);
    expect(await page.evaluate(() => document.body.dataset.predictionK)).toBe('3');
  });
});
