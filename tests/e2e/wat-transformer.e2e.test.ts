// WAT (Transformer) in a real Chromium: the same WAT predictor and UI as the RNN, another manifest
// entry. Select it, compose a 3-action sequence, predict K = 10 futures from a test-split history,
// and check the per-sample segments, stop lengths and variance curves it returns.
import { afterAll, beforeAll, describe, expect, inject, it } from 'vitest';
import type { Page } from 'playwright-core';
import type { WatParams } from '../../web/src/predictor/wat';
import type { BrowserSession } from './browser';
import { compose, NO_PROBLEMS, openPredictPage, predicted, servedModel, stageShot, waiting } from './predict-page';

const baseUrl = inject('baseUrl');
const entry = servedModel('wat-transformer');
const params = entry.params as unknown as WatParams;
/** Walk, punch, jump when the model knows those actions, else its first three (the manifest's). */
const WANTED = ['walk', 'punch', 'jump'];
const SEQUENCE = WANTED.every((a) => params.actions.includes(a)) ? WANTED : params.actions.slice(0, 3);
const pretty = (a: string) => a.replace(/_/g, ' ');


describe('WAT (Transformer) in the browser', () => {
  let session: BrowserSession;
  let page: Page;

  beforeAll(async () => {
    session = await openPredictPage(baseUrl);
    page = session.page;
  });
  afterAll(async () => { await session?.close(); });

  it(`is a model of its own that predicts ${SEQUENCE.join(' -> ')} with per-sample stops`, async () => {
    expect(entry.method).toBe('wat_transformer');
    await page.locator('#model-select').selectOption('wat-transformer');
    expect(await page.locator('.history-note').textContent()).toMatch(/test part/);
    await page.locator('#control-k').fill('10');
    await compose(page, SEQUENCE);
    expect(await page.locator('.action-chip').allTextContents()).toEqual(SEQUENCE.map((a, i) => `${i + 1}. ${pretty(a)}×`));
    await waiting(page);
    await page.locator('#predict').click();
    await predicted(page);

    const d = await page.evaluate(() => ({ ...document.body.dataset }));
    expect(d.predictionModel).toBe('wat-transformer');
    expect(d.predictionK).toBe('10');
    const lengths = d.predictionLengths!.split(',').map(Number);
    const { min_frames: tMin } = params.stop;
    expect(lengths).toHaveLength(10);
    expect(lengths.every((l) => l >= 3 * tMin && l <= 3 * params.future_frames)).toBe(true);

    const samples = await page.evaluate(() => window.motionFutures!.predictor.last!.prediction.samples);
    for (const [i, s] of samples.entries()) {
      expect(s.segments.map((g) => g.action)).toEqual(SEQUENCE);
      expect(s.segments.reduce((c, g) => c + g.length, 0)).toBe(lengths[i]);
      for (const g of s.segments) {
        expect(g.length).toBeGreaterThanOrEqual(tMin);
        expect(g.stopped).toBe(g.length < params.future_frames);
        expect(g.flagged).toBe(g.smoothness! > params.smoothness.flag_threshold);
      }
    }
    expect(await page.locator('.sample-item').count()).toBe(10);
    expect(await page.locator('figure.curve svg.curve-plot path').count()).toBe(10);

    await stageShot(session, page, 'wat-transformer.png', 40, 0.008);
    expect(session.problems).toEqual(NO_PROBLEMS);
  });
});
