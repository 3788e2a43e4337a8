// Accessibility and classroom habits in a real Chromium: axe-core finds no serious or critical
// violation on the predictor, How it works and Model card pages (light and dark); the predictor is
// driven by keys alone (play/pause, step, predict, choose a sample); the 3D view has a text
// alternative; capture saves a real PNG and a non-empty WebM (MediaRecorder on the canvas).
import { readFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { afterAll, beforeAll, describe, expect, inject, it } from 'vitest';
import type { Page } from 'playwright-core';
import { openBrowser, type BrowserSession } from './browser';

const baseUrl = inject('baseUrl');
const NO_PROBLEMS = { consoleErrors: [], pageErrors: [], failedRequests: [] };
const AXE = readFileSync(createRequire(import.meta.url).resolve('axe-core/axe.min.js'), 'utf8');
const PNG_SIGNATURE = [0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a];

interface Violation { id: string; impact: string | null; help: string; nodes: { target: unknown[]; failureSummary?: string }[] }

/** axe-core's violations of impact serious or critical, in words a failing test can show. */
async function seriousViolations(page: Page): Promise<string[]> {
  await page.evaluate(AXE);
  const violations = await page.evaluate(async () => {
    const axe = (window as unknown as { axe: { run(ctx: Document, o: object): Promise<{ violations: Violation[] }> } }).axe;
    const r = await axe.run(document, { resultTypes: ['violations'] });
    return r.violations;
  });
  return violations.filter((v) => v.impact === 'serious' || v.impact === 'critical')
    .map((v) => `${v.id} (${v.impact}): ${v.help} — ${v.nodes.slice(0, 3).map((n) => `${JSON.stringify(n.target)} ${n.failureSummary ?? ''}`).join(' | ')}`);
}

const PAGES: [string, string][] = [
  ['', 'body[data-predict-status="done"]'],
  ['explainer.html', 'body[data-status="ready"]'],
  ['model-card.html', 'body[data-status="ready"]'],
];

describe('axe-core: no serious or critical violations', () => {
  for (const scheme of ['light', 'dark'] as const) {
    it(`${scheme}: the predictor, How it works and the Model card`, async () => {
      const s = await openBrowser({ colorScheme: scheme, viewport: { width: 1200, height: 900 } });
      try {
        const found: Record<string, string[]> = {};
        for (const [path, ready] of PAGES) {
          await s.page.goto(new URL(path, baseUrl).href);
          await s.page.waitForSelector(ready, { state: 'attached', timeout: 120_000 });
          found[path || 'index.html'] = await seriousViolations(s.page);
        }
        expect(found).toEqual({ 'index.html': [], 'explainer.html': [], 'model-card.html': [] });
        expect(s.problems).toEqual(NO_PROBLEMS);
      } finally {
        await s.close();
      }
    });
  }
});

describe('the model card', () => {
  it('reads its numbers from results.json and cites the papers', async () => {
    const results = JSON.parse(readFileSync(new URL('../../public/results.json', import.meta.url), 'utf8'));
    const s = await openBrowser({ viewport: { width: 390, height: 844 } });
    try {
      await s.page.goto(new URL('model-card.html', baseUrl).href);
      await s.page.waitForSelector('body[data-status="ready"]', { state: 'attached', timeout: 60_000 });
      const text = (await s.page.locator('#card').textContent())!;
      // a claim's status and a table's title, as results.json has them
      expect(text).toContain(results.claims[0].text);
      expect(text).toContain(results.tables[0].title);
      expect(await s.page.locator('[data-verdict="can"] li').count()).toBeGreaterThan(0);
      expect(await s.page.locator('[data-verdict="cannot"] li').count()).toBeGreaterThan(0);
      const bib = (await s.page.locator('#bibtex-papers').textContent())!;
      for (const key of ['mao2022weakly', 'aliakbarian2021contextually', 'kiciroglu2022keyposes', 'peng2018deepmimic', 'cmumocap']) expect(bib).toContain(key);
      expect(await s.page.locator('#bibtex-project').textContent()).toContain('@software{motion_futures');
      // each served model's paper as a readable citation (title, authors, venue and year), never a method id
      const methods = JSON.parse(readFileSync(new URL('../../public/models/manifest.json', import.meta.url), 'utf8')).models.map((m: { method: string }) => m.method) as string[];
      expect(new RegExp(`\\b(${methods.filter((m) => m.includes('_')).join('|')})\\b`).test(text), 'a method id in the card').toBe(false);
      const papers = await s.page.locator('#card td').allTextContents();
      expect(papers.filter((t) => /, (CVPR|ICCV|3DV) \d{4}\)$/.test(t)).length, 'cited papers in the models table').toBeGreaterThanOrEqual(3);
      const { scroll, client } = await s.page.evaluate(() => ({ scroll: document.documentElement.scrollWidth, client: document.documentElement.clientWidth }));
      expect(scroll).toBeLessThanOrEqual(client);
      await s.screenshot('model-card-phone.png');
      expect(s.problems).toEqual(NO_PROBLEMS);
    } finally {
      await s.close();
    }
  });
});

