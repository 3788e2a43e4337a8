// WAT (RNN) in a real Chromium: compose a 3-action sequence, predict K = 10 futures from a history of
// the test split, and read each sample's length, its segments' smoothness (flagged above the
// manifest's threshold) and the variance curves with delta and T_min marked; bad input is named.
// Then a walk -> jump -> kick run on stage (issue 29 items 3 and 4): each figure's label names its
// current action and says "stopped" once its sample stops, the scrubber marks every action change and
// stop (of the selected sample), the sample closest to the ground truth can be highlighted and the
// ground truth hidden, the camera presets turn the view, and every export carries the ground truth.
// Playback is paused and seeked to fixed frames (seed fixed) before anything drawn is compared.
import { readFileSync } from 'node:fs';
import { mkdir, writeFile } from 'node:fs/promises';
import { afterAll, beforeAll, describe, expect, inject, it } from 'vitest';
import type { Page } from 'playwright-core';
import type { SampleInfo } from '../../web/src/predictor/types';
import type { WatParams } from '../../web/src/predictor/wat';
import type { BrowserSession } from './browser';
import { defaultHistory, index } from './data';
import { compose, failed, NO_PROBLEMS, openPredictPage, predicted, servedModel, settle, stageShot, waiting } from './predict-page';

const baseUrl = inject('baseUrl');
const entry = servedModel('wat-rnn');
const params = entry.params as unknown as WatParams;
/** Walk, punch, jump when the model knows those actions, else its first three (the manifest's). */
const WANTED = ['walk', 'punch', 'jump'];
const SEQUENCE = WANTED.every((a) => params.actions.includes(a)) ? WANTED : params.actions.slice(0, 3);
const pretty = (a: string) => a.replace(/_/g, ' ');
/** Issue 29's run: walk -> jump -> kick (the model's first three actions if it lacks one). */
const RUN = ['walk', 'jump', 'kick'].every((a) => params.actions.includes(a)) ? ['walk', 'jump', 'kick'] : params.actions.slice(0, 3);
const RUN_K = 5;
const SHOTS = '/tmp/h29b';
const byFrame = <T extends { frame: number; sample: number }>(xs: T[]) => [...xs].sort((a, b) => a.frame - b.frame || a.sample - b.sample);


