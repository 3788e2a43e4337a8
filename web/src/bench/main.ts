// The benchmark page (bench.html), driven by bench/ and tests/e2e/memory.e2e.test.ts through
// window.mfBench: the site's own predictor worker with no UI around it, and a second worker that
// times single ONNX graphs for the export experiments. Nothing here runs onnxruntime on the page.
import type { Manifest } from '../contract/types';
import { fetchContract } from '../contract/validate';
import { motionFromDoc, window as clipWindow, type Motion } from '../motion/clip';
import { PredictorClient } from '../predictor/client';
import type { GraphTiming } from '../predictor/protocol';
import type { PredictRequest } from '../predictor/types';
import type { Feed, GraphJob, GraphResult } from './protocol';

export interface BenchCase {
  model: string;
  clip: string;
  start: number;
  request: PredictRequest;
}

export interface CaseRuns {
  /** predictor.predict in the worker (noise, graphs, stopping, smoothness, interpolation). */
  workerMs: number[];
  /** From postMessage to the result on the page. */
  roundTripMs: number[];
  /** Per run, each graph call. */
  timings: GraphTiming[][];
  /** The worker's wasm memory after each run. */
  wasmBytes: (number | null)[];
  lengths: number[];
  frames: number;
}

export interface GraphSpec {
  /** The ONNX file, base64. */
  base64: string;
  /** Float32 little-endian bytes, base64 (as export/bench/native.py writes them). */
  feeds: Record<string, { dims: number[]; base64: string }>;
  warmup: number;
  warmupMs?: number;
  runs: number;
  optimization?: GraphJob['optimization'];
  profile?: boolean;
  keepOutputs?: boolean;
  /** Time in a new worker: a new onnxruntime wasm instance whose compiled code no other graph has shaped. */
  fresh?: boolean;
}

const root = new URL('./', location.href).href;
const status = document.getElementById('status')!;
let manifest: Manifest;
let client: PredictorClient;
const clips = new Map<string, Promise<Motion>>();
let graphWorker: Worker | null = null;
let nextGraphJob = 1;
const graphJobs = new Map<number, (r: GraphResult) => void>();

function clip(name: string): Promise<Motion> {
  let m = clips.get(name);
  if (!m) {
    m = fetchContract(`${root}clips/${name}.json`, 'clip').then(motionFromDoc);
    clips.set(name, m);
  }
  return m;
}

async function start(): Promise<{ models: string[] }> {
  manifest = await fetchContract(`${root}models/manifest.json`, 'manifest');
  client = new PredictorClient(root, manifest, undefined, { instrument: true });
  status.textContent = 'ready';
  return { models: manifest.models.map((m) => m.id) };
}

async function load(model: string): Promise<{ roundTripMs: number; workerMs: number }> {
  const t0 = performance.now();
  const workerMs = await client.load(model);
  return { roundTripMs: performance.now() - t0, workerMs };
}

async function run(c: BenchCase, warmup: number, runs: number): Promise<CaseRuns> {
  const entry = manifest.models.find((m) => m.id === c.model);
  if (!entry) throw new Error(`no model ${c.model}`);
  const m = await clip(c.clip);
  const n = entry.params.history_frames;
  const history = { positions: clipWindow(m, c.start, n), frames: n, joints: m.joints };
  const out: CaseRuns = { workerMs: [], roundTripMs: [], timings: [], wasmBytes: [], lengths: [], frames: 0 };
  for (let i = 0; i < warmup + runs; i++) {
    status.textContent = `${c.model} K=${c.request.k}: run ${i + 1} of ${warmup + runs}`;
    const t0 = performance.now();
    const r = await client.predict('bench', c.model, { ...history, positions: history.positions.slice() }, c.request);
    const roundTrip = performance.now() - t0;
    if (i < warmup) continue;
    out.workerMs.push(r.ms);
    out.roundTripMs.push(roundTrip);
    out.timings.push(r.timings ?? []);
    out.wasmBytes.push(r.wasmBytes ?? null);
    out.lengths = Array.from(r.prediction.lengths);
    out.frames = r.prediction.frames;
  }
  return out;
}

function decode(base64: string): ArrayBuffer {
  const bin = atob(base64);
  const bytes = new Uint8Array(bin.length);
  for (let i = 0; i < bin.length; i++) bytes[i] = bin.charCodeAt(i);
  return bytes.buffer;
}

function graph(spec: GraphSpec): Promise<GraphResult> {
  if (spec.fresh && graphWorker) {
    // V8 optimises onnxruntime's wasm with call feedback from the graphs run so far, so a graph's
    // time in a shared worker depends on what ran before it (bench/browser.ts: graphs()).
    graphWorker.terminate();
    graphWorker = null;
    for (const [id, resolve] of graphJobs) resolve({ id, error: 'the graph worker was replaced' });
    graphJobs.clear();
  }
  graphWorker ??= new Worker(new URL('./graph-worker.ts', import.meta.url), { type: 'module' });
  graphWorker.onmessage = (ev: MessageEvent<GraphResult>) => {
    graphJobs.get(ev.data.id)?.(ev.data);
    graphJobs.delete(ev.data.id);
  };
  const feeds: Record<string, Feed> = {};
  for (const [name, f] of Object.entries(spec.feeds)) {
    const data = new Float32Array(decode(f.base64));
    if (data.length !== f.dims.reduce((a, b) => a * b, 1)) throw new Error(`feed ${name}: ${data.length} values for dims ${f.dims}`);
    feeds[name] = { dims: f.dims, data };
  }
  const job: GraphJob = {
    id: nextGraphJob++, bytes: decode(spec.base64), feeds, warmup: spec.warmup, warmupMs: spec.warmupMs, runs: spec.runs,
    optimization: spec.optimization, profile: spec.profile, keepOutputs: spec.keepOutputs,
  };
  return new Promise((resolve) => {
    graphJobs.set(job.id, resolve);
    graphWorker!.postMessage(job, [job.bytes]);
  });
}

declare global {
  interface Window {
    mfBench?: {
      ready: Promise<{ models: string[] }>;
      load: typeof load;
      run: typeof run;
      graph: typeof graph;
    };
  }
}

window.mfBench = { ready: start(), load, run, graph };
window.mfBench.ready.catch((err) => { status.textContent = `failed: ${(err as Error).message}`; });
