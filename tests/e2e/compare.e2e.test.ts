// Issue 29 items 2 and 7 in a real Chromium. Compare mode: two models from a permalink on the same
// history end and seed, one labelled row per model on stage, each with its read-out, kept in the link,
// and in an embed through its compare attribute; an unknown model id is named. A refusal: the stage
// drops the previous model's futures, says so in one sentence and offers the nearest start the method
// accepts, which then predicts; a clip with no such start says so.
import { mkdirSync, writeFileSync } from 'node:fs';
import { afterAll, beforeAll, describe, expect, inject, it } from 'vitest';
import type { Page } from 'playwright-core';
import { shortLabel } from '../../web/src/ui/compare';
import { openBrowser, type BrowserSession } from './browser';
import { defaultHistory } from './data';
import { failed, NO_PROBLEMS, predicted, servedModel, settle, waiting } from './predict-page';

const baseUrl = inject('baseUrl');
const SHOTS = '/tmp/h29d';
const A = servedModel('wat-rnn');
const B = servedModel('lcp-vae');
const KEYPOSES = servedModel('keyposes');
const COMPARE = `${A.id},${B.id}`;

/** The prediction figures on stage at `frame`, with their row and label. */
async function figuresAt(page: Page, frame: number) {
  return page.evaluate((f) => {
    const app = window.motionFutures!;
    app.player.pause(); app.player.seek(f);
    return app.view.figures().map((x) => ({ role: x.role, group: x.group, label: x.label, cy: (x.box.top + x.box.bottom) / 2 }));
  }, frame);
}

/** A digest of a float array (exact: the same futures give the same digest). */
const digest = (a: ArrayLike<number>) => { let h = 0; for (let i = 0; i < a.length; i++) h = (h * 31 + Math.round(a[i] * 1e6)) | 0; return h; };

