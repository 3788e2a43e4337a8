// What the method browser tests share: the predict page opened on the walker's test history, and
// the waits and inputs they drive it with.
import type { Page } from 'playwright-core';
import { openBrowser, type BrowserSession } from './browser';

export const NO_PROBLEMS = { consoleErrors: [], pageErrors: [], failedRequests: [] };

export const predicted = (page: Page) =>
  page.waitForSelector('body[data-predict-status="done"]', { state: 'attached', timeout: 120_000 });
export const failed = (page: Page) =>
  page.waitForSelector('body[data-predict-status="error"]', { state: 'attached', timeout: 60_000 });
/** Mark the status so the next predicted()/failed() waits for the coming prediction, not the last one. */
export const waiting = (page: Page) => page.evaluate(() => { document.body.dataset.predictStatus = 'waiting'; });
export const settle = (page: Page) =>
  page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));

/** Replace the action sequence in the composer. */
export async function compose(page: Page, actions: string[]): Promise<void> {
  await page.locator('.control-actions button', { hasText: 'Clear' }).click();
  for (const a of actions) {
    await page.locator('#control-actions-pick').selectOption(a);
    await page.locator('.control-actions .add-action').click();
  }
}

/** A 1400x1000 page on the site, once the default clip (walker_walk_forward, a test clip) is ready. */
export async function openPredictPage(baseUrl: string): Promise<BrowserSession> {
  const session = await openBrowser({ viewport: { width: 1400, height: 1000 } });
  await session.page.goto(baseUrl);
  await session.page.waitForSelector('body[data-current-clip="walker_walk_forward"][data-clip-status="ready"]',
    { state: 'attached', timeout: 60_000 });
  return session;
}
