// The browser half of `make bench`: build the site into runs/bench/dist, serve it with
// `vite preview` (stopped by PID), and drive Chromium (tests/e2e/browser.ts: Debian's binary, a
// fresh profile) through the plan export/bench writes: the bench page (web/bench.html) for
// session loads, end-to-end cases and single graphs; the main page for navigation -> first frame
// with futures drawn (the first view, and each model by link), frame gaps during a K=50 prediction
// and the frame rate with K=50 futures playing. MF_BENCH_ONLY=page runs the main page's part alone
// (a quick look while working on start-up; export/bench needs the whole run for its report), and
// MF_BENCH_TREE=DIR builds another source tree instead (an earlier commit: a before/after).
import { readFileSync, writeFileSync } from 'node:fs';
import { resolve } from 'node:path';
import type { Page } from 'playwright-core';
import { openBrowser, type BrowserSession } from '../tests/e2e/browser';
import { ROOT } from '../tests/e2e/server';
import { buildSite, buildTree, startPreview, type PreviewServer as Served } from '../tests/e2e/server';
import type { BenchCase } from '../web/src/bench/main';
import { OPTIMIZATION_LEVELS, SESSION_OPTIMIZATION } from '../web/src/predictor/ort-runner';

interface Plan {
  runs: number;
  warmup: number;
  dist: string;
  cases: (BenchCase & { id: string; k: number })[];
  models: { id: string; files: string[]; k50: boolean }[];
  graphs: { id: string; file: string; feeds: Record<string, { dims: number[]; base64: string }>; variants: { name: string; file: string }[] }[];
}

const LOAD_REPEATS = 2; // plus the load cases() makes on its own fresh page
// A freshly launched Chromium builds its own WebUI (a chrome://omnibox-popup renderer: about 1 s of
// CPU, seen in a trace of the navigation) in its first seconds; on 2 cores that ran alongside the
// page being timed. A user opens a link in a browser that is already running: the timed navigation
// starts once about:blank has been open this long (the profile stays fresh: nothing cached).
const SETTLE_MS = 2000;
const NAV_REPEATS = Number(process.env.MF_BENCH_NAV_REPEATS ?? 5); // fewer for a quick look
const FPS_SECONDS = 3;
const WARM_WORKER_MS = 2000;
const WARM_GRAPH_MS = 300;
// A fresh graph worker starts in V8's baseline code and tiers hot functions up in the background:
// wat-rnn/decoder/b10 ran 7.6 ms after 300 ms of warm-up and 5.4-5.8 ms after 1 s.
const WARM_FRESH_MS = 1000;
// Session optimisation levels tried on the served graph besides the site's own.
const LEVELS = OPTIMIZATION_LEVELS.filter((l) => l !== SESSION_OPTIMIZATION);

const started = Date.now();
const log = (text: string) => console.log(`bench: ${((Date.now() - started) / 1000).toFixed(0).padStart(4)} s  ${text}`);

async function benchPage(b: BrowserSession, s: Served): Promise<Page> {
  const { page } = b;
  await page.goto(`${s.url}bench.html`);
  await page.evaluate(() => window.mfBench!.ready);
  return page;
}

type Loads = Record<string, { round_trip_ms: number[]; worker_ms: number[] }>;

async function loads(b: BrowserSession, s: Served, plan: Plan): Promise<Loads> {
  const out: Loads = {};
  for (const m of plan.models) {
    out[m.id] = { round_trip_ms: [], worker_ms: [] };
    for (let i = 0; i < LOAD_REPEATS; i++) {
      const page = await benchPage(b, s); // a fresh page: a fresh worker without sessions
      const r = await page.evaluate((id) => window.mfBench!.load(id), m.id);
      out[m.id].round_trip_ms.push(r.roundTripMs);
      out[m.id].worker_ms.push(r.workerMs);
    }
  }
  return out;
}

