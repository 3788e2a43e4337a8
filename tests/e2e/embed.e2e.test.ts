// The widget on someone else's page: one script include, two <motion-futures> tags with
// different models, on a host page elsewhere on the origin. Both render and predict, they share
// one worker and one copy of each model, and keys act on the focused one. Plus embed.html in an iframe.
import { readFileSync } from 'node:fs';
import { afterAll, beforeAll, describe, expect, inject, it } from 'vitest';
import type { Page, Request } from 'playwright-core';
import { openBrowser, type BrowserSession } from './browser';
import { defaultHistory, index } from './data';
import { pixelStats } from './pixels';

const baseUrl = inject('baseUrl');
const origin = new URL(baseUrl).origin;
const NO_PROBLEMS = { consoleErrors: [], pageErrors: [], failedRequests: [] };
const manifest = JSON.parse(readFileSync(new URL('../../public/models/manifest.json', import.meta.url), 'utf8'));
// Two different models: the first two the site lists.
const MODEL_A = manifest.models[0].id as string;
const MODEL_B = manifest.models[1].id as string;
// The host page lives outside the site's folder: assets must resolve from the script, not the page.
const HOST_URL = `${origin}/elsewhere/project/page.html`;
// A training clip for the first widget, the default test history for the second (from the clip index).
const CLIP_A = (index.clips.find((c) => c.role === 'train' && c.frames >= 30) ?? index.clips[0]).name;
const CLIP_B = defaultHistory().clip.name;

const hostPage = (body: string) => `<!doctype html>
<html lang="en"><head><meta charset="utf-8"><title>A project page</title>
<style>body { font-family: serif; margin: 1rem; } button { background: hotpink; } .cols { display: grid; grid-template-columns: 1fr 1.4fr; gap: 1rem; }</style>
</head><body><h1>Our project</h1>${body}</body></html>`;

const TWO = hostPage(`
<script type="module" src="${baseUrl}assets/motion-futures.js"></script>
<div class="cols">
  <motion-futures id="a" model="${MODEL_A}" clip="${CLIP_A}" seed="1" autoplay style="height: 420px"></motion-futures>
  <motion-futures id="b" model="${MODEL_B}" clip="${CLIP_B}" seed="2" controls="full" autoplay style="height: 620px"></motion-futures>
</div>`);

const done = (page: Page, id: string) =>
  page.waitForSelector(`motion-futures#${id}[data-predict-status="done"]`, { state: 'attached', timeout: 120_000 });
const playLabel = (page: Page, id: string) => page.locator(`#${id}`).getByTestId('play').getAttribute('aria-label');
const settle = (page: Page) => page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));

