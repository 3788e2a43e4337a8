// The explainer's worker: runs one named graph of a served model, nothing else. The figures plot
// what a Prediction does not carry (WAT's variance past the stop frame, the KP-GRU's label logits,
// LCP-VAE's mu_c and sigma_c), so they need the graphs' own outputs; the sampling around the
// graphs stays on the page, in the predictors' own functions. Same OrtRunner as the predictor worker.
import type { Manifest } from '../contract/types';
import { OrtRunner, type OrtModule } from '../predictor/ort-runner';
import type { FromGraphWorker, ToGraphWorker } from './graph-protocol';

const scope = self as unknown as DedicatedWorkerGlobalScope;
let manifest: Manifest | null = null;
let baseUrl = '';
let ortModule: Promise<OrtModule> | null = null;
const runners = new Map<string, OrtRunner>();
let queue: Promise<void> = Promise.resolve(); // one graph call at a time, like the predictor worker

function runtime(): Promise<OrtModule> {
  ortModule ??= import('onnxruntime-web/wasm').then((ort) => {
    ort.env.wasm.numThreads = 1;
    ort.env.logLevel = 'error';
    return ort as unknown as OrtModule;
  });
  return ortModule;
}

async function fetchBytes(file: string): Promise<Uint8Array> {
  const res = await fetch(new URL(`models/${file}`, baseUrl).href);
  if (!res.ok) throw new Error(`models/${file} could not be loaded (HTTP ${res.status})`);
  return new Uint8Array(await res.arrayBuffer());
}

async function runnerFor(model: string): Promise<OrtRunner> {
  let r = runners.get(model);
  if (!r) {
    const entry = manifest?.models.find((m) => m.id === model);
    if (!entry) throw new Error(`unknown model '${model}'`);
    r = new OrtRunner(await runtime(), entry, fetchBytes);
    runners.set(model, r);
  }
  return r;
}

scope.onmessage = (ev: MessageEvent<ToGraphWorker>) => {
  const msg = ev.data;
  if (msg.type === 'init') {
    manifest = msg.manifest;
    baseUrl = msg.baseUrl;
    return;
  }
  queue = queue.then(async () => {
    try {
      const outputs = await (await runnerFor(msg.model)).run(msg.role, msg.feeds);
      const reply: FromGraphWorker = { type: 'result', id: msg.id, outputs };
      scope.postMessage(reply);
    } catch (err) {
      const reply: FromGraphWorker = { type: 'error', id: msg.id, message: (err as Error)?.message ?? String(err) };
      scope.postMessage(reply);
    }
  });
};