describe('keyboard, text alternative and capture on the predictor', () => {
  let session: BrowserSession;
  let page: Page;
  const summary = () => page.getByTestId('view-summary').textContent();
  const playing = () => page.evaluate(() => window.motionFutures!.player.state.playing);
  const position = () => page.evaluate(() => window.motionFutures!.player.state.position);

  beforeAll(async () => {
    session = await openBrowser({ viewport: { width: 1200, height: 900 } });
    page = session.page;
    await page.goto(baseUrl);
    await page.waitForSelector('body[data-predict-status="done"]', { state: 'attached', timeout: 90_000 });
  });
  afterAll(async () => { await session?.close(); });

  it('describes the 3D view in words: model, K, lengths', async () => {
    const d = await page.evaluate(() => ({ ...document.body.dataset }));
    const label = await page.evaluate(() => window.motionFutures!.predictor.manifest!.models.find((m) => m.id === document.body.dataset.predictionModel)!.label);
    const text = (await summary())!;
    expect(text).toContain(label);
    expect(text).toContain(`${d.predictionK} future`);
    expect(text).toMatch(/\d+\.\d\d s/);
    // the canvas points at it
    const describedBy = await page.locator('canvas.stage-canvas').getAttribute('aria-describedby');
    expect(describedBy).toBe('view-summary');
  });

  it('plays, pauses, steps, predicts and picks a sample from the keyboard alone', async () => {
    await page.locator('motion-futures').focus();
    if (await playing()) await page.keyboard.press(' ');
    expect(await playing()).toBe(false);
    const before = await position();
    await page.keyboard.press('ArrowRight');
    expect(await position()).toBe(before + 1);
    await page.keyboard.press(' ');
    expect(await playing()).toBe(true);
    await page.keyboard.press(' ');
    expect(await playing()).toBe(false);

    // a stochastic model (Keyposes), then P
    const model = 'keyposes';
    await page.locator('#model-select').selectOption(model);
    await page.locator('motion-futures').focus();
    await page.evaluate(() => { document.body.dataset.predictStatus = 'waiting'; });
    await page.keyboard.press('p');
    await page.waitForSelector('body[data-predict-status="done"]', { state: 'attached', timeout: 90_000 });
    expect(await page.evaluate(() => document.body.dataset.predictionModel)).toBe(model);
    const k = Number(await page.evaluate(() => document.body.dataset.predictionK));
    expect(k, `${model} draws several futures`).toBeGreaterThan(1);
    await page.keyboard.press('2');
    await expect.poll(summary).toMatch(/Future #2 is selected/);
    await page.keyboard.press('0');
    await expect.poll(summary).not.toMatch(/is selected/);
    // every control in the side panel has an accessible name (axe checks the rest)
    expect(await page.locator('#capture-png').getAttribute('aria-keyshortcuts')).toBe('S');
  });

  it('shows where the focus is', async () => {
    await page.locator('#predict').focus();
    await page.keyboard.press('Shift+Tab');
    await page.keyboard.press('Tab');
    const outline = await page.evaluate(() => {
      let a: Element | null = document.activeElement;
      while (a?.shadowRoot?.activeElement) a = a.shadowRoot.activeElement;
      const cs = getComputedStyle(a!);
      return { id: a!.id, style: cs.outlineStyle, width: parseFloat(cs.outlineWidth) };
    });
    expect(outline.id).toBe('predict');
    expect(outline.style).not.toBe('none');
    expect(outline.width).toBeGreaterThanOrEqual(2);
  });

  it('S saves the view as a PNG (with a PNG signature)', async () => {
    const [download] = await Promise.all([page.waitForEvent('download', { timeout: 60_000 }), page.keyboard.press('s')]);
    expect(download.suggestedFilename()).toMatch(/^motion-futures\..*\.png$/);
    const bytes = readFileSync((await download.path())!);
    expect([...bytes.subarray(0, 8)]).toEqual(PNG_SIGNATURE);
    expect(bytes.length).toBeGreaterThan(1000);
  });

  it('R records the playing futures as a WebM of more than 0 bytes', async () => {
    const [download] = await Promise.all([
      page.waitForEvent('download', { timeout: 110_000 }),
      page.keyboard.press('r'),
    ]);
    expect(download.suggestedFilename()).toMatch(/\.webm$/);
    const bytes = readFileSync((await download.path())!);
    expect(bytes.length).toBeGreaterThan(0);
    // WebM is Matroska: the EBML magic number
    expect([...bytes.subarray(0, 4)]).toEqual([0x1a, 0x45, 0xdf, 0xa3]);
    expect(await page.evaluate(() => document.body.dataset.captureStatus)).toBe('done');
    expect(session.problems).toEqual(NO_PROBLEMS);
  });
});
