// Messages between the page and the predictor worker.
import type { Manifest, Skeleton } from '../contract/types';
import type { StageReadout } from '../ui/readout';
import type { History, Prediction, PredictRequest } from './types';

/** What the stage's read-out needs besides the prediction and the history: the clip's frames after the
 *  history (any number) and the clip's skeleton. The worker computes the read-out, so K = 50's APD and
 *  ADE (about 45 ms) do not hold up the page's frames. */
export interface ReadoutInput { truth: Float32Array | null; skeleton: Skeleton }

/** One session.run: the graph's role, its batch (dim 0 of the first input) and its milliseconds. */
export interface GraphTiming { role: string; batch: number; ms: number }

export type ToWorker =
  // instrument: keep the wasm memory's handle and report its size with each result (bench/, memory test)
  | { type: 'init'; baseUrl: string; manifest: Manifest; instrument?: boolean }
  | { type: 'load'; id: number; model: string }
  | { type: 'predict'; id: number; view: string; model: string; history: History; request: PredictRequest; readout?: ReadoutInput };

export type ErrorKind = 'predict' | 'load' | 'superseded' | 'internal';

export type FromWorker =
  | { type: 'progress'; id: number; model: string; loaded: number; total: number }
  | { type: 'loaded'; id: number; model: string; ms: number }
  // timings: each graph call of this prediction; wasmBytes only when instrumented; readout when asked
  // (readoutError: why it could not be computed; the prediction still stands)
  | { type: 'result'; id: number; prediction: Prediction; ms: number; timings?: GraphTiming[]; wasmBytes?: number | null;
      readout?: StageReadout; readoutError?: string }
  | { type: 'error'; id: number; kind: ErrorKind; message: string };