describe('compare mode and refusals', () => {
  let session: BrowserSession;
  let page: Page;

  beforeAll(async () => {
    mkdirSync(SHOTS, { recursive: true });
    session = await openBrowser({ viewport: { width: 1440, height: 900 } });
    page = session.page;
  });
  afterAll(async () => { await session?.close(); });

  it('runs two models from a permalink, one labelled row each, same history end and seed, kept in the link', async () => {
    await page.goto(`${baseUrl}?compare=${COMPARE}&k=3&seed=4&layout=side`);
    await predicted(page);
    await page.waitForSelector(`body[data-compare-models="${COMPARE}"]`, { state: 'attached' });
    const rows = await page.evaluate(() => window.motionFutures!.predictor.last!.compare!.map((r) => ({
      id: r.entry.id, start: r.start, n: r.entry.params.history_frames, k: r.prediction?.k, error: r.error,
      digest: r.prediction ? Array.from(r.prediction.futures.subarray(0, 999)) : null, controls: r.controls,
    })));
    expect(rows.map((r) => r.id)).toEqual([A.id, B.id]);
    expect(rows.map((r) => r.error)).toEqual([undefined, undefined]);
    expect(rows.map((r) => r.k)).toEqual([3, 3]);
    expect(rows[0].start + rows[0].n).toBe(rows[1].start + rows[1].n);   // the same history end, each its own length
    // distinct rows on stage, each figure labelled with its model
    const origin = Math.max(A.params.history_frames, B.params.history_frames);
    const figures = (await figuresAt(page, origin + 20)).filter((f) => f.role === 'prediction');
    expect(figures.filter((f) => f.group === 0)).toHaveLength(3);
    expect(figures.filter((f) => f.group === 1)).toHaveLength(3);
    for (const f of figures) expect(f.label.startsWith(`${shortLabel(f.group === 0 ? A : B)} #`)).toBe(true);
    const rowY = (g: number) => { const ys = figures.filter((f) => f.group === g).map((f) => f.cy); return ys.reduce((a, b) => a + b, 0) / ys.length; };
    expect(Math.abs(rowY(0) - rowY(1))).toBeGreaterThan(30);   // two rows, not one line of six
    // each row's read-out in cm
    const readouts = await page.locator('[data-testid="compare-rows"] li').allTextContents();
    expect(readouts).toHaveLength(2);
    for (const [i, t] of readouts.entries()) {
      expect(t).toContain([A.label, B.label][i]);
      expect(t).toMatch(/per-joint error (\d+\.\d cm|–) · spread \d+\.\d cm/);   // – : the truth ends before the futures
    }
    expect(readouts.some((t) => /per-joint error \d+\.\d cm/.test(t))).toBe(true);
    await settle(page);
    writeFileSync(`${SHOTS}/compare.png`, await session.screenshot('compare.png'));
    writeFileSync(`${SHOTS}/compare-panel.png`, await session.screenshot('compare-panel.png', page.locator('[data-section="compare"]')));
    // the link keeps compare mode; a reload gives the same futures in both rows
    const search = await page.evaluate(() => location.search);
    expect(new URLSearchParams(search).get('compare')).toBe(COMPARE);
    await waiting(page);
    await page.goto(`${baseUrl}${search}`);
    await predicted(page);
    const again = await page.evaluate(() => window.motionFutures!.predictor.last!.compare!.map((r) => Array.from(r.prediction!.futures.subarray(0, 999))));
    expect(again.map(digest)).toEqual(rows.map((r) => digest(r.digest!)));
    // the second row is what LCP-VAE alone predicts from its own history at that seed and K
    const alone = new URLSearchParams({ model: B.id, clip: defaultHistory().clip.name, start: String(rows[1].start), seed: '4', k: '3',
      horizon: String(rows[1].controls.horizon), sigma_scale: String(rows[1].controls.sigma_scale) });
    await waiting(page);
    await page.goto(`${baseUrl}?${alone}`);
    await predicted(page);
    const single = await page.evaluate(() => Array.from(window.motionFutures!.predictor.last!.prediction.futures.subarray(0, 999)));
    expect(digest(single)).toBe(digest(rows[1].digest!));
    expect(session.problems).toEqual(NO_PROBLEMS);
  });

  it('names an unknown model id in the link and shows one model', async () => {
    await page.goto(`${baseUrl}?compare=${A.id},no-such-model`);
    await predicted(page);
    const text = (await page.locator('.message-warning').allTextContents()).join(' ');
    expect(text).toMatch(/'no-such-model', which this site does not serve/);
    expect(await page.evaluate(() => document.body.dataset.compareModels)).toBeUndefined();
    expect(await page.evaluate(() => document.body.dataset.predictionModel)).toBe(A.id);
    expect(session.problems.pageErrors).toEqual([]);
    session.resetProblems();
  });

  it('compares in an embed through its compare attribute', async () => {
    const host = `${new URL(baseUrl).origin}/elsewhere/compare/page.html`;
    await page.route(host, (route) => route.fulfill({ status: 200, contentType: 'text/html', body: `<!doctype html><html lang="en"><head>
      <meta charset="utf-8"><title>Compare</title></head><body><h1>Two methods</h1>
      <script type="module" src="${baseUrl}assets/motion-futures.js"></script>
      <motion-futures id="c" compare="${COMPARE}" k="2" seed="4" style="height: 480px"></motion-futures></body></html>` }));
    await page.goto(host);
    await page.waitForSelector(`motion-futures#c[data-compare-models="${COMPARE}"][data-predict-status="done"]`, { state: 'attached', timeout: 120_000 });
    const labels = await page.locator('#c .figure-label-prediction').allTextContents();
    expect(labels.filter((l) => l.startsWith(`${shortLabel(A)} #`)).length).toBe(2);
    expect(labels.filter((l) => l.startsWith(`${shortLabel(B)} #`)).length).toBe(2);
    expect(session.problems.pageErrors).toEqual([]);
    session.resetProblems();
  });

  it('a refused history clears the old futures, offers the nearest accepted start in one click, and that predicts', async () => {
    const n = KEYPOSES.params.history_frames;
    await page.goto(`${baseUrl}?model=${A.id}&k=3`);
    await predicted(page);
    // the clip with its first 2n frames at three times the body's size (refused: too large a body)
    await waiting(page);
    await page.evaluate(({ giant, first }) => {
      const app = window.motionFutures!;
      const m = app.onStage().motion!;
      const stride = m.joints * 3;
      const positions = m.positions.map((v, i) => (i < giant * stride ? 3 * v : v));
      app.showMotion({ ...m, name: 'giant.bvh', positions, test: [], train: [], origin: { kind: 'dropped-file', file: 'giant.bvh' } },
        { kind: 'dropped', name: 'giant.bvh' });
      app.predictor.setStart(first);
    }, { giant: 2 * n, first: 3 * n });
    await predicted(page);   // WAT's futures from a normal part of the clip
    expect((await figuresAt(page, 20)).some((f) => f.role === 'prediction')).toBe(true);
    await page.evaluate(() => window.motionFutures!.predictor.setStart(0));
    await waiting(page);
    await page.locator('#model-select').selectOption(KEYPOSES.id);
    await failed(page);
    const notice = page.getByTestId('refusal-notice');
    await notice.waitFor();
    expect(await notice.locator('.refusal-text').textContent())
      .toBe(`${KEYPOSES.label} cannot predict from this history (frames 0–${n - 1} of giant.bvh), so no futures are shown.`);
    // nothing of WAT's is left on stage
    expect(await page.evaluate(() => window.motionFutures!.predictor.last)).toBeNull();
    expect(new Set((await figuresAt(page, 5)).map((f) => f.role))).toEqual(new Set(['history']));
    await page.waitForFunction(() => !['searching', undefined].includes(document.body.dataset.refusalSearch), undefined, { timeout: 60_000 });
    const found = Number(await page.evaluate(() => document.body.dataset.refusalSearch));
    expect(found).toBeGreaterThan(0);
    expect(found).toBeLessThan(2 * n);   // the first start whose history is mostly the normal body
    const go = page.getByTestId('refusal-go');
    expect(await go.textContent()).toBe(`Start the history at frame ${found}`);
    writeFileSync(`${SHOTS}/refusal.png`, await session.screenshot('refusal.png'));
    await waiting(page);
    await go.click();
    await predicted(page);
    expect(await page.evaluate(() => [document.body.dataset.predictionModel, window.motionFutures!.predictor.historyStart()])).toEqual([KEYPOSES.id, found]);
    expect(await notice.count()).toBe(0);
    expect((await figuresAt(page, n + 10)).some((f) => f.role === 'prediction')).toBe(true);

    // a clip whose every start is refused says so
    await waiting(page);
    await page.evaluate((frames) => {
      const app = window.motionFutures!;
      const m = app.onStage().motion!;
      const stride = m.joints * 3;
      app.showMotion({ ...m, name: 'all-giant.bvh', frames, positions: m.positions.slice(0, frames * stride).map((v) => 3 * v),
        test: [], train: [], origin: { kind: 'dropped-file', file: 'all-giant.bvh' } }, { kind: 'dropped', name: 'all-giant.bvh' });
    }, n + 40);
    await failed(page);
    await page.waitForSelector('body[data-refusal-search="none"]', { state: 'attached', timeout: 60_000 });
    expect(await page.getByTestId('refusal-way').textContent()).toMatch(new RegExp(`${KEYPOSES.label.replace(/[()]/g, '\\$&')} accepts none of the \\d+ history starts tried across this clip`));
    expect(session.problems).toEqual(NO_PROBLEMS);
  });
});
