// The widget on someone else's page: one script include, two <motion-futures> tags with
// different models, on a host page elsewhere on the origin. Both render and predict, they share
// one worker and one copy of each model, and keys act on the focused one. Plus embed.html in an iframe.
import { mkdirSync, readFileSync } from 'node:fs';
import { afterAll, beforeAll, describe, expect, inject, it } from 'vitest';
import type { Page, Request } from 'playwright-core';
import { openBrowser, type BrowserSession } from './browser';
import { defaultHistory, index, stageModel } from './data';
import { blogPage, projectPage, type HostPageParts } from './host-pages';
import { pixelStats } from './pixels';
import { clipTitle } from '../../web/src/ui/clip-name';
import { shortLabel } from '../../web/src/ui/compare';

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
    // b is narrower than 760 px: its panel opens from the "Controls" button, over the stage
    expect(await page.locator('#b #panel').isVisible()).toBe(false);
    await page.locator('#b .panel-toggle').click();
    expect(await page.locator('#b #panel').isVisible()).toBe(true);
    await page.locator('#b .panel-toggle').click();
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

// A good citizen of someone else's page (issue 29 item 6), under a dark system preference: on a
// project page with a CSS reset, a Bulma-like stylesheet and html { font-size: 62.5% }, and in a
// minimal blog (a narrow serif column, the same root font size). One page load per host carries the
// desktop checks, another the phone's on the project page.
const STOCHASTIC = stageModel.id;
const IFRAME_SRC = `${baseUrl}embed.html?model=${STOCHASTIC}&clip=${CLIP_B}&k=5&seed=3&controls=full`;
/** The README's responsive iframe snippet (README "Embedding"). */
const RESPONSIVE = 'width: 100%; max-width: 720px; aspect-ratio: 3 / 2; min-height: 400px; border: 0';
/** The same widgets on every host: a minimal one (display: block), the README's iframe, a 320 px one. */
const PARTS: HostPageParts = {
  teaser: `<script type="module" src="${baseUrl}assets/motion-futures.js"></script>
  <motion-futures id="w" model="${STOCHASTIC}" clip="${CLIP_B}" k="5" seed="3" theme="light" autoplay
    style="display: block; height: 480px; max-width: 720px; margin: 0 auto 24px"></motion-futures>
  <iframe id="fr" src="${IFRAME_SRC}" title="motion-futures" style="${RESPONSIVE}; display: block; margin: 0 auto"></iframe>`,
  results: `<motion-futures id="n" model="${STOCHASTIC}" clip="${CLIP_B}" k="5" seed="4" style="height: 360px"></motion-futures>`,
};
const PROJECT = projectPage(PARTS);
const HOSTS = [
  { name: 'a project page', shot: 'project', body: PROJECT },
  { name: 'a minimal blog', shot: 'blog', body: blogPage(PARTS) },
];
const SHOTS = '/tmp/h29c';

type Widget = HTMLElement & { app: import('../../web/src/ui/app').App };
/** Count WebGL draws per canvas, in every frame (drawn frames are what a paused render loop saves). */
const COUNT_DRAWS = () => {
  for (const proto of [WebGL2RenderingContext.prototype, WebGLRenderingContext.prototype]) {
    for (const name of ['drawElements', 'drawArrays', 'drawElementsInstanced', 'drawArraysInstanced'] as const) {
      const original = (proto as unknown as Record<string, (...a: unknown[]) => unknown>)[name];
      if (!original) continue;
      (proto as unknown as Record<string, unknown>)[name] = function (this: WebGL2RenderingContext, ...a: unknown[]) {
        const c = this.canvas as HTMLCanvasElement & { draws?: number };
        c.draws = (c.draws ?? 0) + 1;
        return original.apply(this, a);
      };
    }
  }
};
const draws = (page: Page, id: string) => page.evaluate((i) => (document.getElementById(i)!.shadowRoot!.querySelector('canvas') as HTMLCanvasElement & { draws?: number }).draws ?? 0, id);
const figureHeight = (page: Page, id: string) => page.evaluate((i) => {
  const figs = (document.getElementById(i) as Widget).app.view.figures();
  return figs.reduce((s, f) => s + (f.box.bottom - f.box.top), 0);
}, id);
const viewDirection = (page: Page, id: string) => page.evaluate((i) => (document.getElementById(i) as Widget).app.view.viewDirection(), id);

