// The How it works page in a real Chromium: every figure draws from the site's clips and served
// models, each slider moves its read-outs, and nothing goes wrong on the page, light, dark and
// at phone width.
import { afterAll, beforeAll, describe, expect, inject, it } from 'vitest';
import type { Page } from 'playwright-core';
import { openBrowser, type BrowserSession } from './browser';
import { index } from './data';
import { clipTitle } from '../../web/src/ui/clip-name';

const baseUrl = inject('baseUrl');
const NO_PROBLEMS = { consoleErrors: [], pageErrors: [], failedRequests: [] };
const FIGURES = ['fig-dct', 'fig-variance', 'fig-keyposes', 'fig-temperature', 'fig-prior'];

async function open(page: Page): Promise<void> {
  await page.goto(new URL('explainer.html', baseUrl).href);
  await page.waitForSelector('body[data-status="ready"]', { state: 'attached', timeout: 120_000 });
  for (const id of FIGURES) await page.waitForSelector(`#${id}[data-ready="true"]`, { state: 'attached', timeout: 120_000 });
}

const text = (page: Page, id: string) => page.getByTestId(id).textContent();

/** Move a slider with the keyboard (as a user would) and wait for every read-out to change. */
async function moveAndExpect(page: Page, slider: string, key: string, presses: number, readouts: string[]): Promise<void> {
  const before = await Promise.all(readouts.map((r) => text(page, r)));
  await page.locator(`#${slider}`).focus();
  for (let i = 0; i < presses; i++) await page.keyboard.press(key);
  for (const [i, r] of readouts.entries()) {
    await expect.poll(() => text(page, r), { timeout: 60_000, message: `${r} after moving ${slider}` }).not.toBe(before[i]);
  }
}

