// The clip browser in a real Chromium: loads, plays, draws a figure, obeys the keyboard, and
// shows contract errors and missing WebGL on the page instead of going blank.
import { readFileSync } from 'node:fs';
import { afterAll, beforeAll, describe, expect, inject, it } from 'vitest';
import type { Page } from 'playwright-core';
import { openBrowser, type BrowserSession } from './browser';
import { index } from './data';
import { pixelStats } from './pixels';

const baseUrl = inject('baseUrl');
// Clips chosen from the clip index by role and length: a training clip to start on, a test clip to
// switch to, and another clip to recover on.
const VIEW = index.clips.find((c) => c.role === 'train' && c.frames >= 30 && c.frames <= 600) ?? index.clips.find((c) => c.frames >= 30)!;
const TEST = index.clips.find((c) => c.role === 'test' && c.name !== VIEW.name && c.frames >= 12)!;
const OTHER = index.clips.find((c) => c.name !== VIEW.name && c.name !== TEST.name)!;
const seconds = (frames: number) => (frames / index.fps).toFixed(2);
const licence: string | undefined = JSON.parse(readFileSync(new URL(`../../public/clips/${VIEW.file}`, import.meta.url), 'utf8')).source?.license;
// The viewer tests start on a training clip and leave predicting to tests/e2e/predict.e2e.test.ts.
const viewerUrl = `${baseUrl}?clip=${VIEW.name}&predict=0`;
const CLIPS = index.clips.length;
const NO_PROBLEMS = { consoleErrors: [], pageErrors: [], failedRequests: [] };

function frameOf(readout: string | null): number {
  const m = /\(frame (\d+)\)/.exec(readout ?? '');
  if (!m) throw new Error(`no frame in read-out "${readout}"`);
  return Number(m[1]);
}

const readout = (page: Page) => page.getByTestId('time').textContent();
const scrubber = (page: Page) => page.getByTestId('scrubber').inputValue();
const clipReady = (page: Page, name: string) =>
  page.waitForSelector(`body[data-current-clip="${name}"][data-clip-status="ready"]`, { state: 'attached', timeout: 60_000 });

