// The content-security policy (web/build/csp.ts): every built page works under it, sent both as the
// preview's header and as the page's <meta>, with no violation; a host page keeps the widget working
// with only what the README's Embedding section lists; and what comes from another origin (a script,
// an inline script, a fetch from the page or the predictor worker) is blocked and reported.
import { createServer, type Server } from 'node:http';
import { spawn } from 'node:child_process';
import { readdirSync } from 'node:fs';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, inject, it } from 'vitest';
import type { Page } from 'playwright-core';
import { CONTENT_SECURITY_POLICY } from '../../web/build/csp';
import { openBrowser, type BrowserSession } from './browser';
import { defaultHistory, manifest } from './data';
import { freePort, ROOT } from './server';

const baseUrl = inject('baseUrl');
const origin = new URL(baseUrl).origin;
const NO_PROBLEMS = { consoleErrors: [], pageErrors: [], failedRequests: [] };
const DIST = join(ROOT, 'dist');

/** A model the benchmark page can run with K and a seed alone (no action sequence). */
const BENCH_MODEL = manifest.models.find((m) => !m.controls.some((c) => c.type === 'actions')) ?? manifest.models[0];
const done = (selector: string) => (page: Page) => page.waitForSelector(selector, { state: 'attached', timeout: 120_000 });
/** How each page says it has done its work; a page not listed here (a new one) must at least load quietly. */
const READY: Record<string, (page: Page) => Promise<unknown>> = {
  'index.html': done('body[data-predict-status="done"]'),
  'embed.html': done('motion-futures[data-predict-status="done"]'),
  'explainer.html': done('body[data-status="ready"]'),
  'model-card.html': done('body[data-status="ready"]'),
  'results.html': done('body[data-status="ready"]'),
  'bring-your-own.html': done('body[data-guide-status="done"]'),
  // the benchmark page starts its predictor worker; one prediction shows its wasm runs under the policy
  'bench.html': (page) => page.evaluate(async (c) => {
    await window.mfBench!.ready;
    return window.mfBench!.run(c, 0, 1);
  }, { model: BENCH_MODEL.id, clip: defaultHistory().clip.name, start: defaultHistory().start, request: { k: 1, seed: 1 } }),
};
const PAGES = readdirSync(DIST).filter((f) => f.endsWith('.html')).sort();

/** Every violation on every page of the context, recorded before the page's own scripts run. */
async function recordViolations(session: BrowserSession): Promise<void> {
  await session.context.addInitScript(() => {
    const seen: string[] = [];
    (window as unknown as { cspViolations: string[] }).cspViolations = seen;
    document.addEventListener('securitypolicyviolation', (e) => {
      seen.push(`${e.effectiveDirective} blocked ${e.blockedURI || '(inline)'} at ${e.sourceFile}:${e.lineNumber}`);
    });
  });
}
const violations = (page: Page) => page.evaluate(() => (window as unknown as { cspViolations: string[] }).cspViolations);

/** A second origin: counts what it is asked for, serves a script that marks the page, and host pages. */
interface Elsewhere { url: string; hits: string[]; pages: Map<string, { body: string; csp: string }>; server: Server }
async function startElsewhere(): Promise<Elsewhere> {
  const port = await freePort();
  const hits: string[] = [];
  const pages = new Map<string, { body: string; csp: string }>();
  const server = createServer((req, res) => {
    hits.push(req.url ?? '');
    const page = pages.get(req.url ?? '');
    if (page) {
      res.writeHead(200, { 'content-type': 'text/html', 'content-security-policy': page.csp });
      res.end(page.body);
    } else if (req.url?.startsWith('/evil.js')) {
      res.writeHead(200, { 'content-type': 'text/javascript', 'access-control-allow-origin': '*' });
      res.end('window.evilRan = true;');
    } else {
      res.writeHead(200, { 'content-type': 'text/plain', 'access-control-allow-origin': '*' });
      res.end('from elsewhere');
    }
  });
  await new Promise<void>((r) => server.listen(port, '127.0.0.1', () => r()));
  return { url: `http://127.0.0.1:${port}`, hits, pages, server };
}