describe('WAT (RNN) in the browser', () => {
  let session: BrowserSession;
  let page: Page;

  beforeAll(async () => {
    session = await openPredictPage(baseUrl);
    page = session.page;
  });
  afterAll(async () => { await session?.close(); });

  it('asks for the action a newly picked clip shows, until the user composes a sequence', async () => {
    const chips = () => page.locator('.action-chip').allTextContents();
    const asChips = (seq: string[]) => seq.map((a, i) => `${i + 1}. ${pretty(a)}×`);
    const pick = async (name: string) => {
      await page.locator(`[data-clip="${name}"]`).click();
      await page.waitForSelector(`body[data-current-clip="${name}"][data-clip-status="ready"]`, { state: 'attached' });
    };
    const home = defaultHistory().clip;
    // a held-out clip of another action the model knows (a dance, a kick, ...)
    const other = index.clips.find((c) => c.role === 'test' && c.action !== home.action && params.actions.includes(c.action))!;
    expect(other, 'a test clip of a second known action').toBeTruthy();
    await page.locator('#model-select').selectOption('wat-rnn');
    expect(params.actions).toContain(home.action);
    expect(await chips()).toEqual(asChips([home.action]));
    await pick(other.name);
    expect(await chips()).toEqual(asChips([other.action]));
    // another model starts from its default sequence, which then follows the clip too
    const transformer = servedModel('wat-transformer');
    await page.locator('#model-select').selectOption(transformer.id);
    const knows = (transformer.params as unknown as WatParams).actions.includes(other.action);
    const fallback = (transformer.controls.find((c) => c.type === 'actions')?.default ?? []) as string[];
    expect(await chips()).toEqual(asChips(knows ? [other.action] : fallback));
    await page.locator('#model-select').selectOption('wat-rnn');
    // a composed sequence is the user's: a new clip leaves it
    const composed = [home.action, other.action];
    await compose(page, composed);
    await pick(home.name);
    expect(await chips()).toEqual(asChips(composed));
    expect(session.problems.pageErrors).toEqual([]);
  });

  it(`predicts K = 10 futures for ${SEQUENCE.join(' -> ')} from a test-split history`, async () => {
    await page.locator('#model-select').selectOption('wat-rnn');
    // the default history is on a test part
    expect(await page.locator('.history-note').textContent()).toMatch(/test part/);
    await page.locator('#control-k').fill('10');
    await compose(page, SEQUENCE);
    expect(await page.locator('.action-chip').allTextContents()).toEqual(SEQUENCE.map((a, i) => `${i + 1}. ${pretty(a)}×`));
    await waiting(page);
    await page.locator('#predict').click();
    await predicted(page);

    const d = await page.evaluate(() => ({ ...document.body.dataset }));
    expect(d.predictionModel).toBe('wat-rnn');
    expect(d.predictionK).toBe('10');
    const lengths = d.predictionLengths!.split(',').map(Number);
    expect(lengths).toHaveLength(10);
    const { min_frames: tMin, delta } = params.stop;
    const tMax = params.future_frames;
    expect(lengths.every((l) => l >= 3 * tMin && l <= 3 * tMax)).toBe(true);

    // what the worker returned: three segments per sample, in order, their lengths adding up
    const samples = await page.evaluate(() => window.motionFutures!.predictor.last!.prediction.samples);
    for (const [i, s] of samples.entries()) {
      expect(s.segments.map((g) => g.action)).toEqual(SEQUENCE);
      expect(s.segments.reduce((c, g) => c + g.length, 0)).toBe(lengths[i]);
      for (const g of s.segments) expect(g.flagged).toBe(g.smoothness! > params.smoothness.flag_threshold);
    }

    // the read-out: one row per sample, each with its three segments' length and smoothness
    expect(await page.locator('.sample-item').count()).toBe(10);
    const rows = await page.locator('.sample-item').first().locator('.segment-list li').allTextContents();
    expect(rows).toHaveLength(3);
    rows.forEach((r, j) => expect(r).toMatch(new RegExp(`^${pretty(SEQUENCE[j])} · [0-9.]+ s · smoothness [0-9.]+e[-+][0-9]+ m²`)));
    const flaggedRows = samples.reduce((c, s) => c + s.segments.filter((g) => g.flagged).length, 0);
    expect(await page.locator('.segment-flagged').count()).toBe(flaggedRows);

    // the variance plot: one curve per sample, delta and T_min marked
    const plot = page.locator('figure.curve svg.curve-plot');
    expect(await plot.locator('path').count()).toBe(10);
    expect(await plot.locator('.plot-label').allTextContents()).toEqual(expect.arrayContaining(['delta', 'T_min']));
    expect(await plot.locator('.plot-level').count()).toBe(1);
    expect(await plot.locator('.plot-mark').count()).toBeGreaterThanOrEqual(1);
    expect(await plot.locator('circle.plot-transition').count()).toBe(10 * (SEQUENCE.length - 1));   // each sample's 2 transitions
    expect(await page.locator('figure.curve figcaption').textContent()).toMatch(/Eq\. 8/);
    expect(delta).toBeGreaterThan(0);

    await stageShot(session, page, 'wat-rnn.png', 40, 0.008);
    // the read-out and the plot (below the fold of the page)
    await writeFile('/tmp/wat-rnn-futures.png', await session.screenshot('wat-rnn-futures.png', page.locator('[data-section="prediction"]')));
    expect(session.problems).toEqual(NO_PROBLEMS);
  });

  it('an empty action sequence is named, not predicted', async () => {
    await page.locator('.control-actions button', { hasText: 'Clear' }).click();
    await waiting(page);
    await page.locator('#predict').click();
    await failed(page);
    expect(await page.locator('.predict-status').textContent()).toMatch(/the action sequence is empty/);
    session.resetProblems();
  });

  it('K outside 1-50 is named, not predicted', async () => {
    await compose(page, [SEQUENCE[0]]);
    await page.locator('#control-k').fill('60');
    await waiting(page);
    await page.locator('#predict').click();
    await failed(page);
    expect(await page.locator('.predict-status').textContent()).toMatch(/K must be an integer from 1 to 50, got 60/);
    // and a valid K predicts again
    await page.locator('#control-k').fill('3');
    await waiting(page);
    await page.locator('#predict').click();
    await predicted(page);
    expect(await page.evaluate(() => document.body.dataset.predictionK)).toBe('3');
  });
  /** The stage of the prediction on it, at fixed frames: each label's action before and at every action
   *  change, "stopped" from the last frame of a sample whose last action stopped (and not a frame
   *  before), and the scrubber's marks without and with a selected sample. Returns the badges drawn
   *  and the stops inside sequences, so a caller can require some. */
  async function checkStage(): Promise<{ badges: number; innerStops: number; n: number; samples: SampleInfo[] }> {
    const { n, samples } = await page.evaluate(() => {
      const app = window.motionFutures!;
      app.player.pause();
      return { n: app.player.state.length - Math.max(...app.predictor.last!.prediction.lengths), samples: app.predictor.last!.prediction.samples };
    });
    expect(samples).toHaveLength(RUN_K);
    for (const s of samples) expect(s.segments.map((g) => g.action)).toEqual(RUN);
    /** Each sample's label (its text) and what the viewer says it draws, at timeline frame f. */
    const at = (f: number) => page.evaluate((frame) => {
      const app = window.motionFutures!;
      app.player.seek(frame);
      const root = document.querySelector('motion-futures')!.shadowRoot!;
      const labels = Object.fromEntries([...root.querySelectorAll<HTMLElement>('.figure-label[data-sample]')].map((l) => [l.dataset.sample, l.textContent]));
      return { labels, figures: app.view.figures().filter((x) => x.role === 'prediction' && !x.shared) };
    }, f);
    const lastStopped = (s: SampleInfo) => s.segments[s.segments.length - 1].stopped === true && !s.cut;
    for (const [i, s] of samples.entries()) {
      for (const [j, g] of s.segments.entries()) {
        if (j === 0) continue;
        const before = await at(n + g.start - 1);
        expect(before.labels[i], `#${i + 1} before ${g.action}`).toMatch(new RegExp(`^#${i + 1} · ${pretty(RUN[j - 1])}( ·|$)`));
        const after = await at(n + g.start);
        expect(after.labels[i], `#${i + 1} at ${g.action}`).toMatch(new RegExp(`^#${i + 1} · ${pretty(RUN[j])}( ·|$)`));
        expect(after.figures.find((x) => x.sample === i)!.action).toBe(RUN[j]);
      }
      const near = await at(n + s.length - 2);
      expect(near.labels[i], `#${i + 1} one frame before its end`).not.toMatch(/stopped/);
      const end = await at(n + s.length - 1);
      expect(end.labels[i], `#${i + 1} at its end`).toBe(`#${i + 1} · ${pretty(RUN[2])}${lastStopped(s) ? ' · stopped' : ''}`);
      expect(end.figures.find((x) => x.sample === i)!.stopped).toBe(lastStopped(s));
    }
    // the badges are drawn on stage (their labels placed), at the last frame every stopped sample has one
    await at(n + Math.max(...samples.map((s) => s.length)) - 1);
    await settle(page);
    const badges = await page.evaluate(() => [...document.querySelector('motion-futures')!.shadowRoot!.querySelectorAll<HTMLElement>('.figure-stopped')]
      .filter((b) => !b.hidden && b.closest<HTMLElement>('.figure-label')!.style.display !== 'none').length);
    expect(badges).toBe(samples.filter(lastStopped).length);

    // the scrubber: with no sample selected, every action change of every sample and each sample's stop or cut
    const marks = async () => byFrame(await page.getByTestId('scrubber-marks').locator('.scrubber-mark').evaluateAll((es) => es.map((e) => ({
      kind: [...e.classList].find((c) => c !== 'scrubber-mark')!.replace('scrubber-', ''), frame: Number(e.getAttribute('data-frame')),
      sample: Number(e.getAttribute('data-sample')), action: e.getAttribute('data-action'),
    }))));
    const ends = samples.flatMap((s, i) => (s.cut ? [{ kind: 'cut', frame: n + s.length - 1, sample: i, action: null }]
      : lastStopped(s) ? [{ kind: 'stop', frame: n + s.length - 1, sample: i, action: null }] : []));
    const changes = samples.flatMap((s, i) => s.segments.slice(1).map((g) => ({ kind: 'action', frame: n + g.start, sample: i, action: g.action! })));
    expect(changes).toHaveLength(RUN_K * (RUN.length - 1));
    expect(await marks()).toEqual(byFrame([...changes, ...ends]));
    // each sample selected in turn: its own action changes, every stop inside its sequence, and its end
    let innerStops = 0;
    for (const [i, s] of samples.entries()) {
      await page.locator(`.sample-button[data-sample="${i}"]`).click();
      const own = s.segments.slice(0, -1).flatMap((g) => (g.stopped ? [{ kind: 'stop', frame: n + g.start + g.length - 1, sample: i, action: null }] : []));
      innerStops += own.length;
      expect(await marks(), `#${i + 1} selected`).toEqual(byFrame([...changes.filter((m) => m.sample === i), ...own, ...ends.filter((m) => m.sample === i)]));
      expect(await page.getByTestId('scrubber-marks').getAttribute('data-sample')).toBe(String(i));
      await page.locator(`.sample-button[data-sample="${i}"]`).click();
    }
    expect(await marks()).toEqual(byFrame([...changes, ...ends]));
    return { badges, innerStops, n, samples };
  }

  it(`${RUN.join(' -> ')}: each figure names its current action and says "stopped"; the scrubber marks every change and stop`, async () => {
    await compose(page, RUN);
    await page.locator('#control-k').fill(String(RUN_K));
    await waiting(page);
    await page.locator('#predict').click();
    await predicted(page);
    const { n, samples } = await checkStage();
    // a screenshot mid-transition: two frames into sample #1's jump
    await mkdir(SHOTS, { recursive: true });
    await page.evaluate((f) => window.motionFutures!.player.seek(f), n + samples[0].segments[1].start + 2);
    await settle(page);
    await writeFile(`${SHOTS}/wat-3-actions-transition.png`, await session.screenshot('wat-3-actions-transition.png'));

    // The served model may run every action to T_max on this history (no stop at all): a replay of the
    // same futures in which #2 stops in walk (at its T_max frame) and in kick, 20 frames early, shows
    // the badge and the stop marks in any case.
    await page.evaluate(() => {
      const app = window.motionFutures!;
      const p = app.predictor.last!.prediction;
      const early = 20;
      const samples = p.samples.map((s, i) => (i !== 1 ? s : {
        ...s, length: s.length - early, stopped: true,
        segments: s.segments.map((g, j) => (j === 0 ? { ...g, stopped: true } : j === s.segments.length - 1 ? { ...g, length: g.length - early, stopped: true } : g)),
      }));
      return app.predictor.present({ ...p, samples, lengths: Int32Array.from(samples, (s) => s.length) });
    });
    const replay = await checkStage();
    expect(replay.badges).toBeGreaterThanOrEqual(1);
    expect(replay.innerStops).toBeGreaterThanOrEqual(1);
    await page.evaluate((f) => window.motionFutures!.player.seek(f), replay.n + replay.samples[1].length - 1);
    await settle(page);
    await writeFile(`${SHOTS}/wat-3-actions-stopped.png`, await session.screenshot('wat-3-actions-stopped.png'));
    // back to the model's own futures
    await waiting(page);
    await page.locator('#predict').click();
    await predicted(page);
    expect(session.problems).toEqual(NO_PROBLEMS);
  });

  it('highlights the sample closest to the ground truth, and hides and shows the ground truth', async () => {
    // the expected best: mean per-joint distance to the clip's own next frames, computed here from the prediction
    const want = await page.evaluate(() => {
      const app = window.motionFutures!;
      const last = app.predictor.last!;
      const p = last.prediction;
      const m = app.onStage().motion!;
      const n = app.player.state.length - Math.max(...p.lengths);
      const J = p.joints;
      const T = Math.min(m.frames - last.start - n, Math.max(...p.lengths));
      const cm = Array.from({ length: p.k }, (_, s) => {
        let sum = 0;
        for (let t = 0; t < T; t++) {
          for (let j = 0; j < J; j++) {
            const a = ((s * p.frames + Math.min(t, p.frames - 1)) * J + j) * 3;
            const b = ((last.start + n + t) * J + j) * 3;
            sum += Math.hypot(p.futures[a] - m.positions[b], p.futures[a + 1] - m.positions[b + 1], p.futures[a + 2] - m.positions[b + 2]);
          }
        }
        return (100 * sum) / (T * J);
      });
      return { sample: cm.indexOf(Math.min(...cm)), cm: Math.min(...cm), T };
    });
    expect(want.T).toBeGreaterThan(0);
    const frame = await page.evaluate(() => { const pl = window.motionFutures!.player; pl.pause(); pl.seek(Math.floor(pl.state.length / 3)); return pl.state.frame; });
    const drawn = () => page.evaluate(() => window.motionFutures!.view.figures());
    const before = await drawn();
    const toggle = page.getByTestId('best-toggle');
    expect(await toggle.isDisabled()).toBe(false);
    await toggle.click();
    expect(await toggle.getAttribute('aria-pressed')).toBe('true');
    expect(await toggle.getAttribute('data-sample')).toBe(String(want.sample));
    expect(await toggle.textContent()).toBe(`Closest to truth: #${want.sample + 1} · ${want.cm.toFixed(1)} cm`);
    expect(await toggle.getAttribute('title')).toMatch(new RegExp(`over the ${want.T} frames of ground truth`));
    const after = await drawn();
    const predictions = (fs: typeof after) => fs.filter((f) => f.role === 'prediction' && !f.shared);
    expect(predictions(after).filter((f) => f.best).map((f) => f.sample)).toEqual([want.sample]);
    // the best keeps its colour, every other sample steps back (its drawn colour changes)
    for (const f of predictions(after)) {
      const was = predictions(before).find((g) => g.sample === f.sample)!;
      if (f.sample === want.sample) expect(f.colour, `#${f.sample! + 1}`).toBe(was.colour);
      else expect(f.colour, `#${f.sample! + 1}`).not.toBe(was.colour);
    }
    const bestLabel = page.locator('.figure-label-best');
    expect(await bestLabel.count()).toBe(1);
    expect(await bestLabel.getAttribute('data-sample')).toBe(String(want.sample));
    expect(await bestLabel.textContent()).toMatch(/ · closest to truth$/);
    await settle(page);
    await writeFile(`${SHOTS}/best-highlight.png`, await session.screenshot('best-highlight.png'));
    await toggle.click();
    expect(await page.locator('.figure-label-best').count()).toBe(0);
    expect((await drawn()).map((f) => f.colour)).toEqual(before.map((f) => f.colour));

    // the ground truth: drawn, then hidden (figure and label), then back
    const truthToggle = page.getByTestId('truth-toggle');
    const truthFigures = async () => (await drawn()).filter((f) => f.role === 'truth').length;
    const truthLabels = () => page.evaluate(() => [...document.querySelector('motion-futures')!.shadowRoot!.querySelectorAll<HTMLElement>('.figure-label[data-role="truth"]')]
      .filter((l) => l.style.display !== 'none').length);
    await settle(page);
    expect(await truthFigures()).toBe(1);
    expect(await truthLabels()).toBe(1);
    await truthToggle.click();
    await settle(page);
    expect(await truthToggle.getAttribute('aria-pressed')).toBe('false');
    expect(await truthFigures()).toBe(0);
    expect(await truthLabels()).toBe(0);
    expect((await drawn()).filter((f) => f.role === 'prediction').length).toBe(RUN_K);
    await truthToggle.click();
    await settle(page);
    expect(await truthFigures()).toBe(1);
    expect(await page.evaluate(() => window.motionFutures!.player.state.frame)).toBe(frame);
    expect(session.problems).toEqual(NO_PROBLEMS);
  });

  it('camera presets: front and side at right angles, top from above, follow frames one figure larger', async () => {
    const n = await page.evaluate(() => { const app = window.motionFutures!; app.player.pause(); return app.player.state.length - Math.max(...app.predictor.last!.prediction.lengths); });
    await page.evaluate((f) => window.motionFutures!.player.seek(f), n + 5);
    const view = async (preset: string) => {
      await page.getByTestId('camera-preset').selectOption(preset);
      await settle(page);
      await writeFile(`${SHOTS}/camera-${preset}.png`, await session.screenshot(`camera-${preset}.png`, page.locator('#viewer')));
      return page.evaluate(() => {
        const app = window.motionFutures!;
        const canvas = document.querySelector('motion-futures')!.shadowRoot!.querySelector('canvas')!;
        return { direction: app.view.viewDirection()!, camera: app.view.camera, figures: app.view.figures(), width: canvas.clientWidth, height: canvas.clientHeight };
      });
    };
    // where the history walks: the figures face that way
    const travel = await page.evaluate(() => {
      const app = window.motionFutures!;
      const m = app.onStage().motion!;
      const start = app.predictor.last!.start;
      const n = app.player.state.length - Math.max(...app.predictor.last!.prediction.lengths);
      const J = m.joints;
      const a = start * J * 3;
      const b = (start + n - 1) * J * 3;
      const d = [m.positions[b] - m.positions[a], m.positions[b + 2] - m.positions[a + 2]];
      const l = Math.hypot(d[0], d[1]);
      return [d[0] / l, d[1] / l];
    });
    const auto = await view('auto');
    const front = await view('front');
    const side = await view('side');
    const top = await view('top');
    const follow = await view('follow');
    expect(front.camera).toBe('front');
    const flat = (d: number[]) => { const l = Math.hypot(d[0], d[2]); return [d[0] / l, d[2] / l]; };
    expect(Math.abs(front.direction[1])).toBeLessThan(0.35);
    expect(Math.abs(side.direction[1])).toBeLessThan(0.35);
    expect(top.direction[1]).toBeGreaterThan(0.99);
    const dot = (a: number[], b: number[]) => a[0] * b[0] + a[1] * b[1];
    expect(Math.abs(dot(flat(front.direction), flat(side.direction)))).toBeLessThan(0.05);
    expect(dot(flat(front.direction), travel), 'front: the camera stands where the history walks to').toBeGreaterThan(0.7);
    // from above, a standing figure is short on screen; following one, it is larger than when all are framed
    const height = (s: typeof auto, sample: number) => { const f = s.figures.find((x) => x.role === 'prediction' && x.sample === sample && !x.shared)!; return f.box.bottom - f.box.top; };
    expect(height(top, 0)).toBeLessThan(0.6 * height(front, 0));
    expect(height(follow, 0)).toBeGreaterThan(1.5 * height(auto, 0));
    const f0 = follow.figures.find((x) => x.role === 'prediction' && x.sample === 0 && !x.shared)!;
    expect(f0.box.left).toBeGreaterThanOrEqual(0);
    expect(f0.box.right).toBeLessThanOrEqual(follow.width);
    // following the selected sample
    await page.locator('.sample-button[data-sample="3"]').click();
    await settle(page);
    const chased = await page.evaluate(() => window.motionFutures!.view.figures().find((x) => x.role === 'prediction' && x.sample === 3 && !x.shared)!);
    expect(chased.box.bottom - chased.box.top).toBeGreaterThan(1.5 * height(auto, 3));
    await page.locator('.sample-button[data-sample="3"]').click();
    await page.getByTestId('camera-preset').selectOption('auto');
    expect(session.problems).toEqual(NO_PROBLEMS);
  });

  it('every export carries the ground truth as its own figure', async () => {
    const { clip, truthFrames, joints, first } = await page.evaluate(() => {
      const app = window.motionFutures!;
      const last = app.predictor.last!;
      const m = app.onStage().motion!;
      const n = app.player.state.length - Math.max(...last.prediction.lengths);
      const T = Math.min(m.frames - last.start - n, Math.max(...last.prediction.lengths));
      const at = (last.start + n) * m.joints * 3;
      return { clip: m.name, truthFrames: T, joints: m.joints, first: Array.from(m.positions.slice(at, at + 3)) };
    });
    const save = async (format: string) => {
      const [download] = await Promise.all([page.waitForEvent('download'), page.locator(`#export-${format}`).click()]);
      return readFileSync((await download.path())!);
    };
    const csv = (await save('csv')).toString('utf8').trimEnd().split('\n');
    const truthRows = csv.filter((r) => r.startsWith('ground_truth,'));
    expect(truthRows).toHaveLength(truthFrames * joints);
    const [, frame, , , x, y, z] = truthRows[0].split(',');
    expect(Number(frame)).toBe(entry.params.history_frames);
    [x, y, z].forEach((v, c) => expect(Math.abs(Number(v) - first[c])).toBeLessThan(1e-6));
    const docs = JSON.parse((await save('json')).toString('utf8')) as { name: string; action: string; positions: number[][][] }[];
    expect(docs.map((d) => d.name)).toEqual([...Array.from({ length: RUN_K }, (_, i) => `${clip}.sample_${i + 1}`), `${clip}.ground_truth`]);
    expect(docs[RUN_K].action).toBe('ground truth');
    expect(docs[RUN_K].positions).toHaveLength(entry.params.history_frames + truthFrames);
    const glb = await save('glb');
    const gltf = JSON.parse(glb.subarray(20, 20 + glb.readUInt32LE(12)).toString('utf8')) as { nodes: { name: string }[] };
    const names = gltf.nodes.map((nd) => nd.name);
    expect(names).toContain('ground_truth');
    expect(names).toContain('ground_truth_left_toe');
    expect(await page.locator('.export-what').textContent()).toMatch(/and the ground truth/);
    expect(session.problems).toEqual(NO_PROBLEMS);
  });
});