describe('how it works', () => {
  let session: BrowserSession;
  let page: Page;

  beforeAll(async () => {
    session = await openBrowser({ viewport: { width: 1200, height: 900 } });
    page = session.page;
    await open(page);
  });
  afterAll(async () => { await session?.close(); });

  it('draws all five figures, each citing its paper and equation', async () => {
    for (const id of FIGURES) {
      const fig = page.locator(`#${id}`);
      expect(await fig.locator('svg.chart').count(), id).toBeGreaterThan(0);
      expect(await fig.locator('.fig-cite').textContent(), id).toMatch(/(WAT|Keyposes|LCP-VAE):.*(Eq\.|section|Fig\.)/);
    }
    await session.screenshot('explainer-light.png');
    expect(session.problems).toEqual(NO_PROBLEMS);
  });

  it('DCT: more bases lower the smoothness loss of the joined transition', async () => {
    const loss = async () => Number((await text(page, 'dct-loss'))!.replace(/[^\d.e+-]/g, ''));
    const before = await loss();
    await moveAndExpect(page, 'dct-m', 'ArrowRight', 6, ['dct-loss', 'dct-loss-captured', 'dct-m-value']);
    expect(await loss()).toBeLessThan(before);
    // another pair of clips gives another loss
    const l0 = await text(page, 'dct-loss');
    await page.locator('#dct-to').selectOption('deepmimic_jump');
    await expect.poll(() => text(page, 'dct-loss')).not.toBe(l0);
  });

  it('variance: delta moves the stop frames', async () => {
    // The largest δ stops every curve that is above it for no window after T_min, so some stop moves
    // (with the test vectors, held poses have v ~ 1e-16 and a smaller δ changes nothing).
    await moveAndExpect(page, 'var-delta', 'End', 1, ['var-stops', 'var-mean', 'var-delta-value']);
    expect(await page.locator('#fig-variance').getAttribute('data-source')).toMatch(/^(model|vectors)$/);
    expect(await page.locator('#fig-variance .fig-cite').textContent()).toMatch(/Curves: .*(variance_stop\.json|served WAT model)/);
    if (await page.locator('#fig-variance').getAttribute('data-source') === 'model') {
      // the sentence names the clip the curves really run on (the site's default clip) and its split
      const clip = index.clips.find((c) => c.name === index.default?.clip) ?? index.clips.find((c) => c.role === 'test')!;
      const status = (await page.locator('#fig-variance .fig-status').textContent())!;
      expect(status).toContain(`frames of ${clipTitle(clip)} (${clip.name})`);
      expect(status).not.toMatch(/walker walk forward|a test clip/);
    }
    await session.screenshot('explainer-variance.png', page.locator('#fig-variance'));
  });

  it('explains the predictor\'s numbers where its read-out links (#numbers): cm first, field units and √18', async () => {
    const section = page.locator('#numbers');
    expect(await section.locator('h2').textContent()).toMatch(/numbers/i);
    const words = (await section.textContent())!;
    expect(words).toMatch(/Per-joint error/);
    expect(words).toMatch(/Pose spread/);
    expect(words).toMatch(/field units/);
    expect(words).toMatch(/√18 ≈ 4\.2/);
    expect(words).toMatch(/APD .*at least √\(18 × N\) times the pose spread/s);
  });

  it('keyposes: a lower threshold keeps more keyposes and rebuilds the clip more closely', async () => {
    const count = async () => Number(/^\d+/.exec((await text(page, 'kp-count'))!)![0]);
    const before = await count();
    await moveAndExpect(page, 'kp-threshold', 'ArrowLeft', 4, ['kp-count', 'kp-error', 'kp-threshold-value']);
    expect(await count()).toBeGreaterThan(before);
    await session.screenshot('explainer-keyposes.png', page.locator('#fig-keyposes'));
  });

  it('temperature: a higher T spreads the label distribution and the sampled sequences', async () => {
    const top = async () => Number((await text(page, 'temp-top'))!.split(' ')[0]);
    const before = await top();
    expect(await page.locator('#fig-temperature .sequence').count()).toBe(5);
    await moveAndExpect(page, 'temp-t', 'ArrowRight', 12, ['temp-top', 'temp-perplexity', 'temp-distinct']);
    expect(await top()).toBeLessThan(before);
    await session.screenshot('explainer-temperature.png', page.locator('#fig-temperature'));
  });

  it('prior: the conditional samples of two histories lie apart, the standard ones do not', async () => {
    const sep = async (id: string) => Number(await text(page, id));
    expect(await sep('prior-sep-conditional')).toBeGreaterThan(await sep('prior-sep-standard'));
    await moveAndExpect(page, 'prior-s', 'ArrowLeft', 10, ['prior-sep-conditional', 'prior-spread', 'prior-s-value']);
    await session.screenshot('explainer-prior.png', page.locator('#fig-prior'));
    expect(session.problems).toEqual(NO_PROBLEMS);
  });
});

describe('how it works, dark and phone-sized', () => {
  it('draws in the dark scheme', async () => {
    const dark = await openBrowser({ colorScheme: 'dark', viewport: { width: 1200, height: 900 } });
    try {
      await open(dark.page);
      expect(await dark.page.evaluate(() => getComputedStyle(document.documentElement).backgroundColor)).toBe('rgb(21, 25, 30)');
      await dark.screenshot('explainer-dark.png');
      await dark.screenshot('explainer-dark-prior.png', dark.page.locator('#fig-prior'));
      expect(dark.problems).toEqual(NO_PROBLEMS);
    } finally {
      await dark.close();
    }
  });

  it('fits a phone: no sideways scrolling, figures as wide as the screen', async () => {
    const phone = await openBrowser({ viewport: { width: 390, height: 844 } });
    try {
      await open(phone.page);
      const { scroll, client } = await phone.page.evaluate(() => ({ scroll: document.documentElement.scrollWidth, client: document.documentElement.clientWidth }));
      expect(scroll).toBeLessThanOrEqual(client);
      const box = (await phone.page.locator('#fig-dct svg.chart').boundingBox())!;
      expect(box.width).toBeGreaterThan(300);
      await phone.screenshot('explainer-phone.png');
      await phone.screenshot('explainer-phone-temperature.png', phone.page.locator('#fig-temperature'));
      expect(phone.problems).toEqual(NO_PROBLEMS);
    } finally {
      await phone.close();
    }
  });
});
