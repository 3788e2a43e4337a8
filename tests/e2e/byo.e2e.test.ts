// Bring your own motion in a real Chromium: drop a BVH on the page, predict from it, export a GLB;
// a bad file is named and the stage keeps what it had.
import { readFileSync } from 'node:fs';
import { afterAll, beforeAll, describe, expect, inject, it } from 'vitest';
import type { Page } from 'playwright-core';
import { openBrowser, type BrowserSession } from './browser';
import { pixelStats } from './pixels';

const baseUrl = inject('baseUrl');
const NO_PROBLEMS = { consoleErrors: [], pageErrors: [], failedRequests: [] };
const fixture = (name: string) => readFileSync(new URL(`../fixtures/${name}`, import.meta.url), 'utf8');
const status = (page: Page, key: string, value: string) =>
  page.waitForSelector(`body[data-${key}="${value}"]`, { state: 'attached', timeout: 90_000 });
const settle = (page: Page) => page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));

/** Drop files on the widget the way a person does: a drop event carrying a DataTransfer. */
async function drop(page: Page, files: { name: string; text: string }[]): Promise<void> {
  await page.evaluate((fs) => {
    const dt = new DataTransfer();
    for (const f of fs) dt.items.add(new File([f.text], f.name, { type: 'application/octet-stream' }));
    const host = document.querySelector('motion-futures')!;
    host.dispatchEvent(new DragEvent('dragover', { dataTransfer: dt, bubbles: true, cancelable: true }));
    host.dispatchEvent(new DragEvent('drop', { dataTransfer: dt, bubbles: true, cancelable: true }));
  }, files);
}

