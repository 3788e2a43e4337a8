// LCP-VAE and Keyposes in a real Chromium: K = 10 futures from a history of the test split, drawn
// on stage, differing from each other (LCP: positions; Keyposes: label sequences); controls cannot
// leave their range, and a link that asks for it is named.
import { afterAll, beforeAll, describe, expect, inject, it } from 'vitest';
import type { Page } from 'playwright-core';
import type { BrowserSession } from './browser';
import { NO_PROBLEMS, openPredictPage, predicted, stageShot, waiting } from './predict-page';

const baseUrl = inject('baseUrl');


/** Mean over frames and joints of the spread between the K futures (metres). */
const spread = (page: Page) => page.evaluate(() => {
  const p = window.motionFutures!.predictor.last!.prediction;
  const n = p.frames * p.joints * 3;
  let total = 0;
  for (let i = 0; i < n; i++) {
    let m = 0;
    for (let q = 0; q < p.k; q++) m += p.futures[q * n + i];
    m /= p.k;
    for (let q = 0; q < p.k; q++) total += (p.futures[q * n + i] - m) ** 2;
  }
  return Math.sqrt(total / (p.k * n / 3));
});

async function predictTen(page: Page, model: string): Promise<void> {
  await page.locator('#model-select').selectOption(model);
  expect(await page.locator('.history-note').textContent()).toMatch(/test part/);
  await page.locator('#control-k').fill('10');
  await waiting(page);
  await page.locator('#predict').click();
  await predicted(page);
  const d = await page.evaluate(() => ({ ...document.body.dataset }));
  expect(d.predictionModel).toBe(model);
  expect(d.predictionK).toBe('10');
}

describe('LCP-VAE and Keyposes in the browser', () => {
  let session: BrowserSession;
  let page: Page;

  beforeAll(async () => {
    session = await openPredictPage(baseUrl);
    page = session.page;
  });
  afterAll(async () => { await session?.close(); });

  it('LCP-VAE draws K = 10 different futures from a test-split history', async () => {
    await predictTen(page, 'lcp-vae');
    expect(await spread(page)).toBeGreaterThan(0.01);
    expect(await page.locator('.sample-item').count()).toBe(10);
    await stageShot(session, page, 'lcp-vae-k10.png', 45);
    expect(session.problems).toEqual(NO_PROBLEMS);
  });

  it('LCP-VAE at sigma scale 0 decodes one future K times; the slider cannot leave its range', async () => {
    await page.locator('#control-sigma_scale').fill('0');
    await waiting(page);
    await page.locator('#predict').click();
    await predicted(page);
    expect(await spread(page)).toBeLessThan(1e-6);
    await page.locator('#control-sigma_scale').fill('3');
    expect(await page.locator('#control-sigma_scale').inputValue()).toBe('2');
    await page.locator('#control-sigma_scale').fill('1');
  });

  it('Keyposes draws K = 10 futures with differing keypose label sequences', async () => {
    await predictTen(page, 'keyposes');
    const labels = await page.evaluate(() =>
      window.motionFutures!.predictor.last!.prediction.samples.map((s) => (s as { labels?: number[] }).labels ?? []));
    expect(labels).toHaveLength(10);
    expect(labels.every((l) => l.length >= 2)).toBe(true);
    expect(new Set(labels.map((l) => l.join(','))).size).toBeGreaterThan(1);
    expect(await spread(page)).toBeGreaterThan(0.01);
    await stageShot(session, page, 'keyposes-k10.png', 45);
    expect(session.problems).toEqual(NO_PROBLEMS);
  });

  it('a link asking Keyposes for temperature 0 is named, and the page still predicts', async () => {
    await page.goto(`${baseUrl}?model=keyposes&temperature=0`);
    await predicted(page);
    await expect.poll(() => page.locator('.message-warning').allTextContents())
      .toEqual(expect.arrayContaining([expect.stringMatching(/\(temperature\) must be between 0.05 and 1.5, got 0/)]));
    expect(await page.evaluate(() => document.body.dataset.predictionModel)).toBe('keyposes');
  });
});