async function cases(b: BrowserSession, s: Served, plan: Plan, loaded: Loads) {
  const out = [];
  for (const m of plan.models) {
    const own = plan.cases.filter((x) => x.model === m.id);
    if (!own.length) continue;
    const page = await benchPage(b, s);
    const first = await page.evaluate((id) => window.mfBench!.load(id), m.id);
    loaded[m.id] ??= { round_trip_ms: [], worker_ms: [] };
    loaded[m.id].round_trip_ms.push(first.roundTripMs);
    loaded[m.id].worker_ms.push(first.workerMs);
    // warm the fresh worker (see graphs()): predictions for WARM_WORKER_MS before any case is timed
    const warm = { model: own[0].model, clip: own[0].clip, start: own[0].start, request: own[0].request };
    for (const t0 = Date.now(); Date.now() - t0 < WARM_WORKER_MS;) await page.evaluate((c) => window.mfBench!.run(c, 0, 3), warm);
    for (const c of own) {
      log(`case ${c.id}`);
      const r = await page.evaluate((a) => window.mfBench!.run(a.c, a.warmup, a.runs),
        { c: { model: c.model, clip: c.clip, start: c.start, request: c.request }, warmup: plan.warmup, runs: plan.runs });
      out.push({ id: c.id, worker_ms: r.workerMs, round_trip_ms: r.roundTripMs, timings: r.timings, wasm_bytes: r.wasmBytes,
        lengths: r.lengths, frames: r.frames });
    }
  }
  return out;
}

async function graphs(b: BrowserSession, s: Served, plan: Plan) {
  const page = await benchPage(b, s);
  const out = [];
  const profiles = [];
  const time = (file: string, feeds: Plan['graphs'][number]['feeds'], extra: Record<string, unknown>) =>
    page.evaluate((spec) => window.mfBench!.graph(spec as Parameters<NonNullable<Window['mfBench']>['graph']>[0]),
      { base64: readFileSync(file).toString('base64'), feeds, warmup: plan.warmup, warmupMs: WARM_GRAPH_MS, runs: plan.runs, ...extra });
  // Pass 1, the order effect: every graph in one worker, one after another, as on a page where the
  // user has switched models. V8 optimises onnxruntime's wasm with call feedback (speculative
  // call_indirect inlining) from whatever ran first, so a graph's time here depends on the graphs
  // before it: keyposes/step/b50 measured 0.60-0.65 ms after regression-gru against 0.26-0.28 ms
  // alone, and Chromium's --js-flags=--no-wasm-inlining-call-indirect removed the difference.
  const shared: Record<string, number[] | undefined> = {};
  if (plan.graphs.length) await time(plan.graphs[0].file, plan.graphs[0].feeds, { warmupMs: WARM_WORKER_MS });
  for (const g of plan.graphs) {
    log(`graph ${g.id} (shared worker)`);
    shared[g.id] = (await time(g.file, g.feeds, {})).runMs;
  }
  // Pass 2, the per-graph times the targets use: each graph alone in a fresh worker, so no other
  // graph has shaped V8's code, as that worker's second session. Chromium (not Node) ran the first
  // session created in a new worker 1.25-1.7x slower for its whole life (keyposes/refine/b10 5.8 ms,
  // 3.5 ms as a later session), and the site's worker creates several sessions per model (its case
  // timings: refine/b10 3.75 ms), so a 2-node opener session takes the first place.
  const opener = plan.graphs[0];
  const alone = async (file: string, feeds: Plan['graphs'][number]['feeds'], extra: Record<string, unknown>) => {
    await time(opener.file, opener.feeds, { fresh: true, warmup: 1, warmupMs: 0, runs: 1 });
    return time(file, feeds, { warmupMs: WARM_FRESH_MS, ...extra });
  };
  for (const g of plan.graphs) {
    log(`graph ${g.id}`);
    const r = await alone(g.file, g.feeds, {});
    const variants = [];
    if (g.variants.length) {
      const p = await time(g.file, g.feeds, { profile: true, warmup: 0, warmupMs: 0, runs: 3 });
      if (p.profile) profiles.push({ graph: g.id, events: p.profile, runs: 3 });
      for (const level of LEVELS) {
        const v = await alone(g.file, g.feeds, { optimization: level });
        variants.push({ name: `served graph, session optimisation '${level}'`, ms: v.runMs, load_ms: v.loadMs, error: v.error });
      }
      for (const vf of g.variants) {
        const v = await alone(vf.file, g.feeds, {});
        variants.push({ name: vf.name, ms: v.runMs, load_ms: v.loadMs, error: v.error });
      }
    }
    out.push({ id: g.id, ms: r.runMs, shared_ms: shared[g.id], reps: r.reps, load_ms: r.loadMs, error: r.error, variants });
  }
  return { graphs: out, profiles };
}

