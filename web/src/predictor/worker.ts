// The predictor worker: owns onnxruntime-web and every session, runs one job at a time.
// A new request from a view supersedes that view's queued or running request; requests from
// other views wait their turn.
import { captureWasmMemory, wasmMemoryBytes } from '../bench/wasm-memory';
import type { Manifest } from '../contract/types';
import { readoutAfter, type StageReadout } from '../ui/readout';
import { createCheckedPredictor } from './history';
import { OrtRunner, type GraphTiming, type OrtModule } from './ort-runner';
import type { ErrorKind, FromWorker, ReadoutInput, ToWorker } from './protocol';
import { Scheduler, type Job as QueuedJob } from './scheduler';
import { PredictError, Superseded, type Prediction, type Predictor } from './types';

interface Job extends QueuedJob { msg: Extract<ToWorker, { type: 'load' | 'predict' }> }

const scope = self as unknown as DedicatedWorkerGlobalScope;
let manifest: Manifest | null = null;
let baseUrl = '';
let ortModule: Promise<OrtModule> | null = null;
const predictors = new Map<string, { predictor: Predictor; runner: OrtRunner }>();
const scheduler = new Scheduler<Job>();
let instrumented = false;
let timings: GraphTiming[] = []; // the running prediction's graph calls (one job runs at a time)

function post(msg: FromWorker, transfer: Transferable[] = []): void {
  scope.postMessage(msg, transfer);
}

/** A one-node ONNX graph (Identity on float[1], opset 13, 65 bytes). */
const OPENER = 'CAc6NwoQCgF4EgF5IghJZGVudGl0eRIBd1oPCgF4EgoKCAgBEgQKAggBYg8KAXkSCgoICAESBAoCCAFCBAoAEA0=';

/** onnxruntime, started as soon as the worker starts: a session of OPENER makes it fetch,
 *  compile and start its 14 MB wasm while the model's files are still on their way (it used to wait
 *  for them: make bench's first-futures timeline, docs/PERFORMANCE.md). A failed opener is not
 *  reported: the model's own session then fails or succeeds with its own message. */
function runtime(): Promise<OrtModule> {
  ortModule ??= import('onnxruntime-web/wasm').then(async (ort) => {
    ort.env.wasm.numThreads = 1; // no COOP/COEP needed; on 2 cores threads were slower
    ort.env.logLevel = 'error';
    try {
      const bytes = Uint8Array.from(atob(OPENER), (c) => c.charCodeAt(0));
      const opener = await ort.InferenceSession.create(bytes, { executionProviders: ['wasm'] });
      void opener.release();
    } catch {
      // see above
    }
    return ort as unknown as OrtModule;
  });
  return ortModule;
}

/** A model file (graph or JSON artefact) that could not be fetched. */
class ModelFileError extends Error {}

async function fetchBytes(file: string, onProgress?: (n: number) => void): Promise<Uint8Array> {
  const url = new URL(`models/${file}`, baseUrl).href;
  let res: Response;
  try {
    res = await fetch(url);
  } catch (err) {
    throw new ModelFileError(`models/${file} could not be loaded (${(err as Error).message})`);
  }
  if (!res.ok) throw new ModelFileError(`models/${file} could not be loaded (HTTP ${res.status})`);
  if (!res.body) return new Uint8Array(await res.arrayBuffer());
  const reader = res.body.getReader();
  const chunks: Uint8Array[] = [];
  let n = 0;
  for (;;) {
    const { done, value } = await reader.read();
    if (done) break;
    chunks.push(value);
    n += value.length;
    onProgress?.(n);
  }
  const out = new Uint8Array(n);
  let o = 0;
  for (const c of chunks) { out.set(c, o); o += c.length; }
  return out;
}

async function predictorFor(model: string, id: number): Promise<{ predictor: Predictor; runner: OrtRunner }> {
  let p = predictors.get(model);
  if (!p) {
    if (!manifest) throw new Error('the worker has no manifest yet');
    const entry = manifest.models.find((m) => m.id === model);
    if (!entry) throw new PredictError(`unknown model '${model}'`);
    const runner = new OrtRunner(runtime(), entry, fetchBytes, (t) => timings.push(t));
    await runner.loadAll((loaded, total) => post({ type: 'progress', id, model, loaded, total }));
    const predictor = createCheckedPredictor({ entry, skeleton: manifest.skeleton, actions: manifest.actions, fps: manifest.fps, runner, loadFile: fetchBytes });
    p = { predictor, runner };
    predictors.set(model, p);
  }
  return p;
}

async function execute(job: Job): Promise<void> {
  const { msg } = job;
  if (msg.type === 'load') {
    const t0 = performance.now();
    await predictorFor(msg.model, msg.id);
    post({ type: 'loaded', id: msg.id, model: msg.model, ms: performance.now() - t0 });
    return;
  }
  const { predictor } = await predictorFor(msg.model, msg.id);
  timings = [];
  const t0 = performance.now();
  const prediction = await predictor.predict(msg.history, msg.request, () => job.cancelled);
  const ms = performance.now() - t0;
  const readout = msg.readout ? readoutOf(prediction, msg.history.positions, msg.readout) : {};
  post({ type: 'result', id: msg.id, prediction, ms, timings, ...readout, ...(instrumented ? { wasmBytes: wasmMemoryBytes() } : {}) },
    [prediction.futures.buffer]);
}

/** The stage's read-out, or why it could not be computed (the prediction stands either way). */
function readoutOf(p: Prediction, history: Float32Array, input: ReadoutInput): { readout?: StageReadout; readoutError?: string } {
  try {
    return { readout: readoutAfter(p, history, input.truth, input.skeleton) };
  } catch (err) {
    return { readoutError: (err as Error).message ?? String(err) };
  }
}

function kindOf(err: unknown, job: Job): ErrorKind {
  if (err instanceof Superseded) return 'superseded';
  if (err instanceof PredictError) return 'predict';
  if (err instanceof ModelFileError) return 'load';
  return job.msg.type === 'load' || !predictors.has(job.msg.model) ? 'load' : 'internal';
}

async function run(job: Job): Promise<void> {
  try {
    await execute(job);
  } catch (err) {
    post({ type: 'error', id: job.id, kind: kindOf(err, job), message: (err as Error).message ?? String(err) });
  }
}

// onnxruntime starts with the worker (web/src/ui/predictor-start.ts starts it before the page has its
// manifest). The init message is handled first anyway: a module worker gets its queued messages
// once this script has run, and onnxruntime's script is fetched after that, so an instrumented
// page's wasm capture is in place before onnxruntime instantiates its wasm.
void runtime();

scope.onmessage = (ev: MessageEvent<ToWorker>) => {
  const msg = ev.data;
  if (msg.type === 'init') {
    manifest = msg.manifest;
    baseUrl = msg.baseUrl;
    if (msg.instrument && !instrumented) { instrumented = true; captureWasmMemory(); } // before onnxruntime loads
    return;
  }
  const job: Job = { id: msg.id, view: msg.type === 'predict' ? msg.view : undefined, cancelled: false, msg };
  for (const old of scheduler.push(job)) {
    post({ type: 'error', id: old.id, kind: 'superseded', message: 'superseded by a newer request' });
  }
  void scheduler.drain(run);
};
