// Offline use: after one visit the service worker serves everything (checked per response, so
// the HTTP cache cannot pass for it); no request ever leaves 127.0.0.1; and the built folder runs
// from the one-line static server the README documents.
import { spawn } from 'node:child_process';
import { existsSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, inject, it } from 'vitest';
import type { Page, Response } from 'playwright-core';
import { openBrowser, type BrowserSession } from './browser';
import { defaultHistory, otherClip } from './data';
import { pixelStats } from './pixels';
import { freePort, ROOT } from './server';

const baseUrl = inject('baseUrl');
const NO_PROBLEMS = { consoleErrors: [], pageErrors: [], failedRequests: [] };
const manifest = JSON.parse(readFileSync(new URL('../../public/models/manifest.json', import.meta.url), 'utf8'));
// Every file a model needs: its graphs and its JSON files (e.g. keypose centres).
const modelFiles: string[] = manifest.models.flatMap((m: { graphs: Record<string, { file: string }>; files?: Record<string, string> }) =>
  [...Object.values(m.graphs).map((g) => g.file), ...Object.values(m.files ?? {})]);
/** The model the offline test switches to: not the default one, so a second model loads offline. */
const OTHER_MODEL: string = (manifest.models[1] ?? manifest.models[0]).id;
const DIST = join(ROOT, 'dist');
/** Clips to switch to (from the clip index): two besides the one the page opens on. */
const CLIP_1 = otherClip(defaultHistory().clip.name).name;
const CLIP_2 = otherClip(CLIP_1).name;

const predicted = (page: Page) =>
  page.waitForSelector('body[data-predict-status="done"]', { state: 'attached', timeout: 120_000 });

/** Wait until the service worker controls the page (it activates only once its precache is complete). */
const controlled = (page: Page) =>
  page.waitForFunction(() => navigator.serviceWorker?.controller?.state === 'activated', undefined, { timeout: 180_000, polling: 500 });

describe('offline', () => {
  let session: BrowserSession;
  let page: Page;

  beforeAll(async () => {
    session = await openBrowser();
    page = session.page;
  });
  afterAll(async () => { await session?.close(); });

  it('precaches the wasm, every model file and every clip', async () => {
    await page.goto(baseUrl);
    await predicted(page);
    await controlled(page);
    // The page says it is safe to go offline once the service worker is active (its precache complete), with the size.
    await page.waitForSelector('body[data-offline="ready"]', { state: 'attached', timeout: 180_000 });
    const state = page.getByTestId('offline-state');
    expect(await state.isVisible()).toBe(true);
    expect(await state.textContent()).toMatch(/^Ready offline \(\d+(\.\d)? MB saved\)$/);
    const bytes = Number(await page.evaluate(() => document.body.dataset.offlineBytes));
    expect(bytes, 'bytes in the caches: at least the 14 MB wasm').toBeGreaterThan(10e6);
    console.log(`ready offline: ${await state.textContent()}`);
    const cached: string[] = await page.evaluate(async () => {
      const urls: string[] = [];
      for (const name of await caches.keys()) for (const req of await (await caches.open(name)).keys()) urls.push(new URL(req.url).pathname);
      return urls;
    });
    const has = (suffix: string) => cached.some((u) => u.endsWith(suffix));
    expect(cached.some((u) => /ort-wasm[^/]*\.wasm$/.test(u)), 'the onnxruntime wasm').toBe(true);
    for (const f of [...modelFiles, 'manifest.json']) expect(has(`/models/${f}`), f).toBe(true);
    for (const c of JSON.parse(readFileSync(join(ROOT, 'public/clips/index.json'), 'utf8')).clips) expect(has(`/clips/${c.file}`), c.file).toBe(true);
    expect(has('/embed.html') && has('/assets/motion-futures.js'), 'the embed page and script').toBe(true);
  });

  it('reloads and predicts with the network off, every response from the service worker', async () => {
    const responses: Response[] = [];
    // The context sees the page's and the predictor worker's responses.
    const record = (r: Response) => { responses.push(r); };
    session.context.on('response', record);
    await session.context.setOffline(true);
    try {
      await page.reload();
      await predicted(page);
      await page.locator(`[data-clip="${CLIP_1}"]`).click();
      await page.waitForSelector(`body[data-current-clip="${CLIP_1}"][data-clip-status="ready"]`, { state: 'attached' });
      await page.evaluate(() => { document.body.dataset.predictStatus = 'waiting'; });
      await page.locator('#model-select').selectOption(OTHER_MODEL);
      await page.locator('#predict').click();
      await predicted(page);
      await page.evaluate(() => { const p = window.motionFutures!.player; p.pause(); p.seek(15); });
      await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
      await session.screenshot('offline-reload.png');
      const stats = await pixelStats(session.context, await session.screenshot('offline-reload-stage.png', page.locator('#viewer')));
      expect(stats.foreground).toBeGreaterThan(0.01 * stats.width * stats.height);
    } finally {
      session.context.off('response', record);
      await session.context.setOffline(false);
    }
    const urls = responses.map((r) => new URL(r.url()).pathname);
    // Not vacuous: the page, the scripts, the wasm, the models and the clips were all asked for.
    for (const want of [/\/$/, /motion-futures\.js$/, /worker-[^/]*\.js$/, /ort-wasm[^/]*\.wasm$/, /models\/manifest\.json$/, /\.onnx$/, new RegExp(`clips/${CLIP_1}\\.json$`)]) {
      expect(urls.some((u) => want.test(u)), `a response for ${want}`).toBe(true);
    }
    const notFromWorker = responses.filter((r) => !r.fromServiceWorker()).map((r) => r.url());
    expect(notFromWorker).toEqual([]);
    expect(session.problems.pageErrors).toEqual([]);
    expect(session.problems.consoleErrors).toEqual([]);
  });
});

