// Permalinks in a real Chromium: the address bar holds the whole state, a reload reproduces the
// same futures, the seed matters for stochastic models, the copy buttons copy, and links that do
// not fit this site (another model hash, unknown names, a dropped file) say so.
import { readFileSync } from 'node:fs';
import { afterAll, beforeAll, describe, expect, inject, it } from 'vitest';
import type { Page } from 'playwright-core';
import type { ControlSpec, Manifest, ModelEntry } from '../../web/src/contract/types';
import { openBrowser, type BrowserSession } from './browser';
import { index, otherClip, testClips } from './data';

const baseUrl = inject('baseUrl');
const NO_PROBLEMS = { consoleErrors: [], pageErrors: [], failedRequests: [] };
const manifest: Manifest = JSON.parse(readFileSync(new URL('../../public/models/manifest.json', import.meta.url), 'utf8'));
const { version } = JSON.parse(readFileSync(new URL('../../package.json', import.meta.url), 'utf8'));
/** A model that draws K samples from a seed, if the site serves one. */
const stochastic = manifest.models.find((m) => m.controls.some((c) => c.id === 'k'));
const model: ModelEntry = stochastic ?? manifest.models[manifest.models.length - 1];

function decimals(step: number): number {
  const s = String(step);
  return s.includes('.') ? s.length - s.indexOf('.') - 1 : 0;
}

/** A valid value other than the default, so the test sees the link's value arrive (generic over controls). */
function nonDefault(spec: ControlSpec): string {
  if (spec.type === 'bool') return spec.default ? '0' : '1';
  if (spec.type === 'actions') {
    const chosen = manifest.actions.filter((a) => !(spec.default as string[] ?? []).includes(a)).slice(0, Math.min(2, spec.max_length ?? 5));
    return chosen.join(',');
  }
  const step = spec.step ?? (spec.type === 'int' ? 1 : ((spec.max ?? 1) - (spec.min ?? 0)) / 4);
  const d = spec.default as number;
  const v = d + step <= (spec.max ?? Infinity) ? d + step : d - step;
  return String(Number(v.toFixed(decimals(step))));
}

// A test clip long enough to start the history at frame 3 (not the page's default, so the link's clip shows).
const LINK_CLIP = (testClips(model.params.history_frames + 3).find((c) => c.name !== index.default?.clip) ?? testClips(model.params.history_frames + 3)[0]).name;
const linkParams = new URLSearchParams({ model: model.id, clip: LINK_CLIP, start: '3', seed: '5' });
for (const c of model.controls) linkParams.set(c.id, nonDefault(c));

const predicted = (page: Page) =>
  page.waitForSelector('body[data-predict-status="done"]', { state: 'attached', timeout: 120_000 });

/** A fingerprint of the futures on stage: K, lengths and an FNV-1a hash of the float32 bytes. */
const futures = (page: Page) => page.evaluate(() => {
  const p = window.motionFutures!.predictor.last!.prediction;
  const bytes = new Uint8Array(p.futures.buffer, p.futures.byteOffset, p.futures.byteLength);
  let h = 2166136261;
  for (const b of bytes) { h ^= b; h = Math.imul(h, 16777619) >>> 0; }
  return `${p.k}:${Array.from(p.lengths).join(',')}:${h.toString(16)}`;
});