/** In a document with a widget: its controls that cannot be reached (outside the visible widget, or
 *  covered), after scrolling each into view inside its own scroll box; and how many were checked. */
const UNREACHABLE = ([sel, within]: [string, string]) => {
  const host = document.querySelector(sel) as HTMLElement;
  const root = host.shadowRoot!;
  const box = host.getBoundingClientRect();
  const vw = document.documentElement.clientWidth;
  const vh = document.documentElement.clientHeight;
  const bad: string[] = [];
  let checked = 0;
  for (const c of root.querySelector(within)!.querySelectorAll<HTMLElement>('button, input, select, textarea, summary, a[href], [tabindex="0"]')) {
    if (!c.checkVisibility({ visibilityProperty: true })) continue; // not shown (a closed section)
    c.scrollIntoView({ block: 'nearest', inline: 'nearest' });
    const r = c.getBoundingClientRect();
    const x = r.left + r.width / 2;
    const y = r.top + Math.min(r.height / 2, 8);
    const name = `${c.tagName.toLowerCase()}${c.id ? `#${c.id}` : ''}[${c.getAttribute('aria-label') ?? c.textContent?.trim().slice(0, 24)}]`;
    checked += 1;
    if (r.width < 4 || r.height < 4) { bad.push(`${name}: ${r.width}x${r.height}`); continue; }
    if (x < Math.max(0, box.left) || x > Math.min(vw, box.right) || y < Math.max(0, box.top) || y > Math.min(vh, box.bottom)) { bad.push(`${name}: outside`); continue; }
    const hit = root.elementFromPoint(x, y);
    const label = c.closest('label');
    if (!hit || !(c.contains(hit) || hit.contains(c) || (label && label.contains(hit)) || (c as HTMLInputElement).labels?.[0]?.contains(hit))) bad.push(`${name}: covered by ${hit?.tagName}.${hit?.className}`);
  }
  const widget = root.querySelector('.mf-widget') as HTMLElement;
  if (widget.scrollHeight > widget.clientHeight + 1) bad.push(`the widget scrolls: ${widget.scrollHeight} in ${widget.clientHeight}`);
  return { bad, checked };
};

/** Every control of a narrow full embed: the stage's with the panel closed, then the panel's, open. */
async function reachable(frame: import('playwright-core').Frame): Promise<void> {
  const stage = await frame.evaluate(UNREACHABLE, ['motion-futures', '.stage-area'] as [string, string]);
  expect(stage.bad).toEqual([]);
  expect(stage.checked, 'the stage\'s controls (playback, camera, layout, Controls)').toBeGreaterThanOrEqual(8);
  await frame.locator('.panel-toggle').click();
  const panel = await frame.evaluate(UNREACHABLE, ['motion-futures', '#panel'] as [string, string]);
  expect(panel.bad).toEqual([]);
  expect(panel.checked, 'the panel\'s controls').toBeGreaterThan(15);
}

/** Tab through a document; every stop must be a visible box of at least 4 x 4 px. */
async function invisibleTabStops(page: Page, presses: number): Promise<string[]> {
  const bad: string[] = [];
  await page.evaluate(() => (document.activeElement as HTMLElement | null)?.blur());
  for (let i = 0; i < presses; i++) {
    await page.keyboard.press('Tab');
    const stop = await page.evaluate(() => {
      let a: Element | null = document.activeElement;
      while (a?.shadowRoot?.activeElement) a = a.shadowRoot.activeElement;
      if (!a || a === document.body || a.tagName === 'IFRAME') return null;
      const r = a.getBoundingClientRect();
      const ok = r.width >= 4 && r.height >= 4 && a.checkVisibility({ opacityProperty: true, visibilityProperty: true });
      return ok ? null : `${a.tagName.toLowerCase()}.${a.className} ${r.width}x${r.height}`;
    });
    if (stop) bad.push(stop);
  }
  return bad;
}