describe('clip viewer', () => {
  let session: BrowserSession;
  let page: Page;

  beforeAll(async () => {
    session = await openBrowser();
    page = session.page;
    await page.goto(viewerUrl);
  });
  afterAll(async () => { await session?.close(); });

  it(`lists the clips, test clips first, and selects ${VIEW.name}`, async () => {
    await page.locator('.clip-button').first().waitFor();
    expect(await page.locator('.clip-button').count()).toBe(CLIPS);
    const firstGroup = await page.locator('.clip-group').first().locator('.role-badge').allTextContents();
    expect(new Set(firstGroup)).toEqual(new Set(['test']));
    await clipReady(page, VIEW.name);
    expect(await page.locator(`[data-clip="${VIEW.name}"]`).getAttribute('aria-current')).toBe('true');
    const info = page.getByTestId('clip-info');
    expect(await info.locator('[data-field="name"]').textContent()).toBe(VIEW.name);
    expect(await info.locator('[data-field="fps"]').textContent()).toBe(String(index.fps));
    expect(await info.locator('[data-field="licence"]').textContent()).toBe(licence ? `Licence: ${licence}` : 'Licence: not stated');
  });

  it(`plays ${VIEW.name}: the read-out and the scrubber advance`, async () => {
    const t0 = await readout(page);
    expect(t0).toMatch(new RegExp(`^t = \\d+\\.\\d\\d s / ${seconds(VIEW.frames).replace('.', '\\.')} s \\(frame \\d+\\)$`));
    await expect.poll(() => readout(page), { timeout: 30_000 }).not.toBe(t0);
    const s0 = await scrubber(page);
    await expect.poll(() => scrubber(page), { timeout: 30_000 }).not.toBe(s0);
    expect(await page.getByTestId('play').getAttribute('aria-label')).toBe('Pause');
  });

  it('draws the figure: left and right limbs in their colours on the grid', async () => {
    // Pause for a steady picture; two frames let the last render land.
    await page.getByTestId('play').click();
    await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
    await session.screenshot('viewer-walk.png');
    const stats = await pixelStats(session.context, await session.screenshot('viewer-walk-stage.png', page.locator('#viewer')));
    expect(stats.distinct).toBeGreaterThan(10);
    expect(stats.foreground).toBeGreaterThan(3000);
    expect(stats.warm).toBeGreaterThan(300);
    expect(stats.cool).toBeGreaterThan(300);
    expect(session.problems).toEqual(NO_PROBLEMS);
  });

  it(`switches to the test clip ${TEST.name} and plays it`, async () => {
    await page.locator(`[data-clip="${TEST.name}"]`).click();
    await clipReady(page, TEST.name);
    expect(await page.locator(`[data-clip="${TEST.name}"]`).getAttribute('aria-current')).toBe('true');
    expect(await page.locator(`[data-clip="${VIEW.name}"]`).getAttribute('aria-current')).toBeNull();
    expect(await page.getByTestId('clip-info').locator('[data-field="split"]').textContent()).toBe('test');
    const t0 = await readout(page);
    expect(t0).toContain(`/ ${seconds(TEST.frames)} s`);
    await expect.poll(() => readout(page), { timeout: 30_000 }).not.toBe(t0);
    expect(session.problems).toEqual(NO_PROBLEMS);
  });

  it('Space pauses, arrows step, Home/End jump, L switches layout', async () => {
    await page.evaluate(() => (document.activeElement as HTMLElement | null)?.blur());
    await page.keyboard.press('Space');
    await expect.poll(() => page.getByTestId('play').getAttribute('aria-label')).toBe('Play');
    const paused = frameOf(await readout(page));
    await page.waitForTimeout(600); // paused means nothing moves, which only time can show
    expect(frameOf(await readout(page))).toBe(paused);

    await page.keyboard.press('ArrowRight');
    expect(frameOf(await readout(page))).toBe((paused + 1) % TEST.frames);
    expect(Number(await scrubber(page))).toBe((paused + 1) % TEST.frames);
    await page.keyboard.press('Home');
    expect(frameOf(await readout(page))).toBe(0);
    await page.keyboard.press('Shift+ArrowRight');
    expect(frameOf(await readout(page))).toBe(10);
    await page.keyboard.press('ArrowLeft');
    expect(frameOf(await readout(page))).toBe(9);
    await page.keyboard.press('End');
    expect(frameOf(await readout(page))).toBe(TEST.frames - 1);

    await page.keyboard.press(']');
    expect(await page.getByLabel('Playback speed').inputValue()).toBe('1.25');
    await page.keyboard.press('[');
    await page.keyboard.press('[');
    expect(await page.getByLabel('Playback speed').inputValue()).toBe('0.75');

    expect(await page.locator('input[name="layout"][value="overlay"]').isChecked()).toBe(true);
    await page.keyboard.press('l');
    expect(await page.locator('input[name="layout"][value="side"]').isChecked()).toBe(true);
    await page.keyboard.press('l');
    expect(await page.locator('input[name="layout"][value="overlay"]').isChecked()).toBe(true);

    await page.keyboard.press('Space');
    await expect.poll(() => page.getByTestId('play').getAttribute('aria-label')).toBe('Pause');
    expect(session.problems).toEqual(NO_PROBLEMS);
  });
});

describe('many tracks', () => {
  it('draws history, samples and truth overlaid and side by side', async () => {
    const session = await openBrowser();
    try {
      const { page } = session;
      await page.goto(viewerUrl);
      await clipReady(page, VIEW.name);
      // Stand-in predictions cut from the clip itself: the viewer does not care where tracks come from.
      await page.evaluate(() => {
        const app = window.motionFutures!;
        const m = app.clips.current!;
        const stride = m.joints * 3;
        const n = 10;
        const cut = (from: number, to: number, dx = 0) => {
          const p = m.positions.slice(from * stride, to * stride);
          for (let i = 0; i < p.length; i += 3) p[i] += dx;
          return p;
        };
        const tracks = [
          { id: 'history', role: 'history' as const, positions: cut(0, n), frames: n, joints: m.joints, startFrame: 0 },
          { id: 'truth', role: 'truth' as const, positions: cut(n, m.frames), frames: m.frames - n, joints: m.joints, startFrame: n },
          ...Array.from({ length: 8 }, (_, k) => ({
            id: `s${k}`, role: 'prediction' as const, sample: k, positions: cut(n, m.frames - k, 0.04 * (k - 4)),
            frames: m.frames - n - k, joints: m.joints, startFrame: n,
          })),
        ];
        app.player.pause();
        app.view.setTracks(tracks, m.skeleton);
        app.view.setSelected(2);
        app.player.load(m.frames, m.fps, 30);
      });
      const settle = () => page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
      await settle();
      const overlay = await pixelStats(session.context, await session.screenshot('viewer-samples-overlay.png', page.locator('#viewer')));
      await page.evaluate(() => (document.activeElement as HTMLElement | null)?.blur());
      await page.keyboard.press('l');
      await settle();
      const side = await pixelStats(session.context, await session.screenshot('viewer-samples-side.png', page.locator('#viewer')));
      for (const stats of [overlay, side]) {
        expect(stats.warm).toBeGreaterThan(100);
        expect(stats.cool).toBeGreaterThan(100);
      }
      expect(side.distinct).toBeGreaterThan(overlay.distinct / 2);
      expect(session.problems).toEqual(NO_PROBLEMS);
    } finally {
      await session.close();
    }
  });
});