describe('bring your own motion', () => {
  let session: BrowserSession;
  let page: Page;

  beforeAll(async () => {
    session = await openBrowser();
    page = session.page;
    await page.goto(baseUrl);
    await status(page, 'predict-status', 'done');
  });
  afterAll(async () => { await session?.close(); });

  it('a dropped BVH becomes the history source, and the model predicts from it', async () => {
    await page.evaluate(() => { document.body.dataset.importStatus = 'waiting'; });
    await drop(page, [{ name: 'My Walk.bvh', text: fixture('walk.bvh') }]);
    await status(page, 'import-status', 'done');
    expect(await page.locator('.import-status').textContent()).toMatch(/my_walk: 46 frames at 30 Hz .* from 151 at 100 Hz, joint map cmu-bvh/);
    const stage = await page.evaluate(() => { const s = window.motionFutures!.onStage(); return { name: s.motion?.name, frames: s.motion?.frames, source: s.source }; });
    expect(stage).toEqual({ name: 'my_walk', frames: 46, source: { kind: 'dropped', name: 'My Walk.bvh' } });
    // a dropped file predicts again on its own (issue 20: never stale)
    await page.waitForFunction(() => window.motionFutures!.predictor.last?.clip === 'my_walk' && document.body.dataset.predictStatus === 'done',
      undefined, { timeout: 90_000 });

    await page.locator('#model-select').selectOption('regression-gru');
    await page.locator('#history-start').fill('20');
    await page.locator('#history-start').dispatchEvent('change');
    await page.evaluate(() => { document.body.dataset.predictStatus = 'waiting'; });
    await page.locator('#predict').click();
    await status(page, 'predict-status', 'done');
    expect(await page.locator('.predict-status').textContent()).toMatch(/Regression GRU.*frames 20–29 of my_walk/);
    expect(await page.locator(".history-note").textContent()).toMatch(/from your file My Walk.bvh/);
    await page.evaluate(() => { const p = window.motionFutures!.player; p.pause(); p.seek(22); });
    await settle(page);
    await session.screenshot('byo-dropped-bvh.png');
    const stats = await pixelStats(session.context, await session.screenshot('byo-dropped-bvh-stage.png', page.locator('#viewer')));
    expect(stats.foreground).toBeGreaterThan(0.01 * stats.width * stats.height);
  });

  it('the Export panel saves a GLB of the history and the future', async () => {
    expect(await page.locator('#export-glb').isDisabled()).toBe(false);
    const [download] = await Promise.all([page.waitForEvent('download'), page.locator('#export-glb').click()]);
    expect(download.suggestedFilename()).toBe('my_walk.regression-gru.sample_1.glb');
    const path = await download.path();
    const bytes = readFileSync(path!);
    expect(bytes.subarray(0, 4).toString('latin1')).toBe('glTF');
    const jsonLength = bytes.readUInt32LE(12);
    const gltf = JSON.parse(bytes.subarray(20, 20 + jsonLength).toString('utf8'));
    const names = gltf.nodes.map((n: { name: string }) => n.name);
    expect(names).toContain('history_root');
    expect(names).toContain('sample_1_left_toe');
    expect(gltf.animations).toHaveLength(1);
    const [csv] = await Promise.all([page.waitForEvent('download'), page.locator('#export-csv').click()]);
    expect(readFileSync((await csv.path())!, 'utf8').split('\n')[0]).toBe('figure,frame,time,joint,x,y,z');
    expect(session.problems).toEqual(NO_PROBLEMS);
  });

  it('a bad file is named and the stage keeps the dropped walk and its prediction', async () => {
    await page.evaluate(() => { document.body.dataset.importStatus = 'waiting'; });
    await drop(page, [{ name: 'notes.bvh', text: 'These are my notes, not motion.' }]);
    await status(page, 'import-status', 'error');
    await expect.poll(() => page.locator('.message-text').allTextContents()).toContainEqual(
      'Could not import: notes.bvh: not a BVH file (it must start with a line "HIERARCHY")');
    await drop(page, [{ name: 'odd.bvh', text: fixture('unknown_skeleton.bvh') }]);
    await expect.poll(() => page.locator('.import-status').textContent()).toMatch(/odd.bvh: unknown skeleton for joint map cmu-bvh/);
    await drop(page, [{ name: 'short.bvh', text: fixture('short.bvh') }]);
    await expect.poll(() => page.locator('.import-status').textContent()).toMatch(/short.bvh: too few frames/);
    const stage = await page.evaluate(() => ({ name: window.motionFutures!.onStage().motion?.name, last: window.motionFutures!.predictor.last?.start }));
    expect(stage).toEqual({ name: 'my_walk', last: 20 });
    await settle(page);
    await session.screenshot('byo-bad-file.png');
    expect(session.problems).toEqual(NO_PROBLEMS);
  });

  // last: it replaces the dropped walk the tests above keep on stage
  it('a dropped .asf and .amc pair becomes the history source too', async () => {
    // CMU take 05_02 as its original files (data/cmu/index.json names them)
    const index = JSON.parse(readFileSync(new URL('../../data/cmu/index.json', import.meta.url), 'utf8')) as { take: string; file: string; asf: string }[];
    const e = index.find((t) => t.take === '05_02')!;
    const read = (rel: string) => readFileSync(new URL(`../../data/cmu/${rel}`, import.meta.url), 'utf8');
    const take = { asf_file: e.asf.split('/').pop()!, amc_file: e.file.split('/').pop()!, asf: read(e.asf), amc: read(e.file) };
    await page.evaluate(() => { document.body.dataset.importStatus = 'waiting'; });
    await drop(page, [{ name: take.asf_file, text: take.asf }, { name: take.amc_file, text: take.amc }]);
    await status(page, 'import-status', 'done');
    expect(await page.locator('.import-status').textContent()).toMatch(/: 28\d frames at 30 Hz \(9\.\d s\) from 112\d at 120 Hz, joint map cmu-asf/);
    const source = await page.evaluate(() => window.motionFutures!.onStage().source);
    expect(source).toEqual({ kind: 'dropped', name: take.amc_file });
  });
});