describe('permalinks', () => {
  let session: BrowserSession;
  let page: Page;
  let first = '';

  beforeAll(async () => {
    session = await openBrowser();
    page = session.page;
    await session.context.grantPermissions(['clipboard-read', 'clipboard-write'], { origin: new URL(baseUrl).origin });
    await page.goto(`${baseUrl}?${linkParams}`);
    await predicted(page);
    first = await futures(page);
  });
  afterAll(async () => { await session?.close(); });

  it("the link's state arrives and the address bar carries the whole state", async () => {
    const q = new URL(page.url()).searchParams;
    expect(q.get('v')).toBe(version);
    expect(q.get('model')).toBe(model.id);
    expect(q.get('hash')).toBe(model.hash.slice('sha256:'.length, 'sha256:'.length + 12));
    expect(q.get('clip')).toBe(LINK_CLIP);
    expect(q.get('start')).toBe('3');
    expect(q.get('seed')).toBe('5');
    for (const c of model.controls) expect(q.get(c.id), c.id).toBe(linkParams.get(c.id));
    expect(await page.evaluate(() => document.body.dataset.predictionModel)).toBe(model.id);
    expect(await page.locator('#history-start').inputValue()).toBe('3');
    expect(await page.locator('#seed').inputValue()).toBe('5');
    const k = model.controls.find((c) => c.id === 'k');
    if (k) expect(await page.evaluate(() => document.body.dataset.predictionK)).toBe(linkParams.get('k'));
    expect(await page.locator('.message').count()).toBe(0); // a link made here fits here
    expect(session.problems).toEqual(NO_PROBLEMS);
  });

  it('reloading reproduces identical futures', async () => {
    await page.reload();
    await predicted(page);
    expect(await futures(page)).toBe(first);
  });

  it.skipIf(!stochastic)('a different seed changes the futures; the same seed brings them back', async () => {
    const other = new URL(page.url());
    other.searchParams.set('seed', '6');
    await page.goto(other.href);
    await predicted(page);
    const changed = await futures(page);
    expect(changed).not.toBe(first);
    other.searchParams.set('seed', '5');
    await page.goto(other.href);
    await predicted(page);
    expect(await futures(page)).toBe(first);
  });

  it('feet=own arrives as "Plant feet" off: other root paths, the same poses; switching it on brings the futures back', async () => {
    const own = new URL(page.url());
    own.searchParams.set('feet', 'own');
    const heights = () => page.evaluate(() => {
      const p = window.motionFutures!.predictor.last!.prediction;
      return Array.from(p.futures.filter((_, i) => i % 3 === 1).slice(0, 3000));
    });
    const planted = await heights();
    await page.goto(own.href);
    await predicted(page);
    expect(await page.locator('#plant-feet').isChecked()).toBe(false);
    expect(new URL(page.url()).searchParams.get('feet')).toBe('own');
    expect(await futures(page)).not.toBe(first);
    expect(await heights()).toEqual(planted);          // only where the body stands changes
    await page.locator('#plant-feet').check();         // any change predicts again
    await expect.poll(() => futures(page), { timeout: 60_000 }).toBe(first);
    await page.waitForFunction(() => !new URL(location.href).searchParams.has('feet'));
    expect(session.problems).toEqual(NO_PROBLEMS);
  });

  it('the stage bar (camera, closest to truth, ground truth) arrives from a link and goes into it', async () => {
    const shown = new URL(page.url());
    shown.searchParams.set('camera', 'side');
    shown.searchParams.set('truth', '0');
    await page.goto(shown.href);
    await predicted(page);
    expect(await page.getByTestId('camera-preset').inputValue()).toBe('side');
    expect(await page.getByTestId('truth-toggle').getAttribute('aria-pressed')).toBe('false');
    expect(await page.evaluate(() => window.motionFutures!.view.camera)).toBe('side');
    await page.getByTestId('best-toggle').click();
    await page.waitForFunction(() => new URL(location.href).searchParams.get('closest') === '1');
    await page.getByTestId('camera-preset').selectOption('auto');
    await page.getByTestId('truth-toggle').click();
    await page.waitForFunction(() => !new URL(location.href).searchParams.has('camera') && !new URL(location.href).searchParams.has('truth'));
    expect(session.problems).toEqual(NO_PROBLEMS);
  });

  it('"Copy link" copies the permalink, which opens the same futures in a new tab', async () => {
    await page.getByTestId('copy-link').click();
    await expect.poll(() => page.getByTestId('share-status').textContent()).toBe('Link copied.');
    const copied = await page.evaluate(() => navigator.clipboard.readText());
    expect(copied).toBe(await page.getByTestId('share-link').inputValue());
    expect(new URL(copied).search).toBe(new URL(page.url()).search);
    const tab = await session.context.newPage();
    try {
      await tab.goto(copied);
      await predicted(tab);
      expect(await futures(tab)).toBe(first);
    } finally {
      await tab.close();
    }
  });

  it('"Copy embed snippet" copies one script include and one tag with the same state', async () => {
    await page.getByTestId('copy-snippet').click();
    await expect.poll(() => page.getByTestId('share-status').textContent()).toMatch(/Embed snippet copied/);
    const snippet = await page.evaluate(() => navigator.clipboard.readText());
    const [script, tag] = snippet.split('\n');
    expect(script).toBe(`<script type="module" src="${baseUrl}assets/motion-futures.js"></script>`);
    expect(tag).toMatch(/^<motion-futures .*><\/motion-futures>$/);
    for (const [k, v] of new URL(page.url()).searchParams) expect(tag).toContain(`${k}="${v.replace(/&/g, '&amp;')}"`);
    expect(session.problems).toEqual(NO_PROBLEMS);
  });
});

