// GraphRunner over onnxruntime-web. Only the worker (and Node tests) import this module; the
// runtime module itself is passed in, so the page never loads onnxruntime on the main thread.
import type * as Ort from 'onnxruntime-web';
import type { ModelEntry } from '../contract/types';
import type { GraphTiming } from './protocol';
import type { FileLoader, GraphRunner, Tensor } from './types';

export type OrtModule = typeof Ort;

/** onnxruntime's session graph optimisation levels, lowest first. */
export const OPTIMIZATION_LEVELS = ['disabled', 'basic', 'extended', 'all'] as const;
/** The level of every predictor session. 'disabled': on the 2-core bench machine with a fresh
 *  profile, the optimiser's own start-up work (run as V8's baseline wasm code, then tiered up in the
 *  background on the same cores) cost more than it saved. Navigation -> first futures drawn, 7
 *  navigations of ?model=wat-rnn: median 1396 ms at 'all', 1271 ms at 'disabled'; each graph's run
 *  stays within 0-30% of 'all' (make bench, "Attempts on the ratio"; wat-rnn's decoder at K = 10:
 *  7.0 against 6.8 ms). The e2e vectors hold at either level. */
export type OptimizationLevel = (typeof OPTIMIZATION_LEVELS)[number];
export const SESSION_OPTIMIZATION: OptimizationLevel = 'disabled';
export type { FileLoader };
export type { GraphTiming };

export class OrtRunner implements GraphRunner {
  private sessions = new Map<string, Promise<{ session: Ort.InferenceSession; ort: OrtModule }>>();
  private readonly ort: Promise<OrtModule>;

  /** `onRun` receives each session.run's timing (the worker returns them with the result; bench/ reads them).
   * `ort` may still be loading: the model files are fetched meanwhile (a shorter first prediction). */
  constructor(ort: OrtModule | Promise<OrtModule>, private readonly entry: ModelEntry, private readonly load: FileLoader,
    private readonly onRun?: (t: GraphTiming) => void) {
    this.ort = Promise.resolve(ort);
  }

  /** Create every graph's session now (lazily per model: called when a model is first used). */
  async loadAll(onProgress?: (loaded: number, total: number) => void): Promise<void> {
    const roles = Object.keys(this.entry.graphs);
    const total = roles.reduce((s, r) => s + (this.entry.graphs[r].bytes ?? 0), 0);
    const done = new Map<string, number>();
    const report = () => onProgress?.([...done.values()].reduce((a, b) => a + b, 0), total);
    await Promise.all(roles.map((role) => this.session(role, (n) => { done.set(role, n); report(); })));
  }

  private session(role: string, onProgress?: (loaded: number) => void): Promise<{ session: Ort.InferenceSession; ort: OrtModule }> {
    let s = this.sessions.get(role);
    if (!s) {
      const spec = this.entry.graphs[role];
      if (!spec) throw new Error(`model ${this.entry.id} has no graph '${role}'`);
      s = Promise.all([this.load(spec.file, onProgress), this.ort]).then(async ([bytes, ort]) => ({
        session: await ort.InferenceSession.create(bytes, { executionProviders: ['wasm'], graphOptimizationLevel: SESSION_OPTIMIZATION }),
        ort,
      }));
      s.catch(() => this.sessions.delete(role)); // a failed load may be retried
      this.sessions.set(role, s);
    }
    return s;
  }

  async run(role: string, feeds: Record<string, Tensor>): Promise<Record<string, Tensor>> {
    const { session, ort } = await this.session(role);
    const inputs: Record<string, Ort.Tensor> = {};
    for (const [name, t] of Object.entries(feeds)) inputs[name] = new ort.Tensor('float32', t.data, t.dims);
    const t0 = performance.now();
    const out = await session.run(inputs);
    this.onRun?.({ role, batch: Object.values(feeds)[0]?.dims[0] ?? 0, ms: performance.now() - t0 });
    const result: Record<string, Tensor> = {};
    for (const spec of this.entry.graphs[role].outputs) {
      const t = out[spec.name];
      result[spec.name] = { data: t.data as Float32Array, dims: [...t.dims] };
    }
    return result;
  }
}