/** Records when body[data-predict-status] first says 'done' (ms since navigation start). */
function watchDone(): void {
  const w = window as unknown as { __mfDone?: number };
  new MutationObserver(() => {
    if (w.__mfDone === undefined && document.body?.dataset.predictStatus === 'done') w.__mfDone = performance.now();
  }).observe(document, { attributes: true, subtree: true, attributeFilter: ['data-predict-status'] });
}

/** What a request is, on the way to the first prediction (null: not tracked). */
function stage(url: string): string | null {
  const path = new URL(url).pathname;
  if (path.endsWith('.wasm')) return 'wasm fetched';
  if (path.endsWith('.onnx')) return 'last ONNX fetched';
  if (path.endsWith('/manifest.json')) return 'manifest fetched';
  if (/\/clips\/.+\.json$/.test(path)) return 'last clip file fetched';
  if (path.endsWith('.js') && path.includes('/assets/')) return 'last script fetched';
  return null;
}

async function navigation(s: Served, plan: Plan) {
  const out = [];
  // the first view (no query: the stage's model at its first-view K), then each model by link
  const targets = [{ id: 'first view', query: '', files: null as string[] | null },
    ...plan.models.map((m) => ({ id: m.id, query: `?model=${encodeURIComponent(m.id)}`, files: m.files as string[] | null }))];
  for (const m of targets) {
    const first: number[] = [];
    const drawn: number[] = [];
    let shownModel: string | undefined;
    const requests = { page: new Set<string>(), service_worker: new Set<string>() };
    const timeline: Record<string, number[]> = {};
    let error: string | undefined;
    for (let i = 0; i < NAV_REPEATS; i++) {
      const b = await openBrowser(); // a fresh profile: nothing cached, no service worker yet
      try {
        b.context.on('request', (r) => {
          if (!r.url().endsWith('.onnx')) return;
          (r.serviceWorker() ? requests.service_worker : requests.page).add(r.url());
        });
        // When each kind of file finished loading (page and worker; epoch ms from the request's timing).
        const loaded: { kind: string; end: number }[] = [];
        b.context.on('requestfinished', (r) => {
          const kind = stage(r.url());
          const t = r.timing();
          if (kind && !r.serviceWorker() && t.responseEnd >= 0) loaded.push({ kind, end: t.startTime + t.responseEnd });
        });
        await b.page.goto('about:blank');
        await b.page.waitForTimeout(SETTLE_MS);
        await b.page.addInitScript(watchDone);
        await b.page.goto(`${s.url}${m.query}`);
        await b.page.waitForFunction(() => (window as unknown as { __mfDone?: number }).__mfDone !== undefined, null, { timeout: 60_000 });
        const done = await b.page.evaluate(() => (window as unknown as { __mfDone: number }).__mfDone);
        first.push(done);
        const [origin, dcl, marks, model] = await b.page.evaluate(() => [performance.timeOrigin,
          (performance.getEntriesByType('navigation')[0] as PerformanceNavigationTiming).domContentLoadedEventEnd,
          performance.getEntriesByType('mark').filter((e) => e.name.startsWith('mf:')).map((e) => [e.name.slice(3), e.startTime] as const),
          document.body.dataset.predictionModel] as const);
        shownModel = model;
        // each mark's first time (a later prediction marks again)
        const firstMarks: Record<string, number> = {};
        for (const [name, t] of marks) firstMarks[name] ??= t;
        if (firstMarks['futures-drawn'] === undefined) throw new Error('the page never marked mf:futures-drawn');
        drawn.push(firstMarks['futures-drawn']);
        const finished: Record<string, number> = { DOMContentLoaded: dcl, ...firstMarks };
        for (const { kind, end } of loaded) {
          if (end - origin <= done) finished[kind] = Math.max(finished[kind] ?? 0, end - origin);
        }
        for (const [kind, ms] of Object.entries(finished)) (timeline[kind] ??= []).push(ms);
      } catch (err) {
        error = (err as Error).message.split('\n')[0];
      } finally {
        await b.close();
      }
    }
    log(`navigation ${m.id}: futures drawn ${drawn.map((x) => x.toFixed(0)).join(', ')} ms; done ${first.map((x) => x.toFixed(0)).join(', ')} ms`);
    const files = m.files ?? plan.models.find((x) => x.id === shownModel)?.files ?? [];
    out.push({ model: m.id, shown_model: shownModel, own_files: files, first_prediction_ms: first, futures_drawn_ms: drawn,
      timeline_ms: timeline, error,
      onnx_requests: { page: [...requests.page], service_worker: [...requests.service_worker] } });
  }
  return out;
}

