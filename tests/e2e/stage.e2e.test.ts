// Issue 20, "the stage a newcomer reads in ten seconds", in a real Chromium: with no input the page and
// the bare embed show K = 5 futures of the stage model from a held-out history, apart and large
// enough to read, each figure named; changes predict again on their own; the camera frames every
// figure; the scrubber marks the history and t counts from the first predicted frame; the read-out
// gives the evaluation's numbers; messages and range warnings never move the stage; the minimal
// embed is mostly stage. Data-driven: the clip index and the manifest say what to expect.
import { writeFile } from 'node:fs/promises';
import { afterAll, beforeAll, describe, expect, inject, it } from 'vitest';
import type { Frame, Page } from 'playwright-core';
import { openBrowser, type BrowserSession } from './browser';
import { defaultHistory, horizonFrames, index, manifest, otherClip, stageModel } from './data';
import { NO_PROBLEMS, predicted, settle } from './predict-page';
import { clipShortTitle, clipTitle } from '../../web/src/ui/clip-name';
import { tintColour } from '../../web/src/viewer/palette';

const baseUrl = inject('baseUrl');
const FIRST_K = 5;
const N = stageModel.params.history_frames;
/** Issue 20: futures within 5 s of opening the page, figures at least 60 px tall, pairs 5 cm apart. */
const FIRST_FUTURES_MS = 5000;
const MIN_FIGURE_PX = 60;
const MIN_PAIR_M = 0.05;

type Target = Page | Frame;

/** Mean per-joint distance between each pair of samples at their last common frame (metres). */
const pairDistances = (t: Target) => t.evaluate(() => {
  const app = document.querySelector('motion-futures')!.app!;
  const p = app.predictor.last!.prediction;
  const J = p.joints;
  const out: number[] = [];
  for (let i = 0; i < p.k; i++) {
    for (let j = i + 1; j < p.k; j++) {
      const f = Math.min(p.lengths[i], p.lengths[j]) - 1;
      let sum = 0;
      for (let q = 0; q < J; q++) {
        const a = ((i * p.frames + f) * J + q) * 3;
        const b = ((j * p.frames + f) * J + q) * 3;
        sum += Math.hypot(p.futures[a] - p.futures[b], p.futures[a + 1] - p.futures[b + 1], p.futures[a + 2] - p.futures[b + 2]);
      }
      out.push(sum / J);
    }
  }
  return out;
});

/** The figures drawn at each of `frames` (timeline frames): label, colour, projected box, and the canvas size. */
const figuresAt = (t: Target, frames: number[]) => t.evaluate((fs) => {
  const app = document.querySelector('motion-futures')!.app!;
  const canvas = app.host.shadowRoot!.querySelector('canvas')!;
  app.player.pause();
  return fs.map((f) => {
    app.player.seek(f);
    return { frame: f, width: canvas.clientWidth, height: canvas.clientHeight, figures: app.view.figures() };
  });
}, frames);

/** Timeline frames worth checking: the first predicted one, the middle of the futures, the last. */
const keyFrames = (t: Target) => t.evaluate((n) => {
  const length = document.querySelector('motion-futures')!.app!.player.state.length;
  return [n, Math.floor((n + length - 1) / 2), length - 1];
}, N);

function expectFramed(shots: Awaited<ReturnType<typeof figuresAt>>, what: string): void {
  for (const s of shots) {
    expect(s.figures.length, `${what}: figures at frame ${s.frame}`).toBeGreaterThan(0);
    for (const f of s.figures) {
      const where = `${what}, frame ${s.frame}, ${f.label}`;
      expect(f.box.left, where).toBeGreaterThanOrEqual(0);
      expect(f.box.top, where).toBeGreaterThanOrEqual(0);
      expect(f.box.right, where).toBeLessThanOrEqual(s.width);
      expect(f.box.bottom, where).toBeLessThanOrEqual(s.height);
      expect(f.box.bottom - f.box.top, `${where}: height in px`).toBeGreaterThanOrEqual(MIN_FIGURE_PX);
    }
  }
}

/** A fingerprint of the futures on stage. */
const futures = (t: Target) => t.evaluate(() => {
  const p = document.querySelector('motion-futures')!.app!.predictor.last?.prediction;
  if (!p) return null;
  const bytes = new Uint8Array(p.futures.buffer, p.futures.byteOffset, p.futures.byteLength);
  let h = 2166136261;
  for (const b of bytes) { h ^= b; h = Math.imul(h, 16777619) >>> 0; }
  return `${p.k}:${Array.from(p.lengths).join(',')}:${h.toString(16)}`;
});

/** Wait until the futures on stage differ from `before` (a new prediction, asked for by nothing but a change). */
const changedFrom = (page: Page, before: string | null) => page.waitForFunction((b) => {
  const app = window.motionFutures!;
  const p = app.predictor.last?.prediction;
  if (!p || document.body.dataset.predictStatus !== 'done') return false;
  const bytes = new Uint8Array(p.futures.buffer, p.futures.byteOffset, p.futures.byteLength);
  let h = 2166136261;
  for (const x of bytes) { h ^= x; h = Math.imul(h, 16777619) >>> 0; }
  return `${p.k}:${Array.from(p.lengths).join(',')}:${h.toString(16)}` !== b;
}, before, { timeout: 60_000, polling: 100 });

