// The end-to-end slice in a real Chromium: manifest -> worker -> predictor -> three.js.
import { readFileSync } from 'node:fs';
import { afterAll, beforeAll, describe, expect, inject, it } from 'vitest';
import type { Page } from 'playwright-core';
import { openBrowser, type BrowserSession } from './browser';
import { defaultHistory, otherClip } from './data';
import { pixelStats } from './pixels';
import { clipTitle } from '../../web/src/ui/clip-name';

const baseUrl = inject('baseUrl');
const NO_PROBLEMS = { consoleErrors: [], pageErrors: [], failedRequests: [] };
const manifest = JSON.parse(readFileSync(new URL('../../public/models/manifest.json', import.meta.url), 'utf8'));
// The history the page opens on, and another clip to switch to (both from the clip index).
const HOME = defaultHistory();
const OTHER = otherClip(HOME.clip.name).name;

const predicted = (page: Page) =>
  page.waitForSelector('body[data-predict-status="done"]', { state: 'attached', timeout: 90_000 });
const settle = (page: Page) => page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));

describe('predicting in the browser', () => {
  let session: BrowserSession;
  let page: Page;

  beforeAll(async () => {
    session = await openBrowser();
    page = session.page;
    await page.goto(baseUrl);
  });
  afterAll(async () => { await session?.close(); });

  it('shows futures on load, from a test clip, without being asked', async () => {
    await predicted(page);
    expect(await page.evaluate(() => document.body.dataset.currentClip)).toBe(HOME.clip.name);
    expect(await page.locator('#history-start').inputValue()).toBe(String(HOME.start));
    expect(await page.locator('.history-note').textContent()).toMatch(/test part/);
    expect(await page.locator('.sample-item').count()).toBeGreaterThan(0);
    // The page loaded the model on its own as soon as the manifest was in (PredictController.warm).
    const marks = await page.evaluate(() => Object.fromEntries(performance.getEntriesByType('mark').map((m) => [m.name, m.startTime])));
    expect(marks['mf:model-loaded']).toBeGreaterThan(0);
    expect(marks['mf:model-loaded']).toBeLessThanOrEqual(marks['mf:prediction-received']);
  });

  it('the regression baseline predicts from the default test history, shown beside the ground truth', async () => {
    await page.locator('#model-select').selectOption('regression-gru');
    await page.locator('input[name="layout"][value="side"]').check();
    await page.evaluate(() => { document.body.dataset.predictStatus = 'waiting'; });
    await page.locator('#predict').click();
    await predicted(page);
    const d = await page.evaluate(() => ({ ...document.body.dataset }));
    expect(d.predictionModel).toBe('regression-gru');
    expect(d.predictionK).toBe('1');
    const horizon = manifest.models.find((m: { id: string }) => m.id === 'regression-gru')
      .controls.find((c: { id: string }) => c.id === 'horizon').default * 30;
    expect(d.predictionLengths).toBe(String(horizon));
    // the tracks on stage: history, the truth that exists in the clip, one future
    const tracks = await page.evaluate(() => window.motionFutures!.predictor.last!.prediction.frames);
    expect(tracks).toBe(horizon);
    expect(await page.locator('.sample-item').count()).toBe(1);
    const regressionFrames = manifest.models.find((m: { id: string }) => m.id === 'regression-gru').params.history_frames as number;
    // the clip by its readable name (ui/clip-name.ts), as every text on the page names it
    expect(await page.locator('.predict-status').textContent()).toContain(`Regression GRU (deterministic baseline): 1 future from frames ${HOME.start}–${HOME.start + regressionFrames - 1} of ${clipTitle(HOME.clip)}`);
    await page.evaluate(() => { const p = window.motionFutures!.player; p.pause(); p.seek(25); });
    await settle(page);
    await session.screenshot('predict-regression.png');
    const stats = await pixelStats(session.context, await session.screenshot('predict-regression-stage.png', page.locator('#viewer')));
    // two figures (truth and the future) are drawn on the grid
    expect(stats.foreground).toBeGreaterThan(0.02 * stats.width * stats.height);
    expect(stats.distinct).toBeGreaterThan(40);
    expect(session.problems).toEqual(NO_PROBLEMS);
  });

  it('P predicts again and digits select a sample', async () => {
    await page.evaluate(() => { document.body.dataset.predictStatus = 'waiting'; (document.activeElement as HTMLElement | null)?.blur(); });
    await page.keyboard.press('p');
    await predicted(page);
    await page.keyboard.press('1');
    expect(await page.locator('.sample-button').first().getAttribute('aria-pressed')).toBe('true');
    await page.keyboard.press('0');
    expect(await page.locator('.sample-button').first().getAttribute('aria-pressed')).toBe('false');
  });
});

describe('prediction failures stay visible', () => {
  it('a missing model file is named, and the clips still play', async () => {
    const session = await openBrowser();
    try {
      const { page } = session;
      await page.route('**/models/regression-gru.predict.onnx', (route) => route.fulfill({ status: 404, body: 'gone' }));
      await page.goto(`${baseUrl}?model=regression-gru`);
      await page.waitForSelector('body[data-predict-status="error"]', { state: 'attached', timeout: 90_000 });
      await expect.poll(() => page.locator('.message-error').first().textContent())
        .toMatch(/models\/regression-gru\.predict\.onnx could not be loaded \(HTTP 404\)/);
      await page.locator(`[data-clip="${OTHER}"]`).click();
      await page.waitForSelector(`body[data-current-clip="${OTHER}"][data-clip-status="ready"]`, { state: 'attached' });
      expect(session.problems.pageErrors).toEqual([]);
    } finally {
      await session.close();
    }
  });

  it('a manifest missing a field is named, and the clip viewer keeps working', async () => {
    const session = await openBrowser();
    try {
      const { page } = session;
      const broken = { ...manifest, models: manifest.models.map((m: Record<string, unknown>) => ({ ...m, hash: undefined })) };
      await page.route('**/models/manifest.json', (route) => route.fulfill({ status: 200, contentType: 'application/json', body: JSON.stringify(broken) }));
      await page.goto(baseUrl);
      await page.waitForSelector('body[data-predict-status="unavailable"]', { state: 'attached', timeout: 60_000 });
      await expect.poll(() => page.locator('.message-error').first().textContent())
        .toMatch(/models\/manifest\.json: field models\/0\/hash: is missing/);
      await page.waitForSelector(`body[data-current-clip="${HOME.clip.name}"][data-clip-status="ready"]`, { state: 'attached' });
      expect(session.problems).toEqual(NO_PROBLEMS);
    } finally {
      await session.close();
    }
  });

  it('without WebAssembly the page says models cannot run, and the clips still play', async () => {
    const session = await openBrowser();
    try {
      const { page } = session;
      await page.addInitScript(() => { delete (window as { WebAssembly?: unknown }).WebAssembly; });
      await page.goto(baseUrl);
      await page.waitForSelector('body[data-predict-status="error"]', { state: 'attached', timeout: 60_000 });
      await expect.poll(() => page.locator('.message-error').first().textContent()).toMatch(/WebAssembly is not available/);
      await page.locator(`[data-clip="${OTHER}"]`).click();
      await page.waitForSelector(`body[data-current-clip="${OTHER}"][data-clip-status="ready"]`, { state: 'attached' });
      expect(session.problems.pageErrors).toEqual([]);
    } finally {
      await session.close();
    }
  });
});