describe('links that do not fit say so', () => {
  let session: BrowserSession;
  beforeAll(async () => { session = await openBrowser(); });
  afterAll(async () => { await session?.close(); });

  it('a link made against another version of the model warns that the futures differ', async () => {
    const { page } = session;
    await page.goto(`${baseUrl}?model=${model.id}&hash=000000000000&v=0.0.1&seed=1`);
    await predicted(page);
    const text = (await page.locator('.message-warning').allTextContents()).join('\n');
    expect(text).toMatch(new RegExp(`different ${model.label.replace(/[()]/g, '\\$&')} \\(model hash 000000000000`));
    expect(text).toMatch(/will differ from the linked ones/);
    expect(text).toMatch(/made with motion-futures 0\.0\.1; this site is /);
  });

  it('unknown names and bad values are named, and the page shows what it can', async () => {
    const { page } = session;
    const spec = model.controls.find((c) => c.type === 'number' || c.type === 'int')!;
    await page.goto(`${baseUrl}?model=no-such-model&clip=no_such_clip&seed=x&predict=0`);
    await page.waitForSelector('body[data-clip-status="ready"]', { state: 'attached', timeout: 60_000 });
    await expect.poll(() => page.locator('.message-warning').count()).toBe(3);
    const text = (await page.locator('.message-warning').allTextContents()).join('\n');
    expect(text).toMatch(/model 'no-such-model', which this site does not serve/);
    expect(text).toMatch(/clip 'no_such_clip', which this site does not have/);
    expect(text).toMatch(/seed must be an integer/);
    // predict=0 stays in the address bar while the state part follows the page
    expect(new URL(page.url()).searchParams.get('predict')).toBe('0');
    await page.goto(`${baseUrl}?model=${model.id}&${spec.id}=${(spec.max ?? 0) + 1000}&predict=0`);
    await page.waitForSelector('body[data-clip-status="ready"]', { state: 'attached', timeout: 60_000 });
    await expect.poll(() => page.locator('.message-warning').first().textContent()).toMatch(new RegExp(`\\(${spec.id}\\) must be between`));
  });

  it('a history from a dropped file cannot be linked, and the copy button says so', async () => {
    const { page } = session;
    await page.goto(`${baseUrl}?predict=0`);
    await page.waitForSelector('body[data-clip-status="ready"]', { state: 'attached', timeout: 60_000 });
    await page.evaluate(() => {
      const app = window.motionFutures!;
      app.showMotion(app.onStage().motion, { kind: 'dropped', name: 'my-walk.bvh' });
    });
    await page.getByTestId('copy-link').click();
    expect(await page.getByTestId('share-status').textContent()).toMatch(/dropped file \(my-walk\.bvh\).*cannot be linked/);
    expect(await page.getByTestId('copy-link').getAttribute('data-unlinkable')).toBe('true');
    expect(await page.getByTestId('copy-snippet').getAttribute('data-unlinkable')).toBe('true');
    expect(await page.getByTestId('share-link').inputValue()).toBe('');
    // the address bar no longer names a clip the stage does not show
    expect(new URL(page.url()).searchParams.has('clip')).toBe(false);
    // picking a clip makes the history linkable again
    const other = otherClip(LINK_CLIP).name;
    await page.locator(`[data-clip="${other}"]`).click();
    await page.waitForSelector(`body[data-current-clip="${other}"][data-clip-status="ready"]`, { state: 'attached' });
    expect(await page.getByTestId('copy-link').getAttribute('data-unlinkable')).toBe('false');
    expect(new URL(page.url()).searchParams.get('clip')).toBe(other);
  });
});