/** Put a script from `src` (or inline code) into the page; resolves with the violation it caused, or null. */
function injectScript(page: Page, script: { src?: string; text?: string }): Promise<string | null> {
  return page.evaluate((s) => new Promise<string | null>((resolve) => {
    document.addEventListener('securitypolicyviolation', (e) => resolve(`${e.effectiveDirective} ${e.blockedURI}`));
    const el = document.createElement('script');
    if (s.src) el.src = s.src; else el.textContent = s.text!;
    document.head.append(el);
    setTimeout(() => resolve(null), 3000);
  }), script);
}

describe('every page under the policy', () => {
  let session: BrowserSession;
  beforeAll(async () => {
    session = await openBrowser();
    await recordViolations(session);
  });
  afterAll(async () => { await session?.close(); });

  it('the build serves the pages this test knows, and each carries the policy', () => {
    for (const p of ['index.html', 'embed.html', 'explainer.html', 'model-card.html', 'results.html', 'bench.html']) expect(PAGES).toContain(p);
  });

  for (const name of PAGES) {
    it(`${name} works with the policy as header and <meta>, with no violation`, async () => {
      const { page } = session;
      const response = await page.goto(new URL(name === 'index.html' ? '' : name, baseUrl).href);
      expect(response?.headers()['content-security-policy']).toBe(CONTENT_SECURITY_POLICY);
      // the <meta> comes before every script and stylesheet, or it would not cover them
      const meta = await page.evaluate(() => {
        const m = document.head.querySelector('meta[http-equiv="Content-Security-Policy"]');
        const first = document.head.querySelector('script, link[rel="stylesheet"], link[rel="modulepreload"]');
        return { content: m?.getAttribute('content'), first: !!m && !!first && !!(m.compareDocumentPosition(first) & Node.DOCUMENT_POSITION_FOLLOWING) };
      });
      expect(meta.content).toBe(CONTENT_SECURITY_POLICY);
      expect(meta.first, 'the <meta> policy precedes the scripts').toBe(true);
      await (READY[name] ?? ((p: Page) => p.waitForLoadState('networkidle')))(page);
      expect(await violations(page)).toEqual([]);
      expect(session.problems).toEqual(NO_PROBLEMS);
    });
  }
});

describe('what comes from another origin is blocked', () => {
  let session: BrowserSession;
  let elsewhere: Elsewhere;
  let page: Page;
  beforeAll(async () => {
    elsewhere = await startElsewhere();
    session = await openBrowser();
    await recordViolations(session);
    page = session.page;
    await page.goto(baseUrl);
    await done('body[data-predict-status="done"]')(page);
  });
  afterAll(async () => {
    await session?.close();
    await new Promise((r) => elsewhere?.server.close(r));
  });

  it('a script from another origin does not run, is never fetched, and is reported', async () => {
    const src = `${elsewhere.url}/evil.js`;
    expect(await injectScript(page, { src })).toBe(`script-src-elem ${src}`);
    expect(await page.evaluate(() => (window as unknown as { evilRan?: boolean }).evilRan)).toBeUndefined();
    expect(elsewhere.hits.filter((h) => h.startsWith('/evil.js'))).toEqual([]);
  });

  it('an inline script does not run either', async () => {
    expect(await injectScript(page, { text: 'window.evilRan = true;' })).toBe('script-src-elem inline');
    expect(await page.evaluate(() => (window as unknown as { evilRan?: boolean }).evilRan)).toBeUndefined();
  });

  it('neither the page nor the predictor worker can fetch from another origin', async () => {
    const probe = (url: string) => fetch(url).then(() => 'fetched', (e: Error) => `refused: ${e.name}`);
    expect(await page.evaluate(probe, `${elsewhere.url}/page`)).toMatch(/^refused/);
    // the worker has the header's policy (a <meta> does not reach workers)
    const worker = page.workers().find((w) => /\/assets\/worker-[^/]*\.js$/.test(w.url()));
    expect(worker, 'the predictor worker is running').toBeDefined();
    expect(await worker!.evaluate(probe, `${elsewhere.url}/worker`)).toMatch(/^refused/);
    expect(elsewhere.hits).toEqual([]);
    expect((await violations(page)).filter((v) => v.startsWith('connect-src'))).not.toEqual([]);
  });

  it('the <meta> alone blocks it where the server sends no header (python3 -m http.server)', async () => {
    const port = await freePort();
    const child = spawn('python3', ['-m', 'http.server', String(port), '--bind', '127.0.0.1'], { cwd: DIST, stdio: 'ignore' });
    try {
      const url = `http://127.0.0.1:${port}/`;
      const deadline = Date.now() + 30_000;
      for (;;) {
        try { if ((await fetch(url, { signal: AbortSignal.timeout(2000) })).ok) break; } catch { /* not up yet */ }
        if (Date.now() > deadline) throw new Error('python3 -m http.server did not start');
        await new Promise((r) => setTimeout(r, 250));
      }
      const response = await page.goto(url);
      expect(response?.headers()['content-security-policy']).toBeUndefined();
      const src = `${elsewhere.url}/evil.js?meta`;
      expect(await injectScript(page, { src })).toBe(`script-src-elem ${src}`);
      expect(await page.evaluate(() => (window as unknown as { evilRan?: boolean }).evilRan)).toBeUndefined();
      expect(elsewhere.hits).toEqual([]);
    } finally {
      child.kill('SIGTERM');
    }
  });
});