describe('the first view (1440 x 900)', () => {
  let session: BrowserSession;
  let page: Page;

  beforeAll(async () => {
    session = await openBrowser({ viewport: { width: 1440, height: 900 } });
    page = session.page;
    await session.context.grantPermissions(['clipboard-read', 'clipboard-write'], { origin: new URL(baseUrl).origin });
    await page.goto(baseUrl);
    await predicted(page);
  });
  afterAll(async () => { await session?.close(); });

  it(`shows K = ${FIRST_K} futures of ${stageModel.label} from the default held-out history within 5 s, without a click`, async () => {
    const d = await page.evaluate(() => ({ ...document.body.dataset }));
    expect(d.predictionModel).toBe(stageModel.id);
    expect(d.predictionK).toBe(String(FIRST_K));
    const shownAt = await page.evaluate(() => performance.getEntriesByName('mf:prediction-shown')[0]?.startTime ?? Infinity);
    expect(shownAt, 'ms from navigation to the futures on stage').toBeLessThanOrEqual(FIRST_FUTURES_MS);
    const { clip, start } = defaultHistory();
    expect(d.currentClip).toBe(clip.name);
    expect(await page.locator('#history-start').inputValue()).toBe(String(start));
    // held out: the whole window lies in a test range of the split
    expect(clip.test.some(([a, b]) => a <= start && start + N <= b), `${clip.name}@${start} lies in the test split`).toBe(true);
    expect(await page.locator('.history-note').textContent()).toMatch(/test part/);
    console.log(`first futures on stage ${shownAt.toFixed(0)} ms after navigation (${clip.name}@${start})`);
  });

  it.skipIf(!index.default)("the index's default history has ground truth for the whole horizon, and the read-out gives its numbers", async () => {
    const { clip, start } = defaultHistory();
    const horizon = horizonFrames(stageModel);
    expect(clip.test.some(([a, b]) => a <= start && start + N + horizon <= b), `${clip.name}@${start}: ${N} + ${horizon} frames held out`).toBe(true);
    const r = await page.evaluate(() => window.motionFutures!.predictor.last!.readout);
    expect(r?.covered).toBe(true);
    expect(r!.truthFrames).toBeGreaterThanOrEqual(r!.frames);
  });

  it('the read-out the worker computed equals the one the page computes for the same prediction', async () => {
    const [fromWorker, onPage] = await page.evaluate(() => {
      const pc = window.motionFutures!.predictor;
      const worker = pc.last!.readout;
      pc.present(pc.last!.prediction, pc.last!.ms); // a replay: the page computes the read-out itself
      return [worker, pc.last!.readout];
    });
    expect(fromWorker?.samples).toHaveLength(FIRST_K);
    expect(onPage).toEqual(fromWorker);
  });

  it(`every pair of futures is at least ${MIN_PAIR_M * 100} cm apart at their last common frame`, async () => {
    const d = await pairDistances(page);
    expect(d).toHaveLength((FIRST_K * (FIRST_K - 1)) / 2);
    expect(Math.min(...d)).toBeGreaterThanOrEqual(MIN_PAIR_M);
  });

  it(`keeps K > 3 samples apart, frames every figure, each at least ${MIN_FIGURE_PX} px tall`, async () => {
    expect(await page.locator('input[name="layout"][value="side"]').isChecked()).toBe(true);
    expectFramed(await figuresAt(page, await keyFrames(page)), 'first view');
  });

  it('names every figure: a legend, one label per figure, swatches in the figures\' own colours', async () => {
    const legend = page.getByTestId('legend');
    for (const role of ['history', 'truth', 'prediction']) expect(await legend.locator(`[data-role="${role}"]`).count(), role).toBe(1);
    expect(await legend.textContent()).toMatch(/history.*ground truth.*samples #1–5/);
    // At the first predicted frame every sample is drawn: one visible label per figure, with its name.
    const [shot] = await figuresAt(page, [N]);
    await settle(page); // labels show or hide when the stage renders
    const labels = await page.evaluate(() => [...document.querySelector('motion-futures')!.shadowRoot!.querySelectorAll<HTMLElement>('.figure-label')]
      .filter((l) => l.style.display !== 'none').map((l) => l.textContent));
    expect(labels.sort()).toEqual(shot.figures.map((f) => f.label).sort());
    expect(shot.figures.filter((f) => f.role === 'prediction').map((f) => f.label.replace(/ ·.*$/, '')).sort())
      .toEqual(Array.from({ length: FIRST_K }, (_, i) => `#${i + 1}`).sort());
    const swatches = await page.evaluate(() => [...document.querySelector('motion-futures')!.shadowRoot!.querySelectorAll<HTMLElement>('[data-testid="sample-swatch"]')]
      .map((s) => `#${getComputedStyle(s).backgroundColor.match(/\d+/g)!.slice(0, 3).map((v) => Number(v).toString(16).padStart(2, '0')).join('')}`));
    const colours = shot.figures.filter((f) => f.role === 'prediction').sort((a, b) => a.sample! - b.sample!).map((f) => f.colour);
    expect(swatches).toEqual(colours);
    await writeFile('/tmp/stage-first-1440.png', await session.screenshot('stage-first-1440.png'));
    expect(session.problems).toEqual(NO_PROBLEMS);
  });

  it('selecting a sample in the list or on the stage highlights it in both', async () => {
    await page.evaluate(() => window.motionFutures!.player.pause());
    await page.locator('.sample-button').nth(2).click();
    const selected = () => page.evaluate(() => [...document.querySelector('motion-futures')!.shadowRoot!.querySelectorAll('.figure-label-selected')].map((e) => e.textContent));
    expect((await selected()).map((t) => t!.replace(/ ·.*$/, ''))).toEqual(['#3']);
    await page.locator('.figure-label[data-sample="0"]').click();
    expect(await page.locator('.sample-button').first().getAttribute('aria-pressed')).toBe('true');
    expect(await page.locator('.sample-button').nth(2).getAttribute('aria-pressed')).toBe('false');
    expect((await selected()).map((t) => t!.replace(/ ·.*$/, ''))).toEqual(['#1']);
    await page.locator('.figure-label[data-sample="0"]').click();
    expect(await page.locator('.sample-button[aria-pressed="true"]').count()).toBe(0);
  });

  it('the scrubber shades the history and marks its end; t reads 0 at the first predicted frame', async () => {
    expect(await page.getByTestId('scrubber-marks').locator('.scrubber-now').getAttribute('data-frame')).toBe(String(N));
    expect(await page.getByTestId('scrubber-marks').locator('.scrubber-history').count()).toBe(1);
    await page.evaluate((n) => window.motionFutures!.player.seek(n), N);
    expect(await page.getByTestId('time').textContent()).toMatch(/^t = 0\.00 s \/ \d+\.\d\d s \(frame \d+\)$/);
    expect(await page.getByTestId('phase').textContent()).toBe('0.0 s');
    await page.evaluate(() => window.motionFutures!.player.seek(0));
    expect(await page.getByTestId('time').textContent()).toMatch(/^t = −\d\.\d\d s/);
    expect(await page.getByTestId('phase').textContent()).toBe('history');
    const later = await page.evaluate((f) => { const pl = window.motionFutures!.player; pl.seek(Math.min(f, pl.state.length - 1)); return pl.state.frame; }, N + 24);
    expect(await page.getByTestId('phase').textContent()).toBe(later === N ? '0.0 s' : `+${((later - N) / 30).toFixed(1)} s`);
    // each sample that stopped (Eq. 8) or was cut has its mark, at its last frame
    const p = await page.evaluate(() => { const x = window.motionFutures!.predictor.last!.prediction; return x.samples.map((s) => ({ length: s.length, stopped: s.stopped, cut: Boolean(s.cut) })); });
    const marks = await page.getByTestId('scrubber-marks').locator('.scrubber-mark').evaluateAll((ms) => ms.map((m) => ({ frame: Number(m.getAttribute('data-frame')), cut: m.classList.contains('scrubber-cut') })));
    expect(marks).toEqual(p.flatMap((s) => (s.stopped || s.cut ? [{ frame: N + s.length - 1, cut: s.cut }] : [])));
  });

  it('the read-out leads with the per-joint error and the pose spread in cm, then the field units; copies them as JSON', async () => {
    const r = await page.evaluate(() => window.motionFutures!.predictor.last!.readout!);
    const cmText = (v: number) => `${v.toFixed(1)} cm`;
    const lead = (metric: string, kind: string) => page.locator(`.readout-lead tr[data-metric="${metric}"] td[data-kind="${kind}"]`).textContent();
    expect(await lead('spread', 'over_frames')).toBe(cmText(r.spreadCm.overFrames));
    expect(await lead('spread', 'last')).toBe(cmText(r.spreadCm.last));
    // the field's numbers follow, labelled as such, with how they relate and where they are defined
    expect(await page.locator('.readout-field-title').textContent()).toMatch(/^Field units/);
    const about = (await page.locator('.readout-about').textContent())!;
    expect(about).toMatch(/ADE and FDE .*√18 ≈ 4\.2 × the per-joint mean/);
    // APD flattens all frames into one vector: its factor is sqrt(18 x frames), and the numbers shown obey it
    const factor = Math.sqrt(18 * r.frames);
    expect(about).toContain(`APD puts each sample's whole future, ${r.frames} frames × 18 joints, into one vector: at least √(18 × ${r.frames}) ≈ ${factor.toFixed(0)} × the pose spread.`);
    expect(r.apd).toBeGreaterThanOrEqual(factor * r.spreadCm.overFrames / 100);
    if (r.covered) expect(r.best!.rootRelative.ade).toBeGreaterThanOrEqual(Math.sqrt(18) * r.bestPerJointCm!.ade / 100);
    expect(new URL((await page.locator('.readout-help').getAttribute('href'))!).pathname).toMatch(/explainer\.html$/);
    expect(new URL((await page.locator('.readout-help').getAttribute('href'))!).hash).toBe('#numbers');
    expect(await page.locator('.readout-apd .metric').textContent()).toBe(`${r.apd.toFixed(3)} m`);
    if (r.covered) {
      expect(await lead('per-joint', 'over_frames')).toBe(cmText(r.bestPerJointCm!.ade));
      expect(await lead('per-joint', 'last')).toBe(cmText(r.bestPerJointCm!.fde));
      // the lead numbers come first in the read-out
      const order = await page.getByTestId('readout').evaluate((e) => [...e.querySelectorAll('.readout-lead, .readout-field')].map((x) => x.className));
      expect(order).toEqual(['readout-lead', 'readout-field']);
      const cell = (metric: string, kind: string) => page.locator(`.readout-table tr[data-metric="${metric}"] td[data-kind="${kind}"]`).textContent();
      expect(await cell('best-of-K ADE', 'root_relative')).toBe(`${r.best!.rootRelative.ade.toFixed(3)} m`);
      expect(await cell('best-of-K ADE', 'world')).toBe(`${r.best!.world.ade.toFixed(3)} m`);
      expect(await cell('best-of-K FDE', 'root_relative')).toBe(`${r.best!.rootRelative.fde.toFixed(3)} m`);
      expect(await page.locator('.sample-numbers').count()).toBe(FIRST_K);
      expect(await page.locator('.sample-numbers [data-kind="per_joint_cm"]').allTextContents()).toEqual(r.samples.map((x) => cmText(x.perJointCm!.ade)));
    } else {
      expect(await page.locator('.readout-uncovered').textContent()).toMatch(/ground truth covers/);
    }
    await page.getByTestId('copy-numbers').click();
    await expect.poll(() => page.locator('.copy-status').textContent()).toBe('Copied.');
    const json = JSON.parse(await page.evaluate(() => navigator.clipboard.readText()));
    expect(json.model).toBe(stageModel.id);
    expect(json.samples).toHaveLength(FIRST_K);
    expect(json.best_of_k === null).toBe(!r.covered);
    expect(json.pose_spread_cm.over_frames).toBeCloseTo(r.spreadCm.overFrames, 3);
    if (r.covered) expect(json.best_of_k.root_relative.ade).toBeCloseTo(r.best!.rootRelative.ade, 5);
    if (r.covered) expect(json.per_joint_cm_best_of_k.ade).toBeCloseTo(r.bestPerJointCm!.ade, 3);
  });

  it('every number in the read-out explains itself on hover (title) and on keyboard focus (tooltip, description)', async () => {
    // the read-out's numbers, then the method's own under the futures (WAT: stopped, mean length, flagged)
    const numbers = page.locator('.stage-readout .metric, .readouts .metric');
    const count = await numbers.count();
    expect(count).toBeGreaterThanOrEqual(3); // spread twice and APD at least
    expect(await page.locator('.readouts li').count(), 'each of the method\'s numbers is a .metric').toBe(await page.locator('.readouts .metric').count());
    // a share of the K samples reads as one ("0 %", "40 %", "33.3 %"), not "0.000 %"
    const shares = (await page.locator('.readouts .metric').allTextContents()).filter((t) => t.endsWith('%'));
    if (stageModel.method === 'wat') expect(shares, 'WAT\'s "stopped"').toHaveLength(1);
    for (const t of shares) expect(t).toMatch(/^\d+(\.\d)? %$/);
    for (let i = 0; i < count; i++) {
      const n = numbers.nth(i);
      const info = await n.evaluate((e) => {
        const root = e.getRootNode() as ShadowRoot;
        const described = root.getElementById(e.getAttribute('aria-describedby') ?? '')?.textContent ?? '';
        return { tab: (e as HTMLElement).tabIndex, title: e.getAttribute('title') ?? '', described };
      });
      expect(info.tab, `number ${i} takes the focus`).toBe(0);
      expect(info.title.length, `number ${i} has a title`).toBeGreaterThan(20);
      expect(info.described).toBe(info.title);
      await n.focus();
      const tip = page.locator('.metric-tooltip');
      await expect.poll(() => tip.isVisible()).toBe(true);
      expect(await tip.textContent()).toBe(info.title);
    }
    // each sample's line of numbers: focusable and explained, each number with its own title
    const line = page.locator('.sample-numbers').first();
    expect(await line.getAttribute('tabindex')).toBe('0');
    expect((await line.getAttribute('title'))!.length).toBeGreaterThan(20);
    for (const t of await line.locator('.sample-number').evaluateAll((ns) => ns.map((x) => x.getAttribute('title') ?? ''))) expect(t.length).toBeGreaterThan(10);
    await line.focus();
    await expect.poll(() => page.locator('.metric-tooltip').textContent()).toBe(await line.getAttribute('title'));
    await page.locator('#predict').focus();
    await expect.poll(() => page.locator('.metric-tooltip').isVisible()).toBe(false);
  });

  it('names the clip as a newcomer reads it: action · person (split) · take, in the list, the facts, the status and the history', async () => {
    const { clip } = defaultHistory();
    const title = clipTitle(clip);
    expect(title).not.toContain('_');
    expect(await page.locator(`[data-clip="${clip.name}"] .clip-name`).evaluate((e) => e.firstChild?.textContent)).toBe(clipShortTitle(clip));
    expect(await page.locator(`[data-clip="${clip.name}"]`).getAttribute('title')).toContain(title);
    expect(await page.getByTestId('clip-info').locator('[data-field="clip"]').textContent()).toBe(title);
    expect(await page.getByTestId('stage-status').textContent()).toContain(`of ${title}`);
    expect(await page.locator('.history-note').textContent()).toContain(`of ${title}`);
    // every clip in the list has its readable name
    const titles = await page.locator('.clip-button').evaluateAll((bs) => bs.map((b) => [b.getAttribute('data-clip'), b.getAttribute('data-title')]));
    for (const [name, t] of titles) expect(t, name!).toBe(clipTitle(index.clips.find((c) => c.name === name)!));
  });

  it('the legend\'s left/right swatches show the limb colours the sample figures are drawn in', async () => {
    const backgrounds = await page.getByTestId('legend').locator('.legend-limbs .swatch').evaluateAll((ss) => ss.map((x) => getComputedStyle(x).backgroundImage));
    expect(backgrounds).toHaveLength(2);
    const rgb = (side: 'left' | 'right', i: number) => `rgb(${tintColour(side, { role: 'prediction', sample: i }).map((v) => Math.round(v * 255)).join(', ')})`;
    for (let i = 0; i < FIRST_K; i++) {
      expect(backgrounds[0], `left of #${i + 1}`).toContain(rgb('left', i));
      expect(backgrounds[1], `right of #${i + 1}`).toContain(rgb('right', i));
    }
  });

  it('the permalink carries the selected sample, the paused frame and the layout, and a new tab restores them', async () => {
    await page.locator('input[name="layout"][value="overlay"]').check();
    await page.locator('.sample-button').nth(1).click();
    const frame = N + 7;
    await page.evaluate((f) => { const pl = window.motionFutures!.player; pl.pause(); pl.seek(f); }, frame);
    await expect.poll(() => new URL(page.url()).searchParams.get('frame')).toBe(String(frame));
    const q = new URL(page.url()).searchParams;
    expect(q.get('sample')).toBe('2');
    expect(q.get('layout')).toBe('overlay');
    const tab = await session.context.newPage();
    try {
      await tab.goto(page.url());
      await predicted(tab);
      await tab.waitForFunction((f) => window.motionFutures!.player.state.frame === f, frame);
      expect(await tab.evaluate(() => window.motionFutures!.player.state.playing)).toBe(false);
      expect(await tab.evaluate(() => window.motionFutures!.predictor.selected)).toBe(1);
      expect(await tab.locator('.sample-button').nth(1).getAttribute('aria-pressed')).toBe('true');
      expect(await tab.locator('input[name="layout"][value="overlay"]').isChecked()).toBe(true);
      expect(await tab.locator('.message').count()).toBe(0);
    } finally {
      await tab.close();
    }
    // back to how the first view was, for the tests after this one
    await page.locator('.sample-button').nth(1).click();
    await page.locator('input[name="layout"][value="side"]').check();
    await expect.poll(() => new URL(page.url()).searchParams.get('sample')).toBeNull();
    expect(session.problems).toEqual(NO_PROBLEMS);
  });

  it('the status line names the model, the history, the seed and the controls of what is shown', async () => {
    const text = await page.getByTestId('stage-status').textContent();
    const { clip, start } = defaultHistory();
    expect(text).toContain(stageModel.label);
    expect(text).toContain(`frames ${start}–${start + N - 1} of ${clipTitle(clip)}`);
    expect(text).toMatch(/seed \d+/);
    expect(text).toContain(`K = ${FIRST_K}`);
  });
});

describe('never stale: every change predicts again on its own', () => {
  let session: BrowserSession;
  let page: Page;

  beforeAll(async () => {
    session = await openBrowser({ viewport: { width: 1280, height: 860 } });
    page = session.page;
    await page.goto(baseUrl);
    await predicted(page);
  });
  afterAll(async () => { await session?.close(); });

  it('a new seed (typed, or "New seed") changes the futures with no click on Predict', async () => {
    let before = await futures(page);
    await page.locator('#seed').fill('12345');
    await page.locator('#seed').dispatchEvent('change');
    expect(await page.evaluate(() => document.body.dataset.stale)).toBe('true'); // marked until the new futures are in
    await changedFrom(page, before);
    expect(await page.getByTestId('stage-status').textContent()).toMatch(/seed 12345/);
    before = await futures(page);
    await page.getByRole('button', { name: 'New seed' }).click();
    await changedFrom(page, before);
  });

  it('a control (K) changes the futures', async () => {
    const before = await futures(page);
    await page.locator('#control-k').fill('3');
    await page.locator('#control-k').dispatchEvent('change');
    await changedFrom(page, before);
    expect(await page.evaluate(() => document.body.dataset.predictionK)).toBe('3');
  });

  it('another model changes the futures; K keeps its value across models; a deterministic model has no seed', async () => {
    const other = manifest.models.find((m) => m.id !== stageModel.id && m.method !== 'keyposes')!;
    const before = await futures(page);
    await page.locator('#model-select').selectOption(other.id);
    await changedFrom(page, before);
    expect(await page.evaluate(() => document.body.dataset.predictionModel)).toBe(other.id);
    const stochastic = other.controls.some((c) => c.id === 'k');
    if (stochastic) expect(await page.locator('#control-k').inputValue()).toBe('3'); // the K set above, not the manifest's
    // a model without K draws one future whatever the seed: the seed is off, and says why
    expect(await page.locator('#seed').isDisabled()).toBe(!stochastic);
    expect(await page.locator('#new-seed').isDisabled()).toBe(!stochastic);
    expect(await page.locator('#seed-note').isVisible()).toBe(!stochastic);
    if (!stochastic) expect(await page.locator('#seed-note').textContent()).toMatch(/deterministic/);
    await page.locator('#model-select').selectOption(stageModel.id);
    await page.waitForFunction((id) => document.body.dataset.predictionModel === id && document.body.dataset.predictStatus === 'done', stageModel.id);
    expect(await page.locator('#control-k').inputValue()).toBe('3');
    expect(await page.evaluate(() => document.body.dataset.predictionK)).toBe('3');
    expect(await page.locator('#seed').isDisabled()).toBe(false);
    expect(await page.locator('#seed-note').isVisible()).toBe(false);
    // another stochastic model keeps it too
    const third = manifest.models.find((m) => m.id !== stageModel.id && m.controls.some((c) => c.id === 'k'));
    if (third) {
      await page.locator('#model-select').selectOption(third.id);
      expect(await page.locator('#control-k').inputValue()).toBe('3');
      await page.waitForFunction((id) => document.body.dataset.predictionModel === id && document.body.dataset.predictStatus === 'done', third.id, { timeout: 60_000 });
      await page.locator('#model-select').selectOption(stageModel.id);
      await page.waitForFunction((id) => document.body.dataset.predictionModel === id && document.body.dataset.predictStatus === 'done', stageModel.id, { timeout: 60_000 });
    }
  });

  it('another history (another clip) changes the futures, and clears the last export\'s "Saved …"', async () => {
    const clip = otherClip(defaultHistory().clip.name);
    const before = await futures(page);
    await Promise.all([page.waitForEvent('download'), page.locator('#export-csv').click()]);
    await expect.poll(() => page.locator('.export-status').textContent()).toMatch(/^Saved /);
    await page.locator(`[data-clip="${clip.name}"]`).click();
    await changedFrom(page, before);
    expect(await page.locator('.export-status').textContent()).toBe('');
    expect(await page.getByTestId('stage-status').textContent()).toContain(`of ${clipTitle(clip)}`);
    expect(session.problems).toEqual(NO_PROBLEMS);
  });

  it('with predict="0" nothing predicts until asked', async () => {
    const s = await openBrowser();
    try {
      await s.page.goto(`${baseUrl}?predict=0`);
      await s.page.waitForSelector('body[data-clip-status="ready"]', { state: 'attached', timeout: 60_000 });
      await s.page.locator('#seed').fill('99');
      await s.page.locator('#seed').dispatchEvent('change');
      await s.page.waitForTimeout(1500); // nothing should start, which only time can show
      expect(await s.page.evaluate(() => document.body.dataset.predictionModel)).toBeUndefined();
      expect(await s.page.getByTestId('stage-status').textContent()).toMatch(/Press Predict/);
      await s.page.locator('#predict').click();
      await predicted(s.page);
      expect(s.problems).toEqual(NO_PROBLEMS);
    } finally {
      await s.close();
    }
  });
});

describe('K = 10 side by side', () => {
  it(`frames every figure inside the canvas, each at least ${MIN_FIGURE_PX} px tall`, async () => {
    const session = await openBrowser({ viewport: { width: 1440, height: 900 } });
    try {
      const { page } = session;
      await page.goto(`${baseUrl}?model=${stageModel.id}&k=10`);
      await predicted(page);
      await page.locator('input[name="layout"][value="side"]').check();
      await settle(page);
      expect(await page.evaluate(() => document.body.dataset.predictionK)).toBe('10');
      const shots = await figuresAt(page, await keyFrames(page));
      expect(shots[0].figures.filter((f) => f.role === 'prediction')).toHaveLength(10);
      expectFramed(shots, 'K = 10 side by side');
      // every sample in the list, with no box scrolling inside the panel: with the list scrolled into
      // the panel's view, all ten rows lie inside the panel and the window
      const list = await page.locator('.sample-list').evaluate((l) => {
        l.scrollIntoView({ block: 'start' });
        const panel = l.closest('.panel')!.getBoundingClientRect();
        const cs = getComputedStyle(l);
        return { overflow: cs.overflowY, scroll: l.scrollHeight, client: l.clientHeight, panel: { top: panel.top, bottom: panel.bottom },
          rows: [...l.querySelectorAll('.sample-item')].map((r) => { const b = r.getBoundingClientRect(); return { top: b.top, bottom: b.bottom }; }) };
      });
      expect(list.overflow).toBe('visible');
      expect(list.scroll).toBeLessThanOrEqual(list.client + 1);
      expect(list.rows).toHaveLength(10);
      for (const [i, r] of list.rows.entries()) {
        expect(r.top, `sample #${i + 1}`).toBeGreaterThanOrEqual(list.panel.top - 1);
        expect(r.bottom, `sample #${i + 1}`).toBeLessThanOrEqual(Math.min(list.panel.bottom, 900) + 1);
      }
      await writeFile('/tmp/stage-k10-list.png', await session.screenshot('stage-k10-list.png'));
      await page.evaluate((n) => window.motionFutures!.player.seek(n + 12), N);
      await settle(page);
      await writeFile('/tmp/stage-k10-side.png', await session.screenshot('stage-k10-side.png'));
      expect(session.problems).toEqual(NO_PROBLEMS);
    } finally {
      await session.close();
    }
  });
});

describe('the phone (390 x 844)', () => {
  it('shows the first view with every figure inside the canvas', async () => {
    const session = await openBrowser({ viewport: { width: 390, height: 844 } });
    try {
      const { page } = session;
      await page.goto(baseUrl);
      await predicted(page);
      const shots = await figuresAt(page, await keyFrames(page));
      for (const s of shots) {
        for (const f of s.figures) {
          expect(f.box.left).toBeGreaterThanOrEqual(0);
          expect(f.box.right).toBeLessThanOrEqual(s.width);
          expect(f.box.top).toBeGreaterThanOrEqual(0);
          expect(f.box.bottom).toBeLessThanOrEqual(s.height);
        }
      }
      // the legend fits the screen (it wraps, never runs off it), and so does the sample list
      const legend = await page.getByTestId('legend').evaluate((l) => ({ right: l.getBoundingClientRect().right, scroll: l.scrollWidth, client: l.clientWidth,
        items: [...l.children].map((c) => c.getBoundingClientRect()).map((b) => ({ right: b.right, bottom: b.bottom })), bottom: l.getBoundingClientRect().bottom }));
      expect(legend.right).toBeLessThanOrEqual(390);
      expect(legend.scroll).toBeLessThanOrEqual(legend.client);
      for (const item of legend.items) { expect(item.right).toBeLessThanOrEqual(390); expect(item.bottom).toBeLessThanOrEqual(legend.bottom + 1); }
      const rows = await page.locator('.sample-item').evaluateAll((rs) => rs.map((r) => r.getBoundingClientRect().right));
      expect(rows).toHaveLength(FIRST_K);
      for (const right of rows) expect(right).toBeLessThanOrEqual(390);
      expect(await page.evaluate(() => document.documentElement.scrollWidth)).toBeLessThanOrEqual(390);
      await page.evaluate((n) => window.motionFutures!.player.seek(n + 12), N);
      await settle(page);
      await writeFile('/tmp/stage-first-390.png', await session.screenshot('stage-first-390.png'));
      await page.locator('.sample-list').evaluate((l) => l.scrollIntoView({ block: 'start' }));
      await writeFile('/tmp/stage-first-390-list.png', await session.screenshot('stage-first-390-list.png'));
      expect(session.problems).toEqual(NO_PROBLEMS);
    } finally {
      await session.close();
    }
  });
});

describe('the bare embed (embed.html in a 720 x 480 iframe)', () => {
  it(`shows K = ${FIRST_K} futures of ${stageModel.label} within 5 s, apart; the stage is at least 75% of the frame; "New futures" changes them`, async () => {
    const session = await openBrowser({ viewport: { width: 900, height: 700 } });
    try {
      const { page } = session;
      const host = `${new URL(baseUrl).origin}/elsewhere/embed-host.html`;
      await page.route(host, (route) => route.fulfill({ status: 200, contentType: 'text/html',
        body: `<!doctype html><html lang="en"><head><meta charset="utf-8"><title>host</title></head><body style="margin:0">`
          + `<iframe id="f" src="${baseUrl}embed.html" width="720" height="480" style="border:0; display:block"></iframe></body></html>` }));
      await page.goto(host);
      const frame = page.frame({ url: /embed\.html/ })!;
      await frame.waitForSelector('motion-futures[data-predict-status="done"]', { state: 'attached', timeout: 120_000 });
      const widget = frame.locator('motion-futures');
      expect(await widget.getAttribute('data-prediction-model')).toBe(stageModel.id);
      expect(await widget.getAttribute('data-prediction-k')).toBe(String(FIRST_K));
      const shownAt = await frame.evaluate(() => performance.getEntriesByName('mf:prediction-shown')[0]?.startTime ?? Infinity);
      expect(shownAt, 'ms from the embed\'s navigation to its futures').toBeLessThanOrEqual(FIRST_FUTURES_MS);
      const pairs = await pairDistances(frame);
      const stage = (await frame.locator('#viewer').boundingBox())!;
      expect(stage.height / 480, 'the stage\'s share of the frame height').toBeGreaterThanOrEqual(0.75);
      // no text refers to what the minimal embed does not show
      const visibleText = await frame.evaluate(() => {
        const root = document.querySelector('motion-futures')!.shadowRoot!;
        const walker = document.createTreeWalker(root, NodeFilter.SHOW_TEXT);
        const out: string[] = [];
        for (let n = walker.nextNode(); n; n = walker.nextNode()) {
          const parent = n.parentElement!;
          const r = parent.getBoundingClientRect();
          if (r.width > 1 && r.height > 1 && parent.checkVisibility()) out.push(n.textContent ?? '');
        }
        return out.join(' ');
      });
      expect(visibleText).not.toMatch(/\bin the list\b|\bPredict\b.*button|the panel|Samples \(K\)/);
      await frame.evaluate((n) => { const p = document.querySelector('motion-futures')!.app!.player; p.pause(); p.seek(n + 12); }, N);
      await settle(page);
      await writeFile('/tmp/stage-embed-720.png', await session.screenshot('stage-embed-720.png', page.locator('#f')));
      const before = await futures(frame);
      await frame.getByTestId('new-futures').click();
      await frame.waitForFunction((b) => {
        const p = document.querySelector('motion-futures')!.app!.predictor.last?.prediction;
        if (!p) return false;
        const bytes = new Uint8Array(p.futures.buffer, p.futures.byteOffset, p.futures.byteLength);
        let h = 2166136261;
        for (const x of bytes) { h ^= x; h = Math.imul(h, 16777619) >>> 0; }
        return `${p.k}:${Array.from(p.lengths).join(',')}:${h.toString(16)}` !== b;
      }, before, { timeout: 60_000 });
      expect(session.problems).toEqual(NO_PROBLEMS);
      expect(Math.min(...pairs), 'the closest pair of the first futures (m)').toBeGreaterThanOrEqual(MIN_PAIR_M);
    } finally {
      await session.close();
    }
  });
});

describe('what lies over the stage never moves it', () => {
  let session: BrowserSession;
  let page: Page;
  const stageBox = () => page.locator('#viewer').boundingBox();

  beforeAll(async () => {
    session = await openBrowser({ viewport: { width: 1280, height: 860 } });
    page = session.page;
    await page.goto(baseUrl);
    await predicted(page);
  });
  afterAll(async () => { await session?.close(); });

  it('a bad BVH file is one sentence on the stage, with the details behind a toggle', async () => {
    const before = await stageBox();
    const joints = Array.from({ length: 40 }, (_, i) => `  JOINT Strange_${i}\n  {\n    OFFSET 0 1 0\n    CHANNELS 3 Zrotation Xrotation Yrotation\n    End Site\n    {\n      OFFSET 0 1 0\n    }\n  }`).join('\n');
    const bvh = `HIERARCHY\nROOT Blob\n{\n  OFFSET 0 0 0\n  CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n${joints}\n}\nMOTION\nFrames: 40\nFrame Time: 0.0333333\n${Array.from({ length: 40 }, () => Array(6 + 40 * 3).fill('0').join(' ')).join('\n')}\n`;
    await page.evaluate((text) => {
      const dt = new DataTransfer();
      dt.items.add(new File([text], 'strange.bvh', { type: 'application/octet-stream' }));
      const host = document.querySelector('motion-futures')!;
      host.dispatchEvent(new DragEvent('drop', { dataTransfer: dt, bubbles: true, cancelable: true }));
    }, bvh);
    const message = page.locator('.message-error').first();
    await message.waitFor();
    const summary = (await message.locator('.message-text').textContent())!;
    expect(summary.length).toBeLessThanOrEqual(121);
    expect(summary).toMatch(/^Could not import: strange\.bvh/);
    expect((await message.locator('.message-text').boundingBox())!.height).toBeLessThan(30); // one line
    expect(await message.locator('.message-details').count()).toBe(1);
    await message.locator('.message-details summary').click();
    expect(await message.locator('.message-details p').textContent()).toMatch(/Strange_|joint/);
    expect(await stageBox()).toEqual(before);
    await page.screenshot({ path: '/tmp/stage-bad-bvh.png' });
    session.resetProblems();
  });

  it('a history outside the training range: one sentence, details behind a toggle, the futures still shown and marked', async () => {
    const before = await stageBox();
    await page.evaluate(() => {
      const app = window.motionFutures!;
      const p = app.predictor.last!.prediction;
      const cutAt = Math.max(1, Math.floor(p.lengths[1] / 2));
      app.predictor.present({
        ...p,
        lengths: Int32Array.from(p.lengths, (l, i) => (i === 1 ? cutAt : l)),
        samples: p.samples.map((s, i) => (i === 1
          ? { ...s, length: cutAt, cut: { frame: cutAt - 1, reason: 'cut: out of bounds' as const, detail: 'test: a joint 9 m from the root' } }
          : { ...s, cut: undefined })),
        warnings: [{ quantity: 'root height', value: 1.8, min: 0.7, max: 1.17, unit: 'm', message: 'The root is higher than in any training window.' }],
      });
    });
    const notice = page.getByTestId('range-notice');
    await notice.waitFor();
    expect(await notice.locator('.range-notice-text').textContent()).toMatch(/^Out of range: .*root height.*shown anyway\.$/);
    await notice.locator('summary').click();
    expect(await notice.locator('li[data-quantity="root height"]').textContent()).toMatch(/1\.80 m; training range 0\.70–1\.17 m/);
    expect(await stageBox()).toEqual(before);
    expect(await page.evaluate(() => document.body.dataset.predictionRange)).toBe('out');
    expect(await page.getByTestId('stage-status').textContent()).toMatch(/Out of the training range/);
    // the cut sample: its list row and its scrubber mark say "cut", apart from Eq. 8's stop
    expect(await page.locator('.sample-button[data-sample="1"]').textContent()).toMatch(/cut \(out of bounds\)/);
    expect(await page.getByTestId('scrubber-marks').locator('.scrubber-cut').count()).toBe(1);
    expect(await page.getByTestId('scrubber-marks').locator('.scrubber-cut').getAttribute('data-sample')).toBe('1');
    expect(await page.locator('.figure-label[data-sample="1"]').textContent()).toMatch(/cut/);
    await page.screenshot({ path: '/tmp/stage-out-of-range.png' });
  });
});
