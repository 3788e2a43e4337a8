// What the method browser tests share: the predict page opened on its default test history (the
// clip index's), and the waits and inputs they drive it with.
import { readFileSync } from 'node:fs';
import { writeFile } from 'node:fs/promises';
import { expect } from 'vitest';
import type { Page } from 'playwright-core';
import type { Manifest, ModelEntry } from '../../web/src/contract/types';
import { openBrowser, type BrowserSession } from './browser';
import { defaultHistory } from './data';
import { pixelStats } from './pixels';

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

/** A 1400x1000 page on the site, once the default clip (a test clip, data.ts defaultHistory) is ready. */
export async function openPredictPage(baseUrl: string): Promise<BrowserSession> {
  const session = await openBrowser({ viewport: { width: 1400, height: 1000 } });
  await session.page.goto(baseUrl);
  await session.page.waitForSelector(`body[data-current-clip="${defaultHistory().clip.name}"][data-clip-status="ready"]`,
    { state: 'attached', timeout: 60_000 });
  return session;
}

/** The committed manifest's entry for `id`; a test without its model says how to make it. */
export function servedModel(id: string): ModelEntry {
  const manifest: Manifest = JSON.parse(readFileSync(new URL('../../public/models/manifest.json', import.meta.url), 'utf8'));
  const entry = manifest.models.find((m) => m.id === id);
  if (!entry) throw new Error(`public/models/manifest.json serves no ${id} model: run \`python -m export models --only ${id}\``);
  return entry;
}

/** Pause on `frame`, save the page as /tmp/`name` and check that figures are drawn on stage. */
/** Screenshot the stage at `frame` and check figures cover at least `coverage` of the viewer. Side by side,
 *  each cell is as wide as the futures' widest spread (viewer.ts spread), so a 9 s action sequence of ten
 *  travelling futures draws smaller figures than a 2 s horizon does: those tests pass a lower coverage. */
export async function stageShot(session: BrowserSession, page: Page, name: string, frame: number, coverage = 0.02): Promise<void> {
  await page.evaluate((f) => { const p = window.motionFutures!.player; p.pause(); p.seek(f); }, frame);
  await settle(page);
  await writeFile(`/tmp/${name}`, await session.screenshot(name));
  const stats = await pixelStats(session.context, await session.screenshot(`stage-${name}`, page.locator('#viewer')));
  expect(stats.foreground).toBeGreaterThan(coverage * stats.width * stats.height);   // figures on stage
}
