// The page's handle on the predictor worker. The page never imports onnxruntime: only the
// worker does (tests/web/worker-structure.test.ts checks it).
import type { Manifest } from '../contract/types';
import type { StageReadout } from '../ui/readout';
import type { FromWorker, GraphTiming, ReadoutInput, ToWorker } from './protocol';
import { PredictError, Superseded, type History, type Prediction, type PredictRequest } from './types';

export class ModelLoadError extends Error {
  constructor(message: string) {
    super(message);
    this.name = 'ModelLoadError';
  }
}

/** What the worker measured for one prediction (bench/ and the memory test read it), and the read-out
 *  when it was asked for. */
export interface Measured { ms: number; timings?: GraphTiming[]; wasmBytes?: number | null; readout?: StageReadout; readoutError?: string }

interface Pending {
  resolve: (v: Measured & { prediction?: Prediction }) => void;
  reject: (e: Error) => void;
  onProgress?: (loaded: number, total: number) => void;
}

export function webAssemblyAvailable(): boolean {
  try {
    return typeof WebAssembly === 'object' && typeof WebAssembly.instantiate === 'function'
      && WebAssembly.validate(new Uint8Array([0, 97, 115, 109, 1, 0, 0, 0]));
  } catch {
    return false;
  }
}

export class PredictorClient {
  private worker: Worker;
  private nextId = 1;
  private pending = new Map<number, Pending>();

  /**
   * `instrument` makes the worker report its wasm memory with each result (bench/ and the memory
   * test); a page can also ask for it by setting globalThis.__mfInstrument = true before it loads.
   */
  constructor(baseUrl: string, manifest: Manifest, worker?: Worker, options: { instrument?: boolean } = {}) {
    if (!webAssemblyAvailable()) throw new ModelLoadError('WebAssembly is not available in this browser, so models cannot run here');
    this.worker = worker ?? new Worker(new URL('./worker.ts', import.meta.url), { type: 'module' });
    this.worker.onmessage = (ev: MessageEvent<FromWorker>) => this.receive(ev.data);
    this.worker.onerror = (ev) => {
      const err = new ModelLoadError(`the predictor worker failed: ${ev.message || 'unknown error'}`);
      for (const p of this.pending.values()) p.reject(err);
      this.pending.clear();
    };
    const instrument = options.instrument ?? (globalThis as { __mfInstrument?: unknown }).__mfInstrument === true;
    this.send({ type: 'init', baseUrl, manifest, instrument });
  }

  private send(msg: ToWorker): void {
    this.worker.postMessage(msg);
  }

  private receive(msg: FromWorker): void {
    const p = this.pending.get(msg.id);
    if (!p) return;
    if (msg.type === 'progress') { p.onProgress?.(msg.loaded, msg.total); return; }
    this.pending.delete(msg.id);
    if (msg.type === 'result') {
      p.resolve({ prediction: msg.prediction, ms: msg.ms, timings: msg.timings, wasmBytes: msg.wasmBytes, readout: msg.readout, readoutError: msg.readoutError });
    }
    else if (msg.type === 'loaded') p.resolve({ ms: msg.ms });
    else if (msg.kind === 'superseded') p.reject(new Superseded());
    else if (msg.kind === 'predict') p.reject(new PredictError(msg.message));
    else p.reject(new ModelLoadError(msg.message));
  }

  private call(msg: ToWorker & { id: number }, onProgress?: Pending['onProgress']) {
    return new Promise<Measured & { prediction?: Prediction }>((resolve, reject) => {
      this.pending.set(msg.id, { resolve, reject, onProgress });
      this.send(msg);
    });
  }

  /** Load a model's sessions (lazily, once); progress in bytes. */
  async load(model: string, onProgress?: (loaded: number, total: number) => void): Promise<number> {
    return (await this.call({ type: 'load', id: this.nextId++, model }, onProgress)).ms;
  }

  /** Predict for one view; a newer request from the same view rejects this one with Superseded. With
   *  `readout`, the worker also computes the stage's read-out. */
  async predict(view: string, model: string, history: History, request: PredictRequest,
    onProgress?: (loaded: number, total: number) => void, readout?: ReadoutInput): Promise<Measured & { prediction: Prediction }> {
    const r = await this.call({ type: 'predict', id: this.nextId++, view, model, history, request, ...(readout ? { readout } : {}) }, onProgress);
    return { ...r, prediction: r.prediction! };
  }

  dispose(): void {
    this.worker.terminate();
  }
}
