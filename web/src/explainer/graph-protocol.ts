// Messages between the explainer page and its graph worker (graph-worker.ts).
import type { Manifest } from '../contract/types';
import type { Tensor } from '../predictor/types';

export type ToGraphWorker =
  | { type: 'init'; baseUrl: string; manifest: Manifest }
  | { type: 'run'; id: number; model: string; role: string; feeds: Record<string, Tensor> };

export type FromGraphWorker =
  | { type: 'result'; id: number; outputs: Record<string, Tensor> }
  | { type: 'error'; id: number; message: string };
