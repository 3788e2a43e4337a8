// LCP-VAE and Keyposes in a real Chromium: K = 10 futures from a history of the test split, drawn
// on stage, differing from each other (LCP: positions; Keyposes: label sequences); WAT's prior temperature
// and LCP-VAE's sigma scale at 0 collapse the K futures to one; controls cannot
// leave their range, and a link that asks for it is named. Each number the method adds under the futures
// (LCP-VAE's diversity, Keyposes' counts and pace) explains itself on hover and focus.
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

/** The method's own read-outs under the futures: each number takes the focus and explains itself (its
 *  title, and the hidden sentence it is described by, the same), in words of its own. */
const ownNumbers = (page: Page) => page.locator('.readouts li').evaluateAll((lis) => lis.map((li) => {
  const n = li.querySelector<HTMLElement>('.metric');
  const root = li.getRootNode() as ShadowRoot;
  return { label: li.querySelector('.readout-label')?.textContent ?? '', tab: n?.tabIndex ?? -1, title: n?.getAttribute('title') ?? '',
    described: root.getElementById(n?.getAttribute('aria-describedby') ?? '')?.textContent ?? '' };
}));

function expectExplained(numbers: Awaited<ReturnType<typeof ownNumbers>>, labels: string[]): void {
  expect(numbers.map((x) => x.label)).toEqual(labels);
  for (const x of numbers) {
    expect(x.tab, x.label).toBe(0);
    expect(x.title.length, x.label).toBeGreaterThan(40);
    expect(x.title, x.label).not.toMatch(/as the method measures it/);   // the fallback: the method gave no words
    expect(x.described, x.label).toBe(x.title);
  }
}

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

describe('LCP-VAE, WAT and Keyposes in the browser', () => {
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
    // its diversity beside the read-out's APD: what it is and how it differs, and the bound it names holds
    const numbers = await ownNumbers(page);
    expectExplained(numbers, ['diversity']);
    expect(numbers[0].title).toMatch(/Eq\. 10.*Unlike APD.*at least √18 ≈ 4\.2 × the pose spread/);
    const { diversity, spreadCm } = await page.evaluate(() => {
      const last = window.motionFutures!.predictor.last!;
      return { diversity: last.prediction.readouts![0].value, spreadCm: last.readout!.spreadCm.overFrames };
    });
    expect(diversity).toBeGreaterThanOrEqual(Math.sqrt(18) * spreadCm / 100 - 1e-4);
    await stageShot(session, page, 'lcp-vae-k10.png', 45);
    expect(session.problems).toEqual(NO_PROBLEMS);
  });

  /** The spread control at 0 collapses the K futures to one; past its manifest maximum the slider clamps. */
  async function collapsesAtZero(control: string, max: number): Promise<void> {
    const slider = page.locator(`#control-${control}`);
    const served = await slider.inputValue();
    await slider.fill('0');
    await waiting(page);
    await page.locator('#predict').click();
    await predicted(page);
    expect(await spread(page)).toBeLessThan(1e-6);
    await slider.fill(String(max + 1));
    expect(await slider.inputValue()).toBe(String(max));
    await slider.fill(served);
  }

  it('LCP-VAE at sigma scale 0 decodes one future K times; the slider cannot leave its range', async () => {
    await collapsesAtZero('sigma_scale', 8);      // the manifest's range, 0-8 (export/methods/lcp_vae.py)
  });

  it('WAT at prior temperature 0 decodes the prior mean K times; the slider cannot leave its range', async () => {
    await predictTen(page, 'wat-rnn');
    expect(await spread(page)).toBeGreaterThan(0.01);
    await collapsesAtZero('temperature', 4);      // the manifest's range, 0-4 (export/methods/wat.py)
    expect(session.problems).toEqual(NO_PROBLEMS);
  });

  it('Keyposes draws K = 10 futures with differing keypose label sequences', async () => {
    await predictTen(page, 'keyposes');
    const labels = await page.evaluate(() =>
      window.motionFutures!.predictor.last!.prediction.samples.map((s) => (s as { labels?: number[] }).labels ?? []));
    expect(labels).toHaveLength(10);
    expect(labels.every((l) => l.length >= 2)).toBe(true);
    expect(new Set(labels.map((l) => l.join(','))).size).toBeGreaterThan(1);
    expect(await spread(page)).toBeGreaterThan(0.01);
    expectExplained(await ownNumbers(page), ['observed keyposes', 'keyposes per future', 'travel pace (history / training)']);
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