/** Scroll so that widget `id` sits `below` px under the top of the window (with page left below it). */
const showAt = (page: Page, id: string, below: number) => page.evaluate(([id, below]) => {
  window.scrollTo(0, document.getElementById(id as string)!.getBoundingClientRect().top + window.scrollY - (below as number));
}, [id, below] as const);
/** Widget `id` (playing) on screen and held at frame 20. A widget that autoplays while unseen (the blog's,
 *  below the fold) starts once seen (visibility.ts): it is paused after that, not before. */
async function stillAt20(page: Page, id: string, below: number): Promise<void> {
  await showAt(page, id, below);
  await expect.poll(() => playLabel(page, id)).toBe('Pause');
  await page.evaluate((i) => { const p = (document.getElementById(i) as Widget).app.player; p.pause(); p.seek(20); }, id);
  await settle(page);
}

describe.each(HOSTS)('the embed on $name', ({ shot, body }) => {
  let session: BrowserSession;
  let page: Page;
  const swRequests: string[] = [];

  beforeAll(async () => {
    mkdirSync(SHOTS, { recursive: true });
    session = await openBrowser({ viewport: { width: 1280, height: 800 }, colorScheme: 'dark' });
    page = session.page;
    session.context.on('request', (r: Request) => { if (/\/sw\.js$|workbox/.test(r.url())) swRequests.push(r.url()); });
    await session.context.addInitScript(COUNT_DRAWS);
    await page.route(HOST_URL, (route) => route.fulfill({ status: 200, contentType: 'text/html', body }));
    await page.goto(HOST_URL);
    await Promise.all([done(page, 'w'), done(page, 'n'),
      page.frameLocator('#fr').locator('motion-futures[data-predict-status="done"]').waitFor({ state: 'attached', timeout: 120_000 })]);
  });
  afterAll(async () => { await session?.close(); });

  it('fills its element with display: block, keeps its own sizes and theme, and shows a stochastic K = 5', async () => {
    const w = page.locator('#w');
    expect(await w.getAttribute('data-prediction-k')).toBe('5');
    const host = (await w.boundingBox())!;
    const area = (await page.locator('#w .stage-area').boundingBox())!;
    const viewer = (await page.locator('#w #viewer').boundingBox())!;
    expect(host.height).toBe(480);
    expect(area.height / host.height, 'the stage with its playback, of the element').toBeGreaterThanOrEqual(0.9);
    expect(viewer.height / host.height, 'the 3D view, of the element').toBeGreaterThanOrEqual(0.75);
    expect(viewer.width / host.width).toBeGreaterThanOrEqual(0.95);
    // html { font-size: 62.5% } (1rem = 10 px on the host page) does not shrink the widget
    const sizes = await page.evaluate(() => {
      const root = document.getElementById('w')!.shadowRoot!;
      const px = (s: string, p: 'fontSize' | 'height') => parseFloat(getComputedStyle(root.querySelector(s)!)[p]);
      return { bar: px('.mini-bar', 'fontSize'), button: px('.icon-button', 'height'), stageBar: px('.stage-view', 'fontSize'),
        hostRem: parseFloat(getComputedStyle(document.documentElement).fontSize) };
    });
    expect(sizes.stageBar, 'the camera bar over the stage').toBeGreaterThanOrEqual(11);
    expect(sizes.hostRem).toBe(10);
    expect(sizes.bar).toBeGreaterThanOrEqual(12);
    expect(sizes.button).toBeGreaterThanOrEqual(30);
    // theme="light" under a dark system preference; the iframe without a theme follows the system
    const bg = (loc: Page | import('playwright-core').FrameLocator) => loc.locator('motion-futures').first().evaluate((h) => getComputedStyle(h).backgroundColor);
    expect(await page.locator('#w').evaluate((h) => getComputedStyle(h).backgroundColor)).toBe('rgb(246, 247, 249)');
    expect(await bg(page.frameLocator('#fr'))).toBe('rgb(21, 25, 30)');
    // the 3D stage reads its colours from the widget's (stage.ts readTheme)
    expect(await page.locator('#w #viewer').evaluate((v) => getComputedStyle(v).getPropertyValue('--stage-bg').trim())).toBe('#eef0f3');
  });

  it('registers no service worker and precaches nothing, in the element or the iframe', async () => {
    await page.waitForTimeout(500); // a registration would follow the first prediction at once
    expect(await page.evaluate(() => navigator.serviceWorker.getRegistrations().then((r) => r.length))).toBe(0);
    const frame = page.frame({ url: /embed\.html/ })!;
    expect(await frame.evaluate(() => navigator.serviceWorker.getRegistrations().then((r) => r.length))).toBe(0);
    expect(await frame.evaluate(() => caches.keys())).toEqual([]);
    expect(swRequests).toEqual([]);
    expect(await page.frameLocator('#fr').locator('text=/offline/i').count()).toBe(0);
  });

  it('lets the page scroll under the wheel; ctrl + wheel, or a click first, zooms', async () => {
    await stillAt20(page, 'w', 60);
    const v = (await page.locator('#w #viewer').boundingBox())!;
    await page.mouse.move(v.x + v.width / 2, v.y + v.height / 2);
    const size0 = await figureHeight(page, 'w');
    const y0 = await page.evaluate(() => window.scrollY);
    for (let i = 0; i < 5; i++) { await page.mouse.wheel(0, 100); await page.waitForTimeout(60); }
    await expect.poll(() => page.evaluate(() => window.scrollY)).toBeGreaterThan(y0 + 300);
    expect(await page.locator('#w .gesture-hint').textContent()).toMatch(/Ctrl \+ scroll to zoom/);
    expect(await figureHeight(page, 'w'), 'the wheel did not zoom').toBeCloseTo(size0, 0);

    await showAt(page, 'w', 60);
    await settle(page);
    const y1 = await page.evaluate(() => window.scrollY);
    await page.keyboard.down('Control');
    for (let i = 0; i < 3; i++) { await page.mouse.wheel(0, -100); await page.waitForTimeout(60); }
    await page.keyboard.up('Control');
    await settle(page);
    expect(await page.evaluate(() => window.scrollY)).toBe(y1);
    const size1 = await figureHeight(page, 'w');
    expect(size1, 'ctrl + wheel zooms in').toBeGreaterThan(size0 * 1.1);

    // a click into the widget: the wheel zooms (out) there until focus leaves
    await page.mouse.click(v.x + 20, v.y + 20);
    expect(await page.evaluate(() => document.activeElement?.id)).toBe('w');
    for (let i = 0; i < 3; i++) { await page.mouse.wheel(0, 100); await page.waitForTimeout(60); }
    await settle(page);
    expect(await page.evaluate(() => window.scrollY)).toBe(y1);
    expect(await figureHeight(page, 'w'), 'a focused widget zooms out under the wheel').toBeLessThan(size1 * 0.9);
    await page.evaluate(() => (document.activeElement as HTMLElement | null)?.blur());
    expect(session.problems).toEqual(NO_PROBLEMS);
  });

  it('stops drawing while scrolled out of view, and plays on when back', async () => {
    await showAt(page, 'w', 60);
    await page.evaluate(() => (document.getElementById('w') as Widget).app.player.play());
    await expect.poll(() => playLabel(page, 'w')).toBe('Pause');
    const a = await draws(page, 'w');
    await page.waitForTimeout(600);
    const shown = (await draws(page, 'w')) - a;
    expect(shown, 'frames drawn in 0.6 s on screen').toBeGreaterThan(5);
    await page.evaluate(() => window.scrollTo(0, document.documentElement.scrollHeight));
    await page.waitForTimeout(300); // the intersection observer reports
    const b = await draws(page, 'w');
    await page.waitForTimeout(800);
    expect((await draws(page, 'w')) - b, 'frames drawn in 0.8 s off screen').toBe(0);
    await showAt(page, 'w', 60);
    await expect.poll(() => playLabel(page, 'w')).toBe('Pause');
    const c = await draws(page, 'w');
    await expect.poll(() => draws(page, 'w').then((d) => d - c)).toBeGreaterThan(3);
  });

  it('fits a 320 px column: the playback bar wraps without overlap; full controls all reachable in the README\'s iframe', async () => {
    const n = page.locator('#n');
    await n.scrollIntoViewIfNeeded();
    expect((await n.boundingBox())!.width).toBe(320);
    const bar = await page.evaluate(() => {
      const root = document.getElementById('n')!.shadowRoot!;
      const host = document.getElementById('n')!.getBoundingClientRect();
      const parts = [...root.querySelector('.playback-bar')!.children].map((c) => ({ r: c.getBoundingClientRect(), cls: c.className, clipped: c.scrollWidth > c.clientWidth + 1 }));
      const overlaps: string[] = [];
      for (const [i, p] of parts.entries()) for (const q of parts.slice(i + 1)) {
        if (p.r.left < q.r.right - 1 && q.r.left < p.r.right - 1 && p.r.top < q.r.bottom - 1 && q.r.top < p.r.bottom - 1) overlaps.push(`${p.cls} / ${q.cls}`);
      }
      return { overlaps, outside: parts.filter((p) => p.r.left < host.left || p.r.right > host.right).map((p) => p.cls),
        clipped: parts.filter((p) => p.clipped).map((p) => p.cls), readout: parts.find((p) => p.cls.includes('time-readout'))!.r.width };
    });
    expect(bar).toEqual({ overlaps: [], outside: [], clipped: [], readout: bar.readout });
    expect(bar.readout).toBeGreaterThan(80);
    // the whole minimal widget fits its 320 x 360 element: it never scrolls inside itself, and the bar under
    // the playback (what is shown, "New futures", "Open in motion-futures") lies inside it without overlap
    const mini = await page.evaluate(() => {
      const root = document.getElementById('n')!.shadowRoot!;
      const host = document.getElementById('n')!.getBoundingClientRect();
      const widget = root.querySelector<HTMLElement>('.mf-widget')!;
      const shown = [...root.querySelector('.mini-bar')!.children].filter((c) => (c as HTMLElement).checkVisibility())
        .map((c) => ({ r: c.getBoundingClientRect(), cls: c.className }));
      const overlaps: string[] = [];
      for (const [i, p] of shown.entries()) for (const q of shown.slice(i + 1)) {
        if (p.r.left < q.r.right - 1 && q.r.left < p.r.right - 1 && p.r.top < q.r.bottom - 1 && q.r.top < p.r.bottom - 1) overlaps.push(`${p.cls} / ${q.cls}`);
      }
      const caption = root.querySelector<HTMLElement>('.mini-caption')!;
      return { scrolls: widget.scrollHeight > widget.clientHeight + 1, overlaps, height: host.height,
        outside: shown.filter((c) => c.r.left < host.left - 0.5 || c.r.right > host.right + 0.5 || c.r.top < host.top - 0.5 || c.r.bottom > host.bottom + 0.5).map((c) => c.cls),
        parts: shown.map((c) => c.cls.split(' ')[0]), caption: { text: caption.textContent, title: caption.title } };
    });
    expect(mini).toEqual({ scrolls: false, overlaps: [], height: 360, outside: [], parts: ['mini-caption', 'text-button', 'mini-open'], caption: mini.caption });
    // one line, cut with an ellipsis: the model's short name and the clip; the whole label on hover
    expect(mini.caption.text).toBe(`${shortLabel(stageModel)} · ${clipTitle(index.clips.find((c) => c.name === CLIP_B)!)}`);
    expect(mini.caption.title).toBe(`${stageModel.label} · ${clipTitle(index.clips.find((c) => c.name === CLIP_B)!)}`);

    const frame = page.frame({ url: /embed\.html/ })!;
    await page.locator('#fr').scrollIntoViewIfNeeded();
    // the README's snippet: as wide as the column up to 720 px (720 x 480 on the project page), at 3 : 2
    const fr = (await page.locator('#fr').boundingBox())!;
    const column = await page.locator('#fr').evaluate((f) => f.parentElement!.clientWidth - parseFloat(getComputedStyle(f.parentElement!).paddingLeft) - parseFloat(getComputedStyle(f.parentElement!).paddingRight));
    expect(fr.width).toBe(Math.min(720, column));
    expect(fr.height).toBeCloseTo(fr.width / 1.5, 0);
    await reachable(frame);
    await frame.locator('.panel-toggle').click();
    expect(await frame.locator('#panel').isVisible()).toBe(false);
  });

  it('has no invisible tab stops', async () => {
    await page.evaluate(() => window.scrollTo(0, 0));
    expect(await invisibleTabStops(page, 45)).toEqual([]);
    await stillAt20(page, 'w', 40);
    await page.screenshot({ path: `${SHOTS}/embed-${shot}-desktop.png` });
    expect(session.problems).toEqual(NO_PROBLEMS);
  });
});

