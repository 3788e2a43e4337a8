// Issue 29 items 2, 4 and 7 in a real Chromium. Compare mode: two models from a permalink on the same
// history end and seed, one labelled row per model on stage, each with its read-out, kept in the link,
// and in an embed through its compare attribute; an unknown model id is named. The closest-to-truth
// highlight marks one sample in each row, and the exports (JSON, CSV) and the read-out's JSON hold
// every compared model, labelled, the ground truth once and the foot-planting option; at K = 5 every figure's
// label (the model's short name) lies inside the stage. A refusal: the stage
// drops the previous model's futures, says so in one sentence and offers the nearest start the method
// accepts, which then predicts; a clip with no such start says so.
import { mkdirSync, readFileSync, writeFileSync } from 'node:fs';
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
    return app.view.figures().map((x) => ({ role: x.role, group: x.group, sample: x.sample, label: x.label, best: x.best, cy: (x.box.top + x.box.bottom) / 2 }));
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
    await session.context.grantPermissions(['clipboard-read', 'clipboard-write'], { origin: new URL(baseUrl).origin });
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

  it('at the first view\'s K = 5, every figure label lies whole inside the stage, the model named short', async () => {
    await waiting(page);
    await page.goto(`${baseUrl}?compare=${COMPARE}`);
    await predicted(page);
    await page.waitForSelector(`body[data-compare-models="${COMPARE}"]`, { state: 'attached' });
    expect(await page.evaluate(() => document.body.dataset.predictionK)).toBe('5');
    const length = await page.evaluate(() => window.motionFutures!.player.state.length);
    const origin = Math.max(A.params.history_frames, B.params.history_frames);
    for (const frame of [origin, Math.floor((origin + length) / 2), length - 1]) {
      await figuresAt(page, frame);
      await settle(page);
      const shown = await page.evaluate(() => {
        const root = document.querySelector('motion-futures')!.shadowRoot!;
        const stage = root.querySelector('#viewer')!.getBoundingClientRect();
        return { stage: { left: stage.left, right: stage.right, top: stage.top, bottom: stage.bottom },
          labels: [...root.querySelectorAll<HTMLElement>('.figure-label-prediction')].filter((l) => l.style.display !== 'none')
            .map((l) => { const b = l.getBoundingClientRect(); return { text: l.textContent!, left: b.left, right: b.right, top: b.top, bottom: b.bottom }; }) };
      });
      expect(shown.labels, `frame ${frame}`).toHaveLength(10);
      for (const l of shown.labels) {
        const where = `frame ${frame}: ${l.text}`;
        expect(l.text.startsWith(`${shortLabel(A)} #`) || l.text.startsWith(`${shortLabel(B)} #`), where).toBe(true);
        expect(l.left, where).toBeGreaterThanOrEqual(shown.stage.left);
        expect(l.right, where).toBeLessThanOrEqual(shown.stage.right);
        expect(l.top, where).toBeGreaterThanOrEqual(shown.stage.top);
        expect(l.bottom, where).toBeLessThanOrEqual(shown.stage.bottom);
      }
    }
    expect(session.problems).toEqual(NO_PROBLEMS);
  });

  it('closest to truth marks one sample in each row; the exports and the read-out JSON hold every row, labelled, the truth once, plant_feet', async () => {
    await waiting(page);
    await page.goto(`${baseUrl}?compare=${COMPARE}&k=3&seed=4&layout=side&feet=own`);
    await predicted(page);
    await page.waitForSelector(`body[data-compare-models="${COMPARE}"]`, { state: 'attached' });
    const clip = defaultHistory().clip.name;
    // each row's closest sample, computed here from the rows' futures and the clip: the smallest mean
    // per-joint distance (world frame) over the truth's frames, a short sample holding its last pose
    const rows = await page.evaluate(() => {
      const app = window.motionFutures!;
      const m = app.onStage().motion!;
      const stride = m.joints * 3;
      return app.predictor.last!.compare!.map((r) => {
        const p = r.prediction!;
        const end = r.start + r.entry.params.history_frames;
        const T = Math.min(m.frames - end, Math.max(...p.lengths));
        const err = Array.from({ length: p.k }, (_, i) => {
          let sum = 0;
          for (let f = 0; f < T; f++) {
            const g = Math.min(f, p.lengths[i] - 1);
            for (let j = 0; j < m.joints; j++) {
              const a = (i * p.frames + g) * stride + j * 3;
              const b = (end + f) * stride + j * 3;
              sum += Math.hypot(p.futures[a] - m.positions[b], p.futures[a + 1] - m.positions[b + 1], p.futures[a + 2] - m.positions[b + 2]);
            }
          }
          return sum / (T * m.joints);
        });
        return { id: r.entry.id, start: r.start, n: r.entry.params.history_frames, k: p.k, closest: err.indexOf(Math.min(...err)), T,
          plantFeet: r.plantFeet, first: Array.from(p.futures.subarray(0, 6)), controls: r.controls };
      });
    });
    expect(rows.map((r) => r.id)).toEqual([A.id, B.id]);
    expect(rows.every((r) => r.T > 0)).toBe(true);
    expect(rows.map((r) => r.plantFeet)).toEqual([false, false]);
    await page.getByTestId('best-toggle').click();
    await settle(page);
    const origin = Math.max(A.params.history_frames, B.params.history_frames);
    const figures = (await figuresAt(page, origin + 15)).filter((f) => f.role === 'prediction');
    const best = figures.filter((f) => f.best);
    expect(best.map((f) => [f.group, f.sample])).toEqual(rows.map((r, g) => [g, r.closest]));
    for (const f of best) expect(f.label).toContain('closest to truth');
    expect(await page.locator('.figure-label-best').count()).toBe(2);   // side by side: one label per cell
    expect(await page.getByTestId('best-toggle').getAttribute('data-rows')).toBe(rows.map((r, g) => `${g}:${r.closest}`).join(','));
    const toggle = await page.getByTestId('best-toggle').textContent();
    expect(toggle).toContain(`${shortLabel(A)} #${rows[0].closest + 1}`);
    expect(toggle).toContain(`${shortLabel(B)} #${rows[1].closest + 1}`);
    await page.locator('[data-section="compare"]').scrollIntoViewIfNeeded();
    writeFileSync(`${SHOTS}/compare-closest.png`, await session.screenshot('compare-closest.png'));
    expect(await page.locator('[data-testid="compare-rows"] li').evaluateAll((li) => li.map((e) => (e as HTMLElement).dataset.plantFeet))).toEqual(['false', 'false']);

    // JSON: a clip per future, named after its model, then the ground truth once; each records its run
    expect(await page.locator('.export-what').textContent()).toContain(`the futures of ${shortLabel(A)} (3) and ${shortLabel(B)} (3) and the ground truth`);
    const [json] = await Promise.all([page.waitForEvent('download'), page.locator('#export-json').click()]);
    expect(json.suggestedFilename()).toBe(`${clip}.${A.id}+${B.id}.6-futures.json`);
    const docs = JSON.parse(readFileSync((await json.path())!, 'utf8')) as { name: string; source: Record<string, any>; positions: number[][][] }[];
    const names = [A, B].flatMap((e) => [1, 2, 3].map((i) => `${clip}.${e.id}_sample_${i}`));
    expect(docs.map((d) => d.name)).toEqual([...names, `${clip}.ground_truth`]);
    rows.forEach((r, g) => {
      const doc = docs[g * 3];
      expect(doc.source.run).toMatchObject({ model: r.id, history_start: r.start, history_frames: r.n, seed: 4, plant_feet: false, controls: r.controls });
      // its first future frame is the row's first predicted pose
      expect(doc.positions[origin][0].map((v) => Math.fround(v))).toEqual(r.first.slice(0, 3).map((v) => Math.fround(v)));
    });
    expect(docs.at(-1)!.source).not.toHaveProperty('run');
    // CSV: the same figures, the ground truth's rows once
    const [csv] = await Promise.all([page.waitForEvent('download'), page.locator('#export-csv').click()]);
    const lines = readFileSync((await csv.path())!, 'utf8').trimEnd().split('\n');
    expect(lines[0]).toBe('figure,frame,time,joint,x,y,z');
    const figureNames = [...new Set(lines.slice(1).map((l) => l.split(',')[0]))];
    expect(figureNames).toEqual(['history', ...names.map((n) => n.slice(clip.length + 1)), 'ground_truth']);
    const J = docs[0].positions[0].length;
    expect(lines.filter((l) => l.startsWith('ground_truth,'))).toHaveLength(Math.max(...rows.map((r) => r.T)) * J);
    // the read-out's JSON names the foot planting, its own and each compared row's
    await page.getByTestId('copy-numbers').click();
    await expect.poll(() => page.locator('.copy-status').textContent()).toBe('Copied.');
    const numbers = JSON.parse(await page.evaluate(() => navigator.clipboard.readText()));
    expect(numbers.plant_feet).toBe(false);
    expect(numbers.compared_with).toEqual([expect.objectContaining({ model: B.id, history_start: rows[1].start, plant_feet: false })]);
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
    // the same history end and seed for both models, each in its own place on stage, and the embed's
    // link to the full page keeps compare mode
    const shown = await page.evaluate(() => {
      const app = (document.getElementById('c') as HTMLElement & { app: NonNullable<typeof window.motionFutures> }).app;
      const last = app.predictor.last!;
      app.player.pause();
      app.player.seek(app.player.state.length - 1);
      return { seed: last.seed, rows: last.compare!.map((r) => ({ id: r.entry.id, end: r.start + r.entry.params.history_frames, k: r.prediction?.k })),
        figures: app.view.figures().filter((f) => f.role === 'prediction').map((f) => ({ group: f.group, x: (f.box.left + f.box.right) / 2, y: (f.box.top + f.box.bottom) / 2 })) };
    });
    expect(shown.seed).toBe(4);
    expect(shown.rows.map((r) => [r.id, r.k])).toEqual([[A.id, 2], [B.id, 2]]);
    expect(shown.rows[0].end).toBe(shown.rows[1].end);
    const centre = (g: number) => { const fs = shown.figures.filter((f) => f.group === g); return [fs.reduce((a, f) => a + f.x, 0) / fs.length, fs.reduce((a, f) => a + f.y, 0) / fs.length]; };
    expect(shown.figures.filter((f) => f.group === 0)).toHaveLength(2);
    expect(shown.figures.filter((f) => f.group === 1)).toHaveLength(2);
    expect(Math.hypot(centre(0)[0] - centre(1)[0], centre(0)[1] - centre(1)[1]), 'the two models apart on stage').toBeGreaterThan(30);
    const open = new URL((await page.locator('#c .mini-open').getAttribute('href'))!);
    expect(open.searchParams.get('compare')).toBe(COMPARE);
    expect(open.searchParams.get('seed')).toBe('4');
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
