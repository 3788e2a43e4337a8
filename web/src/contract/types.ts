// Types of the contract files; the JSON schemas in contract/ are the authority.

export interface Skeleton {
  joints: string[];
  parents: number[];
  offsets?: [number, number, number][];
}

export type Role = 'train' | 'train+test' | 'test';
export type Range = [number, number];

export interface ClipDoc {
  format: 'motion-futures/clip';
  /** 2 keeps the horizontal root translation (world frame); 1 files have the root above the origin. */
  version: 1 | 2;
  name: string;
  action: string;
  fps: number;
  loops: boolean;
  cycle_frames?: number;
  skeleton: Skeleton;
  split: { role: Role; train: Range[]; test: Range[] };
  source?: { dataset?: string; file?: string; license?: string };
  /** The person performing (the split keeps each person on one side), and the source's take name. */
  subject?: number | string;
  take?: string;
  positions: number[][][];
}

export interface ClipIndexEntry {
  name: string;
  file: string;
  action: string;
  loops: boolean;
  cycle_frames?: number;
  subject?: number | string;
  take?: string;
  dataset?: string;
  frames: number;
  role: Role;
  train: Range[];
  test: Range[];
}

export interface ClipIndex {
  format: 'motion-futures/clip-index';
  version: 1 | 2;
  fps: number;
  skeleton: Skeleton;
  split_rules: string[];
  data_hash?: string;
  /** The history the site opens on (a held-out take whose ground truth covers the default horizon). */
  default?: { clip: string; start: number };
  notes?: Record<string, string>;
  clips: ClipIndexEntry[];
}

export interface TensorSpec {
  name: string;
  shape: (number | string)[];
  dtype: 'float32' | 'int64';
}

export interface GraphSpec {
  file: string;
  bytes?: number;
  sha256?: string;
  inputs: TensorSpec[];
  outputs: TensorSpec[];
}

export interface ControlSpec {
  id: string;
  type: 'int' | 'number' | 'bool' | 'actions';
  label: string;
  help?: string;
  min?: number;
  max?: number;
  step?: number;
  max_length?: number;
  default: unknown;
}

export type Method = 'zero_velocity' | 'regression' | 'wat' | 'wat_transformer' | 'lcp_vae' | 'keyposes';

export interface ModelParams {
  history_frames: number;
  future_frames: number;
  latent_size?: number;
  stop?: { q: number; delta: number; min_frames: number };
  smoothness?: { l: number; m: number; flag_threshold?: number };
  [key: string]: unknown;
}

export interface ModelEntry {
  id: string;
  method: Method;
  label: string;
  description?: string;
  config?: string;
  hash: string;
  graphs: Record<string, GraphSpec>;
  files?: Record<string, string>;
  params: ModelParams;
  controls: ControlSpec[];
  metrics?: Record<string, unknown>;
}

export interface Manifest {
  format: 'motion-futures/manifest';
  version: 1;
  fps: number;
  skeleton: Skeleton;
  actions: string[];
  data_hash: string;
  /** The speed quantities and tempo_poses every model's envelope shares, stored once in the file;
   *  validate() puts them back into each model's params.envelope and drops this field. */
  speed_envelope?: Record<string, unknown>;
  models: ModelEntry[];
}
