// The predictor worker, started before the widget builds its stage and panels: the worker starts
// onnxruntime (its script and its 14 MB wasm) at once, so that start-up overlaps the page's own
// instead of waiting for the manifest, which the busy main thread reads only once its start-up
// task is over (make bench's first-futures timeline, docs/PERFORMANCE.md). One worker and one
// client per site, as web/src/embed/shared.ts's sharedClient, which this stands in for in app.ts.
import type { Manifest } from '../contract/types';
import { PredictorClient, webAssemblyAvailable } from '../predictor/client';

const workers = new Map<string, Worker>();
const clients = new Map<string, PredictorClient>();

/** Start this site's worker now (nothing happens without WebAssembly or when it already runs). */
export function startWorker(siteRoot: string): void {
  if (workers.has(siteRoot) || clients.has(siteRoot) || !webAssemblyAvailable()) return;
  try {
    workers.set(siteRoot, new Worker(new URL('../predictor/worker.ts', import.meta.url), { type: 'module' }));
  } catch {
    // the client made later tries again and reports what fails
  }
}

/** The site's client on the worker startWorker started (or a new one); throws ModelLoadError without WebAssembly. */
export function workerClient(siteRoot: string, manifest: Manifest): PredictorClient {
  let c = clients.get(siteRoot);
  if (!c) {
    c = new PredictorClient(siteRoot, manifest, workers.get(siteRoot));
    workers.delete(siteRoot);
    clients.set(siteRoot, c);
  }
  return c;
}