describe('two widgets on a host page', () => {
  let session: BrowserSession;
  let page: Page;
  const modelFiles: string[] = [];

  beforeAll(async () => {
    session = await openBrowser({ viewport: { width: 1280, height: 900 } });
    page = session.page;
    // Requests from the predictor worker count too (the context sees every request).
    session.context.on('request', (r: Request) => { if (r.url().endsWith('.onnx')) modelFiles.push(new URL(r.url()).pathname.split('/').pop()!); });
    await page.route(HOST_URL, (route) => route.fulfill({ status: 200, contentType: 'text/html', body: TWO }));
    await page.goto(HOST_URL);
  });
  afterAll(async () => { await session?.close(); });

  it('both render and both predict, each with its own model', async () => {
    await Promise.all([done(page, 'a'), done(page, 'b')]);
    expect(await page.locator('#a').getAttribute('data-prediction-model')).toBe(MODEL_A);
    expect(await page.locator('#b').getAttribute('data-prediction-model')).toBe(MODEL_B);
    expect(await page.locator('#a').getAttribute('data-current-clip')).toBe(CLIP_A);
    expect(await page.locator('#b').getAttribute('data-current-clip')).toBe(CLIP_B);
    // minimal controls: no side panel, the one-line bar instead; full controls: the panel
    expect(await page.locator('#a #panel').isVisible()).toBe(false);
    expect(await page.locator('#a .mini-bar').isVisible()).toBe(true);
    expect(await page.locator('#b #panel').isVisible()).toBe(true);
    expect(await page.locator('#b .mini-bar').isVisible()).toBe(false);
    // the host page's styles stay out: the widget's buttons are not pink
    const bg = await page.locator('#a .mini-bar button').evaluate((b) => getComputedStyle(b).backgroundColor);
    expect(bg).not.toBe('rgb(255, 105, 180)');

    await page.evaluate(() => { for (const id of ['a', 'b']) { const p = document.querySelector<HTMLElement & { app: { player: { pause(): void; seek(f: number): void } } }>(`#${id}`)!.app.player; p.pause(); p.seek(20); } });
    await settle(page);
    await session.screenshot('embed-two-instances.png');
    for (const id of ['a', 'b']) {
      const stats = await pixelStats(session.context, await session.screenshot(`embed-${id}-stage.png`, page.locator(`#${id} #viewer`)));
      expect(stats.foreground, `widget ${id} draws figures`).toBeGreaterThan(0.01 * stats.width * stats.height);
      expect(stats.distinct, `widget ${id} draws figures`).toBeGreaterThan(30);
    }
    expect(session.problems).toEqual(NO_PROBLEMS);
  });

  it('they share one worker and fetch each model once', async () => {
    expect(page.workers()).toHaveLength(1);
    const graphs = (id: string) => Object.values(manifest.models.find((m: { id: string }) => m.id === id).graphs).map((g) => (g as { file: string }).file);
    const expected = [...new Set([...graphs(MODEL_A), ...graphs(MODEL_B)])].sort();
    expect([...modelFiles].sort()).toEqual(expected);
    // Widget a switches to b's model: already in the worker, nothing is fetched again.
    await page.evaluate(async (model) => {
      const app = document.querySelector<HTMLElement & { app: import('../../web/src/ui/app').App }>('#a')!.app;
      app.predictor.setInputs({ model });
      await app.predictor.predict();
    }, MODEL_B);
    expect(await page.locator('#a').getAttribute('data-prediction-model')).toBe(MODEL_B);
    expect([...modelFiles].sort()).toEqual(expected);
    expect(page.workers()).toHaveLength(1);
  });

  it("a request supersedes only its own widget's earlier one", async () => {
    // a asks twice in a row (its first request may be superseded), b once: b's still comes back.
    const shown = await page.evaluate(async () => {
      const app = (id: string) => document.querySelector<HTMLElement & { app: import('../../web/src/ui/app').App }>(`#${id}`)!.app;
      const a = app('a').predictor;
      const b = app('b').predictor;
      a.last = null;
      b.last = null;
      await Promise.all([a.predict(), a.predict(), b.predict()]);
      return [Boolean(a.last), Boolean(b.last)];
    });
    expect(shown).toEqual([true, true]);
    expect(await page.locator('#a').getAttribute('data-predict-status')).toBe('done');
    expect(await page.locator('#b').getAttribute('data-predict-status')).toBe('done');
    expect(session.problems).toEqual(NO_PROBLEMS);
  });

  it('keys act on the focused widget only', async () => {
    await page.evaluate(() => { for (const id of ['a', 'b']) document.querySelector<HTMLElement & { app: import('../../web/src/ui/app').App }>(`#${id}`)!.app.player.play(); });
    await expect.poll(() => playLabel(page, 'a')).toBe('Pause');
    await expect.poll(() => playLabel(page, 'b')).toBe('Pause');

    await page.locator('#b #viewer').click({ position: { x: 30, y: 30 } });
    expect(await page.evaluate(() => document.activeElement?.id)).toBe('b');
    await page.keyboard.press('Space');
    await expect.poll(() => playLabel(page, 'b')).toBe('Play');
    expect(await playLabel(page, 'a')).toBe('Pause');

    await page.locator('#a #viewer').click({ position: { x: 30, y: 30 } });
    expect(await page.evaluate(() => document.activeElement?.id)).toBe('a');
    await page.keyboard.press('Space');
    await expect.poll(() => playLabel(page, 'a')).toBe('Play');
    expect(await playLabel(page, 'b')).toBe('Play');

    // Nothing focused: a widget on a host page leaves the page's keys alone.
    await page.evaluate(() => (document.activeElement as HTMLElement | null)?.blur());
    await page.keyboard.press('Space');
    await page.waitForTimeout(300); // nothing should start, which only time can show
    expect(await playLabel(page, 'a')).toBe('Play');
    expect(await playLabel(page, 'b')).toBe('Play');
    expect(session.problems).toEqual(NO_PROBLEMS);
  });
});

describe('embed.html in an iframe', () => {
  it('takes the same options as URL parameters', async () => {
    const session = await openBrowser({ viewport: { width: 900, height: 700 } });
    try {
      const { page } = session;
      const src = `${baseUrl}embed.html?model=${MODEL_B}&clip=${CLIP_A}&seed=3&autoplay=1`;
      await page.route(HOST_URL, (route) => route.fulfill({
        status: 200, contentType: 'text/html',
        body: hostPage(`<iframe id="f" src="${src}" width="720" height="460" style="border: 1px solid #999"></iframe>`),
      }));
      await page.goto(HOST_URL);
      const frame = page.frameLocator('#f');
      await frame.locator('motion-futures[data-predict-status="done"]').waitFor({ state: 'attached', timeout: 120_000 });
      const widget = frame.locator('motion-futures');
      expect(await widget.getAttribute('data-prediction-model')).toBe(MODEL_B);
      expect(await widget.getAttribute('data-current-clip')).toBe(CLIP_A);
      expect(await frame.locator('#panel').isVisible()).toBe(false); // minimal by default
      await expect.poll(() => frame.getByTestId('play').getAttribute('aria-label')).toBe('Pause'); // autoplay=1
      await session.screenshot('embed-iframe.png');
      expect(session.problems).toEqual(NO_PROBLEMS);
    } finally {
      await session.close();
    }
  });
});