// The minimal embed's legend (issue 29 item 7): which colour is the history, the ground truth and each
// sample, in the figures' own colours, on a phone: a widget as wide as the 390 px screen, and one of 320 px.
describe("the minimal embed's legend", () => {
  let session: BrowserSession;
  let page: Page;
  const PHONE = hostPage(`<script type="module" src="${baseUrl}assets/motion-futures.js"></script>
<motion-futures id="p" model="${STOCHASTIC}" clip="${CLIP_B}" k="5" seed="3" style="height: 480px"></motion-futures>
<motion-futures id="q" model="${STOCHASTIC}" clip="${CLIP_B}" k="5" seed="3" style="height: 420px; width: 320px"></motion-futures>`)
    .replace('margin: 1rem', 'margin: 0');

  beforeAll(async () => {
    session = await openBrowser({ viewport: { width: 390, height: 844 } });
    page = session.page;
    await page.route(HOST_URL, (route) => route.fulfill({ status: 200, contentType: 'text/html', body: PHONE }));
    await page.goto(HOST_URL);
    await Promise.all([done(page, 'p'), done(page, 'q')]);
  });
  afterAll(async () => { await session?.close(); });

  for (const [id, width] of [['p', 390], ['q', 320]] as const) {
    it(`names the history, the ground truth and #1-#5 in the figures' colours, within a ${width} px widget`, async () => {
      await page.locator(`#${id}`).scrollIntoViewIfNeeded();
      expect((await page.locator(`#${id}`).boundingBox())!.width).toBe(width);
      const legend = page.locator(`#${id}`).getByTestId('mini-legend');
      expect(await legend.isVisible()).toBe(true);
      // what each entry says, and its swatch's colour as "#rrggbb"
      const entries = () => legend.evaluate((ul) => [...ul.querySelectorAll('li')].map((li) => {
        const [r, g, b] = getComputedStyle(li.querySelector('.mini-swatch')!).backgroundColor.match(/\d+/g)!.map(Number);
        return { text: li.textContent, role: li.dataset.role, sample: li.dataset.sample, colour: `#${[r, g, b].map((v) => v.toString(16).padStart(2, '0')).join('')}` };
      }));
      const shown = await entries();
      expect(shown.map((e) => e.text)).toEqual(['history', 'ground truth', '#1', '#2', '#3', '#4', '#5']);
      // the colours the GPU draws the figures' heads in: the history's in its phase, the others' at the end
      const colours = (frame: number) => page.evaluate(([id, frame]) => {
        const app = (document.getElementById(id as string) as Widget).app;
        app.player.pause();
        app.player.seek(frame < 0 ? app.player.state.length - 1 : frame as number);
        return app.view.figures().map((f) => ({ role: f.role, sample: f.sample === undefined ? undefined : String(f.sample), colour: f.colour }));
      }, [id, frame] as const);
      const drawn = [...(await colours(0)), ...(await colours(-1))];
      for (const e of shown) {
        const figure = drawn.find((f) => f.role === e.role && f.sample === e.sample);
        expect(figure, `a figure for ${e.text}`).toBeDefined();
        expect(e.colour, e.text).toBe(figure!.colour);
      }

      // it fits: inside the widget, nothing clipped, above the playback bar and apart from it; no tab stop
      const fit = await page.evaluate((id) => {
        const root = document.getElementById(id)!.shadowRoot!;
        const host = document.getElementById(id)!.getBoundingClientRect();
        const ul = root.querySelector<HTMLElement>('.mini-legend')!;
        const box = ul.getBoundingClientRect();
        const bar = root.querySelector('.playback-bar')!.getBoundingClientRect();
        const items = [...ul.querySelectorAll('li')].map((li) => li.getBoundingClientRect());
        return {
          inside: box.left >= host.left && box.right <= host.right && box.top >= host.top && box.bottom <= host.bottom
            && items.every((r) => r.left >= box.left && r.right <= box.right && r.top >= box.top && r.bottom <= box.bottom),
          clipped: ul.scrollWidth > ul.clientWidth + 1 || ul.scrollHeight > ul.clientHeight + 1,
          aboveBar: box.bottom <= bar.top, lines: new Set(items.map((r) => Math.round(r.top))).size,
          focusable: ul.querySelectorAll('a, button, input, select, [tabindex]').length + (ul.hasAttribute('tabindex') ? 1 : 0),
        };
      }, id);
      expect(fit).toEqual({ inside: true, clipped: false, aboveBar: true, lines: fit.lines, focusable: 0 });
      expect(fit.lines, 'one or two lines').toBeLessThanOrEqual(2);
      await page.evaluate((id) => { document.getElementById(id)!.scrollIntoView({ block: 'start' }); (document.getElementById(id) as Widget).app.player.seek(20); }, id);
      await settle(page);
      mkdirSync(SHOTS, { recursive: true });
      await page.locator(`#${id}`).screenshot({ path: `${SHOTS}/embed-legend-${width}.png` });
      expect(session.problems).toEqual(NO_PROBLEMS);
    });
  }

  it('follows the stage: the ground truth hidden leaves the legend, K = 7 adds #6 and #7', async () => {
    const legendTexts = () => page.locator('#p').getByTestId('mini-legend').locator('li').allTextContents();
    await page.locator('#p').scrollIntoViewIfNeeded();
    await page.locator('#p .stage-view button', { hasText: /Truth/ }).click();
    await expect.poll(legendTexts).toEqual(['history', '#1', '#2', '#3', '#4', '#5']);
    await page.locator('#p .stage-view button', { hasText: /Truth/ }).click();
    await page.evaluate(async () => {
      const app = (document.getElementById('p') as Widget).app;
      app.predictor.setInputs({ controls: { k: 7 } });
      await app.predictor.predict();
    });
    await expect.poll(legendTexts).toEqual(['history', 'ground truth', '#1', '#2', '#3', '#4', '#5', '#6', '#7']);
    expect(session.problems).toEqual(NO_PROBLEMS);
  });
});

