// Messages between the benchmark page and its graph-timing worker (web/src/bench/graph-worker.ts).

export interface Feed {
  dims: number[];
  data: Float32Array;
  type?: 'float32';
}

export interface GraphJob {
  id: number;
  /** The ONNX file. */
  bytes: ArrayBuffer;
  feeds: Record<string, Feed>;
  warmup: number;
  /** Keep warming up until this long has passed too (ms). */
  warmupMs?: number;
  runs: number;
  /** Session graph optimisation level (default: the site's, predictor/ort-runner.ts SESSION_OPTIMIZATION; the
   *  levels are spelt out here because the bench page's main thread may not import ort-runner, which imports onnxruntime). */
  optimization?: 'disabled' | 'basic' | 'extended' | 'all';
  /** Also return onnxruntime's per-node profile events (runs are slower then). */
  profile?: boolean;
  /** Return the first run's outputs (to check a variant against the served graph). */
  keepOutputs?: boolean;
}

export interface GraphResult {
  id: number;
  loadMs?: number;
  /** Per timed sample: the mean of `reps` back-to-back runs (ms). */
  runMs?: number[];
  reps?: number;
  warmupRuns?: number;
  outputs?: Record<string, number[]>;
  profile?: unknown[];
  error?: string;
}