describe("the ground truth's label", () => {
  it('covers no other figure and no other label, overlaid and side by side', async () => {
    const session = await openBrowser();
    try {
      const { page } = session;
      await page.goto(viewerUrl);
      await clipReady(page, VIEW.name);
      // Futures cut from the clip, fanned out a little, and one mid-jump right over the truth: its body
      // is where the truth's label would sit over the truth's head.
      const n = await page.evaluate(() => {
        const app = window.motionFutures!;
        const m = app.clips.current!;
        const stride = m.joints * 3;
        const n = 10;
        const cut = (from: number, to: number, dx = 0, dy = 0) => {
          const p = m.positions.slice(from * stride, to * stride);
          for (let i = 0; i < p.length; i += 3) { p[i] += dx; p[i + 1] += dy; }
          return p;
        };
        const futures = (k: number, dx: number, dy: number) => ({
          id: `s${k}`, role: 'prediction' as const, sample: k, positions: cut(n, m.frames, dx, dy),
          frames: m.frames - n, joints: m.joints, startFrame: n,
        });
        app.player.pause();
        app.view.setTracks([
          { id: 'history', role: 'history' as const, positions: cut(0, n), frames: n, joints: m.joints, startFrame: 0 },
          { id: 'truth', role: 'truth' as const, positions: cut(n, m.frames), frames: m.frames - n, joints: m.joints, startFrame: n },
          ...[0, 1, 2, 3].map((k) => futures(k, 0.06 * (k - 1.5), 0)),
          futures(4, 0, 0.45),
        ], m.skeleton);
        app.player.load(m.frames, m.fps, 30);
        return n;
      });
      const check = async (layout: string) => {
        const length = await page.evaluate(() => window.motionFutures!.player.state.length);
        for (const frame of [n, n + 5, Math.floor((n + length - 1) / 2), length - 1]) {
          await page.evaluate((f) => window.motionFutures!.player.seek(f), frame);
          await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
          const scene = await page.evaluate(() => {
            const app = window.motionFutures!;
            const root = app.host.shadowRoot!;
            const canvas = root.querySelector('canvas')!.getBoundingClientRect();
            const rect = (e: Element) => {
              const r = e.getBoundingClientRect();
              return { left: r.left - canvas.left, top: r.top - canvas.top, right: r.right - canvas.left, bottom: r.bottom - canvas.top };
            };
            const labels = [...root.querySelectorAll<HTMLElement>('.figure-label')].filter((e) => e.style.display !== 'none')
              .map((e) => ({ role: e.dataset.role, text: e.textContent, box: rect(e) }));
            return { labels, figures: app.view.figures().map((f) => ({ label: f.label, role: f.role, box: f.box })), width: canvas.width, height: canvas.height };
          });
          const truth = scene.labels.filter((l) => l.role === 'truth');
          expect(truth, `${layout}, frame ${frame}: one truth label`).toHaveLength(1);
          const t = truth[0].box;
          const hit = (b: typeof t) => t.left < b.right && b.left < t.right && t.top < b.bottom && b.top < t.bottom;
          for (const f of scene.figures) expect(hit(f.box), `${layout}, frame ${frame}: the truth's label over the figure of ${f.label}`).toBe(false);
          for (const l of scene.labels.filter((x) => x.role !== 'truth')) expect(hit(l.box), `${layout}, frame ${frame}: over the label ${l.text}`).toBe(false);
          expect(t.left >= 0 && t.top >= 0 && t.right <= scene.width && t.bottom <= scene.height, `${layout}, frame ${frame}: on the stage`).toBe(true);
          // it stays by its figure: within 150 px of the truth's head
          const own = scene.figures.find((f) => f.role === 'truth')!.box;
          expect(Math.hypot((t.left + t.right) / 2 - (own.left + own.right) / 2, t.bottom - own.top), `${layout}, frame ${frame}`).toBeLessThan(150);
          if (layout === 'overlaid') {
            // the scene is the hard one: the jumper's body fills the room over the truth's head, where its label would go
            const jumper = scene.figures.find((f) => f.label.startsWith('#5'))!.box;
            const x = (own.left + own.right) / 2;
            expect(jumper.top < own.top - 10 && jumper.bottom > own.top && jumper.left < x && jumper.right > x, `frame ${frame}: the jumper over the truth's head`).toBe(true);
          }
        }
      };
      await check('overlaid');
      await session.screenshot('viewer-truth-label-overlay.png', page.locator('#viewer'));
      await page.evaluate(() => window.motionFutures!.view.setLayout('side'));
      await check('side by side');
      await session.screenshot('viewer-truth-label-side.png', page.locator('#viewer'));
      expect(session.problems).toEqual(NO_PROBLEMS);
    } finally {
      await session.close();
    }
  });
});