describe('the embed on a project page, on a phone', () => {
  it('one finger scrolls the page, two fingers turn the view; the full iframe fits 390 px', async () => {
    const session = await openBrowser({ viewport: { width: 390, height: 844 }, colorScheme: 'dark' });
    try {
      const { page } = session;
      await page.route(HOST_URL, (route) => route.fulfill({ status: 200, contentType: 'text/html', body: PROJECT }));
      await page.goto(HOST_URL);
      await Promise.all([done(page, 'w'),
        page.frameLocator('#fr').locator('motion-futures[data-predict-status="done"]').waitFor({ state: 'attached', timeout: 120_000 })]);
      expect(await page.evaluate(() => document.documentElement.scrollWidth), 'no page wider than the phone').toBeLessThanOrEqual(390);
      await page.evaluate(() => { const p = (document.getElementById('w') as Widget).app.player; p.pause(); p.seek(20); window.scrollTo(0, 250); });
      await settle(page);
      mkdirSync(SHOTS, { recursive: true });
      await page.screenshot({ path: `${SHOTS}/embed-project-phone.png` });
      const cdp = await session.context.newCDPSession(page);
      await cdp.send('Emulation.setTouchEmulationEnabled', { enabled: true, maxTouchPoints: 5 });
      const v = (await page.locator('#w #viewer').boundingBox())!;
      const cx = v.x + v.width / 2;
      const cy = v.y + v.height / 2;
      const swipe = async (fingers: number, dx: number, dy: number) => {
        const at = (t: number) => Array.from({ length: fingers }, (_, i) => ({ x: cx + i * 60 - 30 * (fingers - 1) + dx * t, y: cy + dy * t, id: i }));
        await cdp.send('Input.dispatchTouchEvent', { type: 'touchStart', touchPoints: at(0) });
        for (let s = 1; s <= 10; s++) { await cdp.send('Input.dispatchTouchEvent', { type: 'touchMove', touchPoints: at(s / 10) }); await page.waitForTimeout(16); }
        await cdp.send('Input.dispatchTouchEvent', { type: 'touchEnd', touchPoints: [] });
        await page.waitForTimeout(300);
      };
      const scrollY = () => page.evaluate(() => window.scrollY);
      const d0 = await viewDirection(page, 'w');
      const y0 = await scrollY();
      await swipe(2, 120, 0);
      expect(await scrollY(), 'two fingers leave the page').toBe(y0);
      const d1 = (await viewDirection(page, 'w'))!;
      expect(Math.hypot(d1[0] - d0![0], d1[1] - d0![1], d1[2] - d0![2]), 'two fingers turn the view').toBeGreaterThan(0.1);
      await swipe(1, 0, -150);
      expect(await scrollY(), 'one finger scrolls the page').toBeGreaterThan(y0 + 80);
      expect(await viewDirection(page, 'w'), 'and leaves the view').toEqual(d1);

      const frame = page.frame({ url: /embed\.html/ })!;
      await page.locator('#fr').scrollIntoViewIfNeeded();
      await reachable(frame);
      expect(session.problems).toEqual(NO_PROBLEMS);
    } finally {
      await session.close();
    }
  });
});