/** rAF intervals on the main page while the next prediction runs: from pressing Predict until the
 * result is shown and drawn (two frames more). `idleMs` of intervals first, as the baseline. */
async function gapsDuringPrediction(page: Page, idleMs: number): Promise<{ idle: number[]; gaps: number[]; ms: number }> {
  await page.evaluate((idle) => new Promise<void>((ready) => {
    const w = window as unknown as { __mfGaps: number[]; __mfIdle: number[]; __mfRecording: boolean; __mfT0?: number; __mfShownMs?: number };
    w.__mfGaps = [];
    w.__mfIdle = [];
    w.__mfRecording = true;
    w.__mfT0 = undefined;
    let last = performance.now();
    const tick = (t: number) => {
      (w.__mfT0 === undefined ? w.__mfIdle : w.__mfGaps).push(t - last);
      last = t;
      if (w.__mfRecording) requestAnimationFrame(tick);
    };
    requestAnimationFrame(tick);
    document.body.dataset.predictStatus = 'waiting';
    new MutationObserver((_, obs) => {
      if (document.body.dataset.predictStatus !== 'done') return;
      obs.disconnect();
      w.__mfShownMs = performance.now() - w.__mfT0!;
      requestAnimationFrame(() => requestAnimationFrame(() => { w.__mfRecording = false; }));
    }).observe(document.body, { attributes: true, attributeFilter: ['data-predict-status'] });
    setTimeout(() => { w.__mfT0 = performance.now(); ready(); }, idle);
  }), idleMs);
  await page.locator('#predict').click();
  await page.waitForFunction(() => (window as unknown as { __mfRecording: boolean }).__mfRecording === false, null, { timeout: 90_000 });
  return page.evaluate(() => {
    const w = window as unknown as { __mfGaps: number[]; __mfIdle: number[]; __mfShownMs: number };
    return { idle: w.__mfIdle.slice(1), gaps: w.__mfGaps, ms: w.__mfShownMs }; // the first idle interval starts mid-frame
  });
}