describe('host pages under their own policy (README, Embedding)', () => {
  let elsewhere: Elsewhere;
  beforeAll(async () => { elsewhere = await startElsewhere(); });
  afterAll(async () => { await new Promise((r) => elsewhere?.server.close(r)); });

  it('a page on the same origin runs <motion-futures> allowing only the site for scripts, workers and connections', async () => {
    // default-src 'none': nothing but what the README lists
    const policy = "default-src 'none'; script-src 'self'; worker-src 'self'; connect-src 'self'; style-src 'unsafe-inline'";
    const hostUrl = `${origin}/elsewhere/csp-host.html`;
    const session = await openBrowser();
    try {
      await recordViolations(session);
      const { page } = session;
      await page.route(hostUrl, (route) => route.fulfill({
        status: 200, contentType: 'text/html', headers: { 'content-security-policy': policy },
        body: `<!doctype html><html lang="en"><head><meta charset="utf-8"><title>host</title></head><body>
<script type="module" src="${baseUrl}assets/motion-futures.js"></script>
<motion-futures id="w" autoplay style="height: 420px"></motion-futures></body></html>`,
      }));
      await page.goto(hostUrl);
      await done('motion-futures#w[data-predict-status="done"]')(page);
      expect(await violations(page)).toEqual([]);
      expect(session.problems).toEqual(NO_PROBLEMS);
    } finally {
      await session.close();
    }
  });

  it('a page on another origin shows embed.html in an iframe allowing only frame-src for the site', async () => {
    elsewhere.pages.set('/frame-host.html', {
      csp: `default-src 'none'; frame-src ${origin}`,
      body: `<!doctype html><html lang="en"><head><meta charset="utf-8"><title>host</title></head><body>
<iframe src="${baseUrl}embed.html?autoplay=1" title="motion-futures" width="720" height="480"></iframe></body></html>`,
    });
    const session = await openBrowser();
    try {
      await recordViolations(session);
      const { page } = session;
      await page.goto(`${elsewhere.url}/frame-host.html`);
      const frame = page.frameLocator('iframe');
      await frame.locator('motion-futures[data-predict-status="done"]').waitFor({ state: 'attached', timeout: 120_000 });
      expect(await violations(page)).toEqual([]);
      const inner = page.frames().find((f) => f.url().startsWith(`${baseUrl}embed.html`))!;
      expect(await inner.evaluate(() => (window as unknown as { cspViolations: string[] }).cspViolations)).toEqual([]);
      expect(session.problems).toEqual(NO_PROBLEMS);
    } finally {
      await session.close();
    }
  });
});
