// Issue 9, memory: after 50 warm-up predictions, 500 more add no wasm memory and less than 5 MB of
// JS heap after GC. Runs on the benchmark page (web/bench.html): the site's predictor worker,
// instrumented to report its wasm memory (web/src/bench/wasm-memory.ts). The JS heap is the page's
// plus the worker's, each read over CDP after HeapProfiler.collectGarbage.
import { readFileSync } from 'node:fs';
import { afterAll, beforeAll, describe, expect, inject, it } from 'vitest';
import type { CDPSession } from 'playwright-core';
import { openBrowser, type BrowserSession } from './browser';
import { defaultHistory } from './data';

const baseUrl = inject('baseUrl');
const manifest = JSON.parse(readFileSync(new URL('../../public/models/manifest.json', import.meta.url), 'utf8'));
// One model with a K control (the brief: K=10, one model, under ~2 min); the first such in the manifest.
const model = manifest.models.find((m: { controls: { id: string }[] }) => m.controls.some((c) => c.id === 'k'));
const K = 10;
const WARMUP = 50;
const MORE = 500;
const HEAP_LIMIT = 5 * 1024 * 1024;

/** CDP to the page and, through the page's session (non-flat mode), to its dedicated workers. */
class Heaps {
  private workers = new Set<string>();
  private nextId = 1;
  private pending = new Map<number, (r: { result?: unknown; error?: { message: string } }) => void>();

  private constructor(private readonly cdp: CDPSession) {
    cdp.on('Target.attachedToTarget', (e) => { if (e.targetInfo.type === 'worker') this.workers.add(e.sessionId); });
    cdp.on('Target.detachedFromTarget', (e) => { this.workers.delete(e.sessionId); });
    cdp.on('Target.receivedMessageFromTarget', (e) => {
      const msg = JSON.parse(e.message) as { id?: number; result?: unknown; error?: { message: string } };
      if (msg.id !== undefined) { this.pending.get(msg.id)?.(msg); this.pending.delete(msg.id); }
    });
  }

  static async attach(cdp: CDPSession): Promise<Heaps> {
    const h = new Heaps(cdp);
    await cdp.send('Target.setAutoAttach', { autoAttach: true, waitForDebuggerOnStart: false, flatten: false });
    return h;
  }

  get workerCount(): number { return this.workers.size; }

  private toWorker(sessionId: string, method: string): Promise<unknown> {
    const id = this.nextId++;
    return new Promise((resolve, reject) => {
      this.pending.set(id, (r) => (r.error ? reject(new Error(`${method}: ${r.error.message}`)) : resolve(r.result)));
      this.cdp.send('Target.sendMessageToTarget', { sessionId, message: JSON.stringify({ id, method }) }).catch(reject);
    });
  }

  /** Bytes of JS heap in use on the page and in every worker, after a full GC of each. */
  async usedAfterGc(): Promise<{ page: number; workers: number }> {
    await this.cdp.send('HeapProfiler.collectGarbage');
    const page = (await this.cdp.send('Runtime.getHeapUsage')).usedSize;
    let workers = 0;
    for (const s of this.workers) {
      await this.toWorker(s, 'HeapProfiler.collectGarbage');
      workers += ((await this.toWorker(s, 'Runtime.getHeapUsage')) as { usedSize: number }).usedSize;
    }
    return { page, workers };
  }
}

describe('memory of repeated predictions', () => {
  let session: BrowserSession;

  beforeAll(async () => { session = await openBrowser(); });
  afterAll(async () => { await session?.close(); });

  it(`${MORE} predictions after ${WARMUP} warm-ups add no wasm memory and < 5 MB of JS heap`, async () => {
    expect(model, 'the manifest has a model with a K control').toBeDefined();
    const { page } = session;
    const cdp = await session.context.newCDPSession(page);
    await cdp.send('Runtime.enable');
    const heaps = await Heaps.attach(cdp);
    await page.goto(`${baseUrl}bench.html`);
    await page.evaluate(() => window.mfBench!.ready);
    const c = { model: model.id, clip: defaultHistory().clip.name, start: defaultHistory().start, request: { k: K, seed: 1 } };
    const run = (n: number) => page.evaluate((a) => window.mfBench!.run(a.c, 0, a.n).then((r) => ({
      wasm: r.wasmBytes, k: r.lengths.length, ms: r.workerMs.reduce((s, x) => s + x, 0) / r.workerMs.length,
    })), { c, n });

    const warm = await run(WARMUP);
    expect(warm.k).toBe(K);
    expect(heaps.workerCount, 'CDP reached the predictor worker').toBeGreaterThan(0);
    const wasmBefore = warm.wasm.at(-1);
    expect(wasmBefore, 'the worker reports its wasm memory').toBeGreaterThan(0);
    const before = await heaps.usedAfterGc();

    const more = await run(MORE);
    const after = await heaps.usedAfterGc();
    const grown = after.page + after.workers - (before.page + before.workers);
    console.log(`memory: ${model.id} K=${K}, ${more.ms.toFixed(1)} ms per prediction; wasm ${wasmBefore} -> ${more.wasm.at(-1)} B;`
      + ` JS heap page ${before.page} -> ${after.page} B, workers ${before.workers} -> ${after.workers} B`);
    expect(more.wasm.every((b) => b === wasmBefore), 'wasm memory stays the same size').toBe(true);
    expect(grown).toBeLessThan(HEAP_LIMIT);
  }, 300_000);
});