describe('nothing leaves this machine', () => {
  it('no request goes anywhere but 127.0.0.1: no CDN, fonts or analytics', async () => {
    const session = await openBrowser();
    const elsewhere: string[] = [];
    const seen: string[] = [];
    try {
      const { context, page } = session;
      await context.route('**/*', (route) => {
        const url = new URL(route.request().url());
        if (url.hostname !== '127.0.0.1') { elsewhere.push(url.href); return route.abort('blockedbyclient'); }
        return route.continue();
      });
      context.on('request', (r) => seen.push(r.url()));
      await page.goto(baseUrl);
      await predicted(page);
      await page.locator(`[data-clip="${CLIP_2}"]`).click();
      await page.waitForSelector(`body[data-current-clip="${CLIP_2}"][data-clip-status="ready"]`, { state: 'attached' });
      await page.locator('#predict').click();
      await predicted(page);
      await page.goto(`${baseUrl}embed.html?autoplay=1`);
      await page.waitForSelector('motion-futures[data-predict-status="done"]', { state: 'attached', timeout: 120_000 });
      expect(seen.length).toBeGreaterThan(10);
      expect(elsewhere).toEqual([]);
      expect(seen.filter((u) => !/^(data|blob):/.test(u) && new URL(u).hostname !== '127.0.0.1')).toEqual([]);
      expect(session.problems).toEqual(NO_PROBLEMS);
    } finally {
      await session.close();
    }
  });
});

describe('the folder on a USB stick', () => {
  let server: { url: string; stop(): Promise<void> } | null = null;

  beforeAll(async () => {
    // README: `cd` into the folder and run `python3 -m http.server 8000 --bind 127.0.0.1`.
    const port = await freePort();
    const child = spawn('python3', ['-m', 'http.server', String(port), '--bind', '127.0.0.1'], { cwd: DIST, stdio: 'ignore' });
    const exited = new Promise<void>((r) => child.once('exit', () => r()));
    const stop = async () => {
      if (child.exitCode !== null || child.signalCode !== null) return;
      process.kill(child.pid!, 'SIGTERM');
      await exited;
    };
    const url = `http://127.0.0.1:${port}/`;
    const deadline = Date.now() + 60_000;
    for (;;) {
      try { if ((await fetch(url, { signal: AbortSignal.timeout(2000) })).ok) break; } catch { /* not up yet */ }
      if (Date.now() > deadline || child.exitCode !== null) { await stop(); throw new Error('python3 -m http.server did not start'); }
      await new Promise((r) => setTimeout(r, 250));
    }
    server = { url, stop };
  });
  afterAll(async () => { await server?.stop(); });

  it('carries its licence and notices', () => {
    for (const f of ['LICENSE', 'THIRD_PARTY_NOTICES.md', 'DATA_NOTICE.md', 'version.json']) expect(existsSync(join(DIST, f)), f).toBe(true);
  });

  it('python3 -m http.server sends the wasm as application/wasm, and the page predicts', async () => {
    const wasm = readFileSync(join(DIST, 'sw.js'), 'utf8').match(/assets\/ort-wasm[^"']*\.wasm/)![0];
    const res = await fetch(`${server!.url}${wasm}`);
    expect(res.status).toBe(200);
    expect(res.headers.get('content-type')).toBe('application/wasm');
    await res.arrayBuffer();
    const session = await openBrowser();
    try {
      await session.page.goto(server!.url);
      await predicted(session.page);
      expect(session.problems).toEqual(NO_PROBLEMS);
    } finally {
      await session.close();
    }
  });
});
