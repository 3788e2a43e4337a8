// A new release replaces the old one cleanly. Release A (the suite's dist/) is served and goes
// offline-ready; then release B is served on the same origin: a real build of a copy of the sources
// with the next version number, one model graph of the page's opening model and one of another
// model with other bytes (their manifest entries follow), and the opening clip changed. After one
// reload the page must run B's code with B's manifest, models and clips, and no page load may ever
// mix files of the two releases (every response is matched against A's and B's files by its
// bytes). A permalink made on A names its model hash as not this site's.
import { createHash } from 'node:crypto';
import { cpSync, existsSync, mkdirSync, mkdtempSync, readdirSync, readFileSync, rmSync, symlinkSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import type { Page, Request } from 'playwright-core';
import type { Manifest } from '../../web/src/contract/types';
import { shortHash } from '../../web/src/share/url-state';
import { openBrowser, type BrowserSession } from './browser';
import { index, manifest, stageModel } from './data';
import { buildTree, freePort, ROOT, startPreview, type PreviewServer } from './server';

type Release = 'A' | 'B';
const A_DIR = join(ROOT, 'dist');
const A_VERSION: string = JSON.parse(readFileSync(join(ROOT, 'package.json'), 'utf8')).version;
const B_VERSION = A_VERSION.replace(/^(\d+)\.(\d+)\.(\d+).*$/, (_, a, b, c) => `${a}.${b}.${Number(c) + 1}`);
/** The model the test switches to after the update: not the opening one, so its files load only then. */
const OTHER = manifest.models.find((m) => m.id !== stageModel.id)!;
const CHANGED_MODELS = [stageModel, OTHER];
const OPENING_CLIP = index.clips.find((c) => c.name === index.default?.clip) ?? index.clips[0];

const sha = (bytes: Buffer | Uint8Array) => createHash('sha256').update(bytes).digest('hex');
const predicted = (page: Page) =>
  page.waitForSelector('body[data-predict-status="done"]', { state: 'attached', timeout: 120_000 });

/**
 * Another graph with the same weights: ONNX is a protobuf, so a doc_string field (ModelProto field
 * 6) appended to the file is read as the model's doc string. Same futures, other bytes.
 */
function otherBytes(onnx: Buffer, note: string): Buffer {
  const text = Buffer.from(note, 'utf8');
  if (text.length > 127) throw new Error('the note must fit a one-byte length');
  return Buffer.concat([onnx, Buffer.from([0x32, text.length]), text]);
}

/** The source tree of release B: a copy of what a build reads, with B's version, graphs and clip. */
function releaseBTree(tree: string): { changed: string[] } {
  mkdirSync(tree, { recursive: true });
  // copied: what B changes, and the config (its paths follow its own file); the rest is linked
  const COPIED = ['web', 'public', 'vite.config.ts', 'package.json'];
  for (const f of COPIED) if (f !== 'package.json') cpSync(join(ROOT, f), join(tree, f), { recursive: true });
  for (const f of readdirSync(ROOT)) {
    if (!COPIED.includes(f) && !['dist', '.git'].includes(f)) symlinkSync(join(ROOT, f), join(tree, f));
  }
  const pkg = JSON.parse(readFileSync(join(ROOT, 'package.json'), 'utf8'));
  writeFileSync(join(tree, 'package.json'), `${JSON.stringify({ ...pkg, version: B_VERSION }, null, 2)}\n`);
  const changed: string[] = [];
  const mf: Manifest = JSON.parse(readFileSync(join(tree, 'public/models/manifest.json'), 'utf8'));
  for (const id of CHANGED_MODELS.map((m) => m.id)) {
    const entry = mf.models.find((m) => m.id === id)!;
    const graph = Object.values(entry.graphs)[0];
    const path = join(tree, 'public/models', graph.file);
    const bytes = otherBytes(readFileSync(path), `motion-futures ${B_VERSION} (update test)`);
    writeFileSync(path, bytes);
    graph.sha256 = sha(bytes);
    graph.bytes = bytes.length;
    entry.hash = `sha256:${sha(Buffer.from(`${entry.hash} ${graph.sha256}`))}`;
    changed.push(`models/${graph.file}`);
  }
  writeFileSync(join(tree, 'public/models/manifest.json'), `${JSON.stringify(mf, null, 1)}\n`);
  const clipPath = join(tree, 'public/clips', OPENING_CLIP.file);
  const clip = JSON.parse(readFileSync(clipPath, 'utf8'));
  clip.source = { ...clip.source, release: B_VERSION };
  writeFileSync(clipPath, JSON.stringify(clip));
  changed.push('models/manifest.json', `clips/${OPENING_CLIP.file}`, 'version.json');
  return { changed };
}

/** What one response's bytes say about its release: A, B, the same in both, or neither. */
type Verdict = Release | 'both' | 'neither' | 'unknown';

describe('a new release replaces the old one', () => {
  let tmp: string;
  let bDir: string;
  let changed: string[];
  let port: number;
  let server: PreviewServer | null = null;
  let session: BrowserSession;
  let page: Page;
  let basePath: string;
  /** Page loads: each main-frame navigation starts one; requests count in the load that made them. */
  let load = 0;
  const seen: { load: number; path: string; verdict: Promise<Verdict> }[] = [];
  const files: Record<Release, string> = { A: A_DIR, B: '' };

  const fileSha = (release: Release, path: string) => {
    const p = join(files[release], path);
    return existsSync(p) ? sha(readFileSync(p)) : null;
  };
  async function verdict(request: Request, path: string): Promise<Verdict> {
    const a = fileSha('A', path);
    const b = fileSha('B', path);
    if (a === null && b === null) return 'unknown';
    if (a === b) return 'both';
    const response = await request.response();
    if (!response || response.status() !== 200) return 'unknown';
    const got = sha(await response.body());
    return got === a ? 'A' : got === b ? 'B' : 'neither';
  }

  beforeAll(async () => {
    tmp = mkdtempSync(join(tmpdir(), 'motion-futures-release-'));
    bDir = join(tmp, 'B');
    files.B = bDir;
    const tree = join(tmp, 'tree');
    ({ changed } = releaseBTree(tree));
    await buildTree(tree, bDir);
    expect(JSON.parse(readFileSync(join(bDir, 'version.json'), 'utf8')).version).toBe(B_VERSION);
    port = await freePort();
    session = await openBrowser();
    page = session.page;
    const finish = new Map<Request, (failed: boolean) => void>();
    session.context.on('requestfinished', (r) => finish.get(r)?.(false));
    session.context.on('requestfailed', (r) => finish.get(r)?.(true));
    session.context.on('request', (r) => {
      // the service worker's own fetches (installing a precache) belong to no page load
      if (r.serviceWorker()) return;
      const url = new URL(r.url());
      if (url.origin !== `http://127.0.0.1:${port}` || !url.pathname.startsWith(basePath)) return;
      const path = url.pathname.slice(basePath.length) || 'index.html';
      // the worker scripts are the service worker's, fetched by the browser when it checks for updates
      if (path === 'sw.js' || /^workbox-[^/]*\.js$/.test(path)) return;
      // a new document (not a history.replaceState) starts a page load
      if (r.isNavigationRequest() && r.resourceType() === 'document' && r.frame() === page.mainFrame()) load += 1;
      const verdictOf = new Promise<Verdict>((resolve) => finish.set(r, (failed) => {
        finish.delete(r);
        if (failed) resolve('unknown'); else verdict(r, path).then(resolve, () => resolve('unknown'));
      }));
      seen.push({ load, path, verdict: verdictOf });
    });
  }, 300_000);

  afterAll(async () => {
    await session?.close();
    await server?.stop();
    if (tmp) rmSync(tmp, { recursive: true, force: true });
  });

  it('runs release A and goes offline-ready', async () => {
    server = await startPreview({ port, outDir: A_DIR });
    basePath = new URL(server.url).pathname;
    await page.goto(server.url);
    await predicted(page);
    await page.waitForSelector('body[data-offline="ready"]', { state: 'attached', timeout: 180_000 });
    expect(new URL(page.url()).searchParams.get('v')).toBe(A_VERSION);
  }, 300_000);

  it('after one reload on release B it runs B\'s code with B\'s models and clips, never a mix', async () => {
    const permalinkA = page.url();
    await server!.stop();
    server = await startPreview({ port, outDir: bDir });
    await page.reload();
    // the page's code writes its own version into the address bar
    await expect.poll(() => new URL(page.url()).searchParams.get('v'), { timeout: 180_000, interval: 500 }).toBe(B_VERSION);
    await predicted(page);
    await page.waitForSelector('body[data-offline="ready"]', { state: 'attached', timeout: 180_000 });
    // a model whose files load only now, from B's caches
    await page.evaluate(() => { document.body.dataset.predictStatus = 'waiting'; });
    await page.locator('#model-select').selectOption(OTHER.id);
    await page.locator('#predict').click();
    await predicted(page);
    const lastLoad = load;

    const byLoad = new Map<number, Map<string, Verdict>>();
    for (const s of seen) {
      const v = await s.verdict;
      if (!byLoad.has(s.load)) byLoad.set(s.load, new Map());
      const m = byLoad.get(s.load)!;
      // one path asked twice in one load must give the same bytes both times
      const before = m.get(s.path);
      m.set(s.path, before && before !== v ? 'neither' : v);
    }
    const summary = [...byLoad].map(([n, m]) => {
      const of = (r: Verdict) => [...m].filter(([, v]) => v === r).map(([p]) => p);
      return { load: n, A: of('A'), B: of('B'), neither: of('neither') };
    });
    console.log(`release update: ${summary.map((s) => `load ${s.load}: ${s.A.length} files of A, ${s.B.length} of B`).join('; ')}`);
    for (const s of summary) {
      expect(s.neither, `load ${s.load}: bytes of neither release`).toEqual([]);
      expect(s.A.length && s.B.length ? s : null, `load ${s.load} mixes releases`).toBeNull();
    }
    const first = summary.find((s) => s.load === 1)!;
    const last = summary.find((s) => s.load === lastLoad)!;
    for (const f of changed.filter((p) => p !== 'version.json')) {
      if (f !== `models/${Object.values(OTHER.graphs)[0].file}`) expect(first.A, `release A loaded ${f}`).toContain(f);
      expect(last.B, `the last page load took ${f} from B`).toContain(f);
    }
    expect(last.B.some((p) => /^assets\/.*\.js$/.test(p)), 'B\'s scripts').toBe(true);
    // the caches hold B's bytes for each changed file, and nothing of A's
    const cached = await page.evaluate(async (paths) => {
      const hex = (b: ArrayBuffer) => [...new Uint8Array(b)].map((x) => x.toString(16).padStart(2, '0')).join('');
      const out: Record<string, string[]> = {};
      for (const name of await caches.keys()) {
        const cache = await caches.open(name);
        for (const req of await cache.keys()) {
          const path = paths.find((p) => new URL(req.url).pathname.endsWith(`/${p}`));
          if (!path) continue;
          const res = await cache.match(req);
          (out[path] ??= []).push(hex(await crypto.subtle.digest('SHA-256', await res!.arrayBuffer())));
        }
      }
      return out;
    }, changed);
    for (const f of changed) expect(cached[f], f).toEqual([fileSha('B', f)]);

    // a permalink made on A names the model hash it was made with, and this site's
    await page.goto(permalinkA);
    await predicted(page);
    const bManifest: Manifest = JSON.parse(readFileSync(join(bDir, 'models/manifest.json'), 'utf8'));
    const aManifest: Manifest = JSON.parse(readFileSync(join(A_DIR, 'models/manifest.json'), 'utf8'));
    const hashOf = (m: Manifest) => shortHash(m.models.find((e) => e.id === stageModel.id)!.hash);
    const text = (await page.locator('.message-warning').allTextContents()).join('\n');
    expect(hashOf(aManifest)).not.toBe(hashOf(bManifest));
    expect(text).toContain(`model hash ${hashOf(aManifest)}; this site's is ${hashOf(bManifest)}`);
    expect(text).toContain(`made with motion-futures ${A_VERSION}; this site is ${B_VERSION}`);
    // a page asking for files its release no longer serves (an old page under a new worker) gets 404s
    expect(session.problems.failedRequests.filter((f) => /: HTTP \d+$/.test(f))).toEqual([]);
    expect(session.problems.pageErrors).toEqual([]);
    expect(session.problems.consoleErrors).toEqual([]);
  }, 400_000);
});