async function frames(s: Served, plan: Plan) {
  const out = [];
  for (const m of plan.models.filter((x) => x.k50)) {
    const b = await openBrowser();
    try {
      const { page } = b;
      await page.goto(`${s.url}?model=${encodeURIComponent(m.id)}&k=50`);
      await page.waitForSelector('body[data-predict-status="done"]', { state: 'attached', timeout: 90_000 });
      const k = Number(await page.evaluate(() => document.body.dataset.predictionK));
      const renderer = await page.getAttribute('[data-renderer]', 'data-renderer');
      // 1. the stage still (playback paused): what the prediction itself costs the main thread
      await page.evaluate(() => window.motionFutures!.player.pause());
      const still = await gapsDuringPrediction(page, 1000);
      // 2. the frame rate with the K=50 futures playing (show() starts playback)
      const fps = await page.evaluate((seconds) => new Promise<number>((done) => {
        let n = 0;
        const t0 = performance.now();
        const tick = () => {
          n++;
          if (performance.now() - t0 < seconds * 1000) requestAnimationFrame(tick);
          else done(n / ((performance.now() - t0) / 1000));
        };
        requestAnimationFrame(tick);
      }), FPS_SECONDS);
      const playing = await page.evaluate(() => window.motionFutures!.player.state.playing);
      // 3. another prediction while the K=50 futures play
      const moving = await gapsDuringPrediction(page, 1000);
      const max = (xs: number[]) => (xs.length ? Math.max(...xs) : null);
      log(`frames ${m.id} K=${k}: longest gap ${max(still.gaps)?.toFixed(0)} ms still, ${max(moving.gaps)?.toFixed(0)} ms playing; ${fps.toFixed(1)} fps`);
      out.push({ model: m.id, k, renderer, max_gap_ms: max(still.gaps), idle_max_gap_ms: max(still.idle), gaps_ms: still.gaps,
        prediction_ms: still.ms, fps, playing, playing_max_gap_ms: max(moving.gaps), playing_idle_max_gap_ms: max(moving.idle),
        playing_prediction_ms: moving.ms, playing_gaps_ms: moving.gaps });
    } catch (err) {
      out.push({ model: m.id, k: 50, error: (err as Error).message.split('\n')[0] });
    } finally {
      await b.close();
    }
  }
  return out;
}

class PageOnly extends Error {}

export async function main(planPath: string, outPath: string): Promise<void> {
  const plan: Plan = JSON.parse(readFileSync(planPath, 'utf8'));
  const tree = process.env.MF_BENCH_TREE;
  log(`vite build${tree ? ` of ${tree}` : ''} into ${plan.dist}`);
  const t0 = performance.now();
  if (tree) await buildTree(tree, plan.dist);
  else await buildSite(300_000, plan.dist);
  const buildMs = performance.now() - t0;
  const s = await startPreview({ outDir: plan.dist });
  const notes: string[] = [];
  try {
    const b = await openBrowser();
    let doc: Record<string, unknown>;
    try {
      if (process.env.MF_BENCH_ONLY === 'page') throw new PageOnly();
      const chromium = await b.page.evaluate(() => navigator.userAgent.match(/Chrome\/[\d.]+/)?.[0] ?? navigator.userAgent);
      log('session loads');
      const load = await loads(b, s, plan);
      const c = await cases(b, s, plan, load);
      const g = await graphs(b, s, plan);
      doc = { chromium, load, cases: c, graphs: g.graphs, profiles: g.profiles };
    } catch (err) {
      if (!(err instanceof PageOnly)) throw err;
      doc = { chromium: null, load: {}, cases: [], graphs: [], profiles: [], page_only: true };
    } finally {
      await b.close();
    }
    const nav = await navigation(s, plan);
    const fr = await frames(s, plan);
    // 'software' or 'gpu': what the stage found (it draws without multisampling on a software renderer)
    const renderer = fr.find((f) => f.renderer)?.renderer ?? null;
    const ortWeb = JSON.parse(readFileSync(resolve(ROOT, 'node_modules/onnxruntime-web/package.json'), 'utf8')).version;
    writeFileSync(outPath, JSON.stringify({ ...doc, session_optimization: SESSION_OPTIMIZATION, renderer, node: process.version, onnxruntime_web: ortWeb, build_ms: buildMs,
      navigation: nav, frames: fr, fps_seconds: FPS_SECONDS, notes }));
  } finally {
    await s.stop();
  }
}
