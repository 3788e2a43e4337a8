// The predictor contract, twin of export/sample/request.py. Every method implements Predictor,
// so the UI never branches on the method: a history and a request in, K futures out.
import type { ModelEntry, Skeleton } from '../contract/types';

export interface Tensor {
  data: Float32Array;
  dims: number[];
}

/** Runs one of a model's graphs (by its role in the manifest) on named float32 inputs. */
export interface GraphRunner {
  run(role: string, feeds: Record<string, Tensor>): Promise<Record<string, Tensor>>;
}

/** A motion window in the world frame: [frames, joints, 3] metres; the root keeps its horizontal travel. */
export interface History {
  positions: Float32Array;
  frames: number;
  joints: number;
}

export interface PredictRequest {
  k: number;
  seed: number;
  actions?: string[];
  horizonFrames?: number;
  controls?: Record<string, number | boolean>;
  /** Feet on the floor carry the root (foot-plant.ts); false keeps the method's own root travel. */
  plantFeet?: boolean;
}

export interface Segment {
  start: number;
  length: number;
  action?: string;
  stopped?: boolean;
  smoothness?: number;
  flagged?: boolean;
}

export interface SampleInfo {
  length: number;
  /** False when a variable-length sample never met its stop rule and kept the maximum length. */
  stopped: boolean;
  segments: Segment[];
  /** Frames to mark on the timeline (e.g. keypose times), relative to the future's first frame. */
  marks?: number[];
  /** Discrete choices the sampler made (e.g. keypose cluster labels), for display and test vectors. */
  labels?: number[];
  /** Set when the sample broke a bound (non-finite values, a bone far from its length, a joint far
   *  from the root) and was cut at its last good frame; separate from Eq. 8's `stopped`. */
  cut?: { frame: number; reason: 'cut: out of bounds'; detail: string };
}

/** A history quantity outside the model's training envelope (issue 19): named, with its value and range. */
export interface RangeWarning {
  quantity: string;
  value: number;
  min: number;
  max: number;
  unit?: string;
  /** One sentence for the stage. */
  message: string;
}

/** A per-sample curve for a small plot, e.g. WAT's variance v_i with delta and T_min marked. */
export interface Curve {
  id: string;
  title: string;
  /** One series per sample, indexed by future frame. */
  series: Float32Array[];
  /** Horizontal rules (e.g. the stop threshold delta). */
  levels?: { label: string; value: number }[];
  /** Vertical rules (e.g. the minimum length T_min). */
  frames?: { label: string; frame: number }[];
  log?: boolean;
}

/** Poses to show as ghost skeletons at given future frames, per sample (e.g. keypose centres). */
export interface Ghosts {
  frames: number[][];
  /** Per sample: [frames.length, joints, 3]. */
  poses: Float32Array[];
}

export interface Prediction {
  k: number;
  /** Frames per future (the longest sample); shorter samples hold their last pose. */
  frames: number;
  joints: number;
  /** [k, frames, joints, 3] metres, world frame. */
  futures: Float32Array;
  lengths: Int32Array;
  samples: SampleInfo[];
  notes: string[];
  curves?: Curve[];
  ghosts?: Ghosts;
  /** Short measured read-outs, e.g. { label: 'diversity', value: 0.41, unit: 'm', about: '…' }; `about`
   *  is the one-line explanation the page shows on hover and focus. */
  readouts?: { label: string; value: number; unit?: string; about?: string }[];
  /** Distance of each thresholded decision (stop tests, sampled uniforms) to its threshold. */
  margins?: number[];
  /** History quantities outside the training envelope; the prediction is still made, marked as out of range. */
  warnings?: RangeWarning[];
}

export interface Predictor {
  readonly entry: ModelEntry;
  predict(history: History, request: PredictRequest, isCancelled?: () => boolean): Promise<Prediction>;
}

/** Reads one of the model's files (named in the manifest) as bytes. */
export type FileLoader = (file: string, onProgress?: (loaded: number) => void) => Promise<Uint8Array>;

export interface PredictorContext {
  entry: ModelEntry;
  skeleton: Skeleton;
  actions: string[];
  fps: number;
  runner: GraphRunner;
  /** For non-graph artefacts such as keypose centres. */
  loadFile: FileLoader;
}

export class PredictError extends Error {
  constructor(message: string) {
    super(message);
    this.name = 'PredictError';
  }
}

/** Thrown between graph calls when a newer request from the same view replaced this one. */
export class Superseded extends Error {
  constructor() {
    super('superseded by a newer request');
    this.name = 'Superseded';
  }
}
