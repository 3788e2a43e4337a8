// Messages between the page and the predictor worker.
import type { Manifest } from '../contract/types';
import type { History, Prediction, PredictRequest } from './types';

/** One session.run: the graph's role, its batch (dim 0 of the first input) and its milliseconds. */
export interface GraphTiming { role: string; batch: number; ms: number }

export type ToWorker =
  // instrument: keep the wasm memory's handle and report its size with each result (bench/, memory test)
  | { type: 'init'; baseUrl: string; manifest: Manifest; instrument?: boolean }
  | { type: 'load'; id: number; model: string }
  | { type: 'predict'; id: number; view: string; model: string; history: History; request: PredictRequest };

export type ErrorKind = 'predict' | 'load' | 'superseded' | 'internal';

export type FromWorker =
  | { type: 'progress'; id: number; model: string; loaded: number; total: number }
  | { type: 'loaded'; id: number; model: string; ms: number }
  // timings: each graph call of this prediction; wasmBytes only when instrumented
  | { type: 'result'; id: number; prediction: Prediction; ms: number; timings?: GraphTiming[]; wasmBytes?: number | null }
  | { type: 'error'; id: number; kind: ErrorKind; message: string };
