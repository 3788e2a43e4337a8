// Messages between the page and the predictor worker.
import type { Manifest } from '../contract/types';
import type { History, Prediction, PredictRequest } from './types';

export type ToWorker =
  | { type: 'init'; baseUrl: string; manifest: Manifest }
  | { type: 'load'; id: number; model: string }
  | { type: 'predict'; id: number; view: string; model: string; history: History; request: PredictRequest };

export type ErrorKind = 'predict' | 'load' | 'superseded' | 'internal';

export type FromWorker =
  | { type: 'progress'; id: number; model: string; loaded: number; total: number }
  | { type: 'loaded'; id: number; model: string; ms: number }
  | { type: 'result'; id: number; prediction: Prediction; ms: number }
  | { type: 'error'; id: number; kind: ErrorKind; message: string };
