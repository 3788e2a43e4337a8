// The page's handle on the explainer's graph worker, and a GraphRunner over it, so the
// predictors' own classes (e.g. KeyposesPredictor) run on the page with their graphs in the worker.
import type { Manifest } from '../contract/types';
import { ModelLoadError, webAssemblyAvailable } from '../predictor/client';
import type { GraphRunner, Tensor } from '../predictor/types';
import type { FromGraphWorker, ToGraphWorker } from './graph-protocol';

export class GraphClient {
  private readonly worker: Worker;
  private nextId = 1;
  private readonly pending = new Map<number, { resolve(o: Record<string, Tensor>): void; reject(e: Error): void }>();

  constructor(baseUrl: string, manifest: Manifest) {
    if (!webAssemblyAvailable()) throw new ModelLoadError('WebAssembly is not available in this browser, so the models cannot run here');
    this.worker = new Worker(new URL('./graph-worker.ts', import.meta.url), { type: 'module' });
    this.worker.onmessage = (ev: MessageEvent<FromGraphWorker>) => {
      const msg = ev.data;
      const p = this.pending.get(msg.id);
      if (!p) return;
      this.pending.delete(msg.id);
      if (msg.type === 'result') p.resolve(msg.outputs);
      else p.reject(new ModelLoadError(msg.message));
    };
    this.worker.onerror = (ev) => {
      const err = new ModelLoadError(`the explainer's model worker failed: ${ev.message || 'unknown error'}`);
      for (const p of this.pending.values()) p.reject(err);
      this.pending.clear();
    };
    this.post({ type: 'init', baseUrl, manifest });
  }

  private post(msg: ToGraphWorker): void {
    this.worker.postMessage(msg);
  }

  run(model: string, role: string, feeds: Record<string, Tensor>): Promise<Record<string, Tensor>> {
    const id = this.nextId++;
    return new Promise((resolve, reject) => {
      this.pending.set(id, { resolve, reject });
      this.post({ type: 'run', id, model, role, feeds });
    });
  }

  /** A GraphRunner for one model, as PredictorContext expects. */
  runner(model: string): GraphRunner {
    return { run: (role, feeds) => this.run(model, role, feeds) };
  }
}
