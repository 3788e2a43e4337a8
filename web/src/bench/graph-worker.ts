// Times one ONNX graph on given inputs with the same onnxruntime-web settings as the predictor
// worker (wasm, 1 thread, its optimisation level), for the export experiments in bench/. With
// `profile`, it also returns onnxruntime's per-node profile: the wasm build prints profile
// events to the console, so console.log is wrapped before onnxruntime loads and those lines kept.
import { SESSION_OPTIMIZATION } from '../predictor/ort-runner';
import type { GraphJob, GraphResult } from './protocol';

const scope = self as unknown as DedicatedWorkerGlobalScope;
const SAMPLE_MS = 5;
const MAX_REPS = 200;
let capturing: string[] | null = null;
const log = console.log.bind(console);
console.log = (...args: unknown[]) => {
  if (capturing) capturing.push(args.map(String).join(' '));
  else log(...args);
};

type Ort = typeof import('onnxruntime-web');
let ortModule: Promise<Ort> | null = null;
function runtime(): Promise<Ort> {
  ortModule ??= import('onnxruntime-web/wasm').then((ort) => {
    ort.env.wasm.numThreads = 1;
    ort.env.logLevel = 'error';
    return ort as unknown as Ort;
  });
  return ortModule;
}

/** Profile lines are JSON objects (one event each, maybe with a trailing comma). */
function events(lines: string[]): unknown[] {
  const out: unknown[] = [];
  for (const text of lines) {
    for (const line of text.split('\n')) {
      const t = line.trim().replace(/,$/, '');
      if (!t.startsWith('{')) continue;
      try { out.push(JSON.parse(t)); } catch { /* not an event */ }
    }
  }
  return out;
}

async function time(job: GraphJob): Promise<GraphResult> {
  const ort = await runtime();
  const t0 = performance.now();
  const session = await ort.InferenceSession.create(new Uint8Array(job.bytes), {
    executionProviders: ['wasm'], graphOptimizationLevel: job.optimization ?? SESSION_OPTIMIZATION, enableProfiling: !!job.profile,
  });
  const loadMs = performance.now() - t0;
  const feeds: Record<string, InstanceType<Ort['Tensor']>> = {};
  for (const [name, f] of Object.entries(job.feeds)) {
    feeds[name] = new ort.Tensor(f.type ?? 'float32', f.data, f.dims);
  }
  const runMs: number[] = [];
  let outputs: Record<string, number[]> | undefined;
  let warmed = 0;
  let reps = 1;
  const lines: string[] = [];
  if (job.profile) capturing = lines;
  try {
    // Warm-up: at least `warmup` runs and `warmupMs` of running, so V8 has tiered the hot wasm
    // functions up from its baseline compiler before the timed runs.
    const warmStart = performance.now();
    while (warmed < job.warmup || performance.now() - warmStart < (job.warmupMs ?? 0)) {
      const out = await session.run(feeds);
      if (warmed === 0 && job.keepOutputs) {
        outputs = Object.fromEntries(Object.entries(out).map(([k, t]) => [k, Array.from(t.data as Float32Array)]));
      }
      warmed++;
    }
    // performance.now() ticks in 0.1 ms steps without cross-origin isolation, so a graph faster
    // than a few ms is timed over `reps` back-to-back runs per sample (each sample >= SAMPLE_MS).
    const perRun = (performance.now() - warmStart) / Math.max(warmed, 1);
    reps = job.profile ? 1 : Math.min(MAX_REPS, Math.max(1, Math.ceil(SAMPLE_MS / Math.max(perRun, 1e-3))));
    for (let i = 0; i < job.runs; i++) {
      const s = performance.now();
      for (let r = 0; r < reps; r++) await session.run(feeds);
      runMs.push((performance.now() - s) / reps);
    }
    if (job.profile) session.endProfiling();
  } finally {
    capturing = null;
    await session.release();
  }
  return { id: job.id, loadMs, runMs, reps, warmupRuns: warmed, outputs, profile: job.profile ? events(lines) : undefined };
}

scope.onmessage = (ev: MessageEvent<GraphJob>) => {
  time(ev.data).then(
    (r) => scope.postMessage(r),
    (err) => scope.postMessage({ id: ev.data.id, error: (err as Error).message ?? String(err) }),
  );
};