// The other side of "registers no service worker": the same iframe registers one when the host asks
// (offline=1), so the checks above would see a registration if the embed made one.
describe('embed.html with offline=1', () => {
  it('registers the site\'s service worker when the host asks for offline use', async () => {
    const session = await openBrowser({ viewport: { width: 900, height: 700 } });
    try {
      const { page } = session;
      await page.route(HOST_URL, (route) => route.fulfill({ status: 200, contentType: 'text/html',
        body: hostPage(`<iframe id="f" src="${IFRAME_SRC.replace('controls=full', 'controls=minimal')}&offline=1" style="${RESPONSIVE}"></iframe>`) }));
      await page.goto(HOST_URL);
      await page.frameLocator('#f').locator('motion-futures[data-predict-status="done"]').waitFor({ state: 'attached', timeout: 120_000 });
      const frame = page.frame({ url: /embed\.html/ })!;
      await expect.poll(() => frame.evaluate(() => navigator.serviceWorker.getRegistrations().then((r) => r.map((x) => new URL(x.scope).pathname))),
        { timeout: 60_000 }).toEqual([new URL(baseUrl).pathname]);
      expect(await page.evaluate(() => navigator.serviceWorker.getRegistrations().then((r) => r.length))).toBe(1);   // same origin: the host sees it
    } finally {
      await session.close();
    }
  });
});
