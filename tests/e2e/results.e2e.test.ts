// The Results page in a real Chromium: it loads public/results.json, renders the tables, the
// claims and both figures, and records nothing wrong on the page, in light and dark.
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { afterAll, beforeAll, describe, expect, inject, it } from 'vitest';
import type { Page } from 'playwright-core';
import { openBrowser, type BrowserSession } from './browser';

const baseUrl = inject('baseUrl');
const NO_PROBLEMS = { consoleErrors: [], pageErrors: [], failedRequests: [] };
const results = JSON.parse(readFileSync(fileURLToPath(new URL('../../public/results.json', import.meta.url)), 'utf8'));

async function ready(page: Page): Promise<void> {
  await page.goto(new URL('results.html', baseUrl).href);
  await page.waitForSelector('body[data-status="ready"]', { state: 'attached', timeout: 60_000 });
}

describe('results page', () => {
  let session: BrowserSession;
  let page: Page;

  beforeAll(async () => {
    session = await openBrowser({ viewport: { width: 1280, height: 900 } });
    page = session.page;
    await ready(page);
  });
  afterAll(async () => { await session?.close(); });

  it('renders every table with its rows and the stated horizon, held-out tables first', async () => {
    expect(await page.locator('.table-block').count()).toBe(results.tables.length);
    for (const t of results.tables) {
      const block = page.locator(`.table-block[data-table="${t.id}"]`);
      expect(await block.locator('table.main tbody tr').count()).toBe(t.rows.length);
      expect(await block.locator('.table-meta').textContent()).toContain(`horizon ${t.horizon_frames} frames`);
    }
    const order = await page.locator('.table-block').evaluateAll((els) => els.map((e) => e.getAttribute('data-table')));
    const inSample = results.tables.filter((t: { in_sample?: boolean }) => t.in_sample).map((t: { id: string }) => t.id);
    expect(order.slice(order.length - inSample.length)).toEqual(inSample);
    await session.screenshot('results-table.png', page.locator('.table-block').nth(1));
    expect(await page.locator('.claim').count()).toBe(results.claims.length);
    for (const c of results.claims) {
      expect(await page.locator(`.claim[data-claim="${c.id}"] .badge`).textContent()).toBe(c.status);
    }
    expect(await page.locator('[data-sanity]').count()).toBe(results.sanity.length);
    expect(await page.locator('[data-copying]').count()).toBe((results.copying ?? []).length);
    expect(await page.locator('#summary li').count()).toBe((results.summary ?? []).length);
  });

  it('draws diversity against context and the length histograms', async () => {
    const points = page.locator('svg.context-plot g.point');
    expect(await points.count()).toBeGreaterThan(1);
    expect(await page.locator('svg.length-plot rect.bar').count()).toBeGreaterThan(0);
    const box = await page.locator('svg.context-plot').first().boundingBox();
    expect(box!.width).toBeGreaterThan(300);
    await session.screenshot('results.png');
    await session.screenshot('results-figures.png', page.locator('#figures'));
    expect(session.problems).toEqual(NO_PROBLEMS);
  });

  it('works in dark mode', async () => {
    const dark = await openBrowser({ colorScheme: 'dark', viewport: { width: 1280, height: 900 } });
    try {
      await ready(dark.page);
      const bg = await dark.page.evaluate(() => getComputedStyle(document.documentElement).backgroundColor);
      expect(bg).toBe('rgb(21, 25, 30)');
      await dark.screenshot('results-dark.png', dark.page.locator('#figures'));
      expect(dark.problems).toEqual(NO_PROBLEMS);
    } finally {
      await dark.close();
    }
  });
});