describe('phone width, dark scheme', () => {
  it('stacks the panel under the stage and still draws the figure', async () => {
    const session = await openBrowser({ viewport: { width: 390, height: 844 }, colorScheme: 'dark' });
    try {
      const { page } = session;
      await page.goto(viewerUrl);
      await clipReady(page, VIEW.name);
      await page.getByTestId('play').click();
      const stage = (await page.locator('#viewer').boundingBox())!;
      const panel = (await page.locator('#panel').boundingBox())!;
      expect(panel.y).toBeGreaterThanOrEqual(stage.y + stage.height);
      expect(stage.width).toBeGreaterThan(300);
      await session.screenshot('viewer-phone-dark.png', page);
      const stats = await pixelStats(session.context, await session.screenshot('viewer-phone-dark-stage.png', page.locator('#viewer')));
      expect(stats.warm).toBeGreaterThan(100);
      expect(stats.cool).toBeGreaterThan(100);
      expect(session.problems).toEqual(NO_PROBLEMS);
    } finally {
      await session.close();
    }
  });
});

describe('failures stay visible', () => {
  it(`an invalid ${VIEW.file} names the file in the banner and the page stays usable`, async () => {
    const session = await openBrowser();
    try {
      const { page } = session;
      const text = readFileSync(new URL(`../../public/clips/${VIEW.file}`, import.meta.url), 'utf8');
      const at = text.indexOf('"positions"');
      const broken = text.slice(0, at) + text.slice(at).replace(/-?\d+(\.\d+)?([eE][-+]?\d+)?/, 'NaN');
      await page.route(`**/clips/${VIEW.file}`, (route) => route.fulfill({ status: 200, contentType: 'application/json', body: broken }));
      await page.goto(viewerUrl);
      await page.waitForSelector(`body[data-current-clip="${VIEW.name}"][data-clip-status="error"]`, { state: 'attached', timeout: 60_000 });
      const banner = page.locator('.message-error');
      await expect.poll(() => banner.first().textContent()).toMatch(new RegExp(`${VIEW.file.replace(/\./g, '\\.')}.*not valid JSON`));
      expect(await page.locator('.clip-button').count()).toBe(CLIPS);
      await session.screenshot('viewer-invalid-clip.png');

      await page.locator(`[data-clip="${OTHER.name}"]`).click();
      await clipReady(page, OTHER.name);
      expect(await banner.count()).toBe(0); // the clip's error is cleared by a good clip
      expect(session.problems).toEqual(NO_PROBLEMS);
    } finally {
      await session.close();
    }
  });

  it('without WebGL the viewer says so and the rest of the page works', async () => {
    const session = await openBrowser();
    try {
      const { page } = session;
      await page.addInitScript(() => {
        const original = HTMLCanvasElement.prototype.getContext;
        HTMLCanvasElement.prototype.getContext = function (this: HTMLCanvasElement, type: string, ...rest: unknown[]) {
          if (type === 'webgl' || type === 'webgl2' || type === 'experimental-webgl') return null;
          return (original as (...a: unknown[]) => unknown).call(this, type, ...rest);
        } as typeof original;
      });
      await page.goto(viewerUrl);
      await clipReady(page, VIEW.name);
      await expect.poll(() => page.locator('.viewer-notice').textContent()).toMatch(/WebGL is not available/);
      expect(await page.locator('.viewer-notice').isVisible()).toBe(true);
      expect(await page.locator('.clip-button').count()).toBe(CLIPS);
      const t0 = await readout(page);
      await expect.poll(() => readout(page), { timeout: 30_000 }).not.toBe(t0);
      expect(session.problems).toEqual(NO_PROBLEMS);
    } finally {
      await session.close();
    }
  });
});
