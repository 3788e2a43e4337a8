// The shape of public/results.json (written by export/eval/report.py) and a check that names
// what is missing, so a stale or broken file gives a readable message on the page.

/** mean over runs ± std: the cluster bootstrap (people, then takes within people) and the seed std (over runs) combined. */
export interface Stat { mean: number; std: number; n: number; seed_std?: number; boot_std?: number }

export interface Row {
  id: string;
  label: string;
  kind: 'model' | 'oracle' | 'noise' | 'baseline' | 'projected';
  group: string;
  note: string;
  notes: string[];
  skipped?: string;
  runs?: number;
  k?: number;
  items?: number;
  history_frames?: number | null;
  parent?: string;
  values?: Record<string, Stat>;
  by_action?: Record<string, Record<string, number>>;
  intervals?: Record<string, [number, number]>;
  lengths?: Record<string, number[]>;
  hashes?: Record<string, string>;
  /** Why the row's futures are not predictions (the guard cuts >5% of samples, or they last < half the horizon). */
  flag?: string;
  /** Windows the row refuses (Keyposes: too little motion in the history), of the table's. */
  refused?: { items: number; of: number; share: number };
  /** For a row that refuses windows: its, the truth's and the baselines' values on exactly the windows it accepts. */
  paired?: { items: number; rows: Record<string, Record<string, number | null>> };
  /** Values per action group (walk, run, jump, dance, other), each over the group's own windows. */
  by_group?: Record<string, { items: number; people: number; takes: number; values: Record<string, Stat> }>;
}

export interface Table {
  id: string;
  title: string;
  about: string;
  source: string;
  history_frames: number | null;   // every row reads the last frames of its own history length
  context_frames?: number;
  horizon_frames: number;
  truth: boolean;
  k: number;
  windows: number | null;
  items?: number;
  takes?: number;
  people?: string[];
  in_sample?: boolean;
  exceptions?: { action: string; horizon_frames: number }[];
  mmade?: { threshold: number; median_set: number; alone: number;
    half: { threshold: number; median_set: number; alone: number }; double: { threshold: number; median_set: number; alone: number } };
  clips: string[];
  actions: string[];
  columns: string[];
  extra_columns?: string[];
  length_edges: number[];
  rows: Row[];
  notes: string[];
}

export interface ClaimPart {
  table: string; a: string; b: string; metric: string; metric_b: string; direction: string; status: string;
  a_value: Stat | null; b_value: Stat | null; difference: number | null; bar: number | null; missing: string[];
  margin?: number; people?: number; takes?: number; items?: number; a_paired?: number; b_paired?: number; reason?: string;
  /** One-sided p, its Holm-adjusted value (in the comparison's family), what the data alone say of an unusable part. */
  p?: number | null; p_holm?: number; data_status?: string; minimum?: number;
  kind?: 'trend'; setting?: string; settings?: number[]; values?: number[];
}

/** A claim's status: holds, fails, inconclusive, no difference, insufficient data, unusable, not evaluated or by construction. */
export interface Claim { id: string; paper: string; text: string; status: string; reason?: string; data_status?: string; parts: ClaimPart[] }

/** A served learned model against a baseline in one held-out table (the copying family's status, after Holm). */
export interface Verdict {
  row: string; table: string; baseline: string; status: string; label: string; baseline_label: string;
  difference: number | null; bar: number | null; a_paired: number | null; b_paired: number | null; items: number;
}

export interface DataSide { people: string[]; takes: number; seconds: number }

/** What the tables are cut from and the models learn from (results.data). */
export interface DataSummaryDoc {
  fps: number; joints: number; clips: number; actions: number;
  heldout_people: string[]; heldout_takes: number; heldout_actions: string[]; heldout_seconds: number;
  train_people: number; train_people_list?: string[]; train_takes: number; train_seconds: number;
  per_action?: Record<string, { group: string; train: DataSide; test: DataSide }>;
  groups?: string[]; balance?: string; train_only_actions?: string[];
}

export interface Sanity {
  id: string; table: string | null; text: string; expected: number | null; measured: number; passed: boolean;
  metric?: string; low?: number; high?: number;
}

/** A model against a baseline that copies (repeat the last cycle) or memorises (the nearest training window). */
export interface Copying extends ClaimPart { row: string; label: string; baseline: string; baseline_label: string; verdict: string }

/** Issue 17's shape terms: a model with and without them. */
export interface ShapeRow {
  table: string; with: string; without: string; metric: string; with_value: Stat; without_value: Stat;
  ratio: number; within: boolean; tolerance: number; difference: number | null; bar: number | null;
  /** Set when either row does not predict: then never "within". */
  flag?: string;
}

export interface ClassifierReport {
  train_accuracy: number;
  test_accuracy: number;
  test_balanced_accuracy: number;
  motionless_class?: string | null;
  test_groups: Record<string, { accuracy: number; snippets: number; predicted?: Record<string, number> }>;
  classes: number;
  chance: number;
  train_snippets: number;
  test_snippets: number;
  selection?: { chosen: string; people: string[]; steps: number; candidates: { name: string; score: number; folds: Record<string, number> }[] };
}

export interface Column { label: string; unit: string; better: 'lower' | 'higher' | '' }

export interface Results {
  format: 'motion-futures/results';
  columns: Record<string, Column>;
  version: number;
  k: number;
  fps: number;
  training_seeds: number[];
  sampling_seeds: number[];
  models: Record<string, string>;
  classifiers: Record<string, ClassifierReport>;
  classifier_config: { snippet_frames: number };
  sanity: Sanity[];
  claims: Claim[];
  copying?: Copying[];
  shape?: ShapeRow[];
  variants?: { eq4: { table: string; printed: string[]; code: string[]; same_order: boolean }[];
    keypose_rules: Record<string, { mean: number; max: number; histories: number }>; keypose_history_frames: number };
  tally?: Record<string, number>;
  bootstrap?: { rounds: number; seed: number };
  min_people?: number;
  min_takes?: number;
  /** How many comparisons each Holm family holds, and the correction. */
  comparisons?: { claims: number; copying: number; correction: string };
  served_learned?: string[];
  verdicts?: Verdict[];
  data?: DataSummaryDoc;
  classifier_seconds?: number;
  tables: Table[];
  skipped: { row: string; label: string; reason: string }[];
  context_plot: string[];
  length_plot: string | null;
  seconds: number;
  /** The model card's short summary (at most five lines), when the evaluation writes one. */
  summary?: string[];
}

export class ResultsError extends Error {}

function need(ok: boolean, what: string): void {
  if (!ok) throw new ResultsError(`results.json: ${what}`);
}

/** Check the fields the page reads; throws ResultsError naming the first problem. */
export function parseResults(doc: unknown): Results {
  need(typeof doc === 'object' && doc !== null, 'not a JSON object');
  const r = doc as Partial<Results>;
  need(r.format === 'motion-futures/results', `format must be "motion-futures/results", got ${JSON.stringify(r.format)}`);
  need(r.version === 1 || r.version === 2, `unsupported version ${JSON.stringify(r.version)}`);
  for (const key of ['tables', 'claims', 'sanity', 'skipped'] as const) need(Array.isArray(r[key]), `field ${key} must be a list`);
  need(typeof r.classifiers === 'object' && r.classifiers !== null, 'field classifiers is missing');
  need(typeof r.columns === 'object' && r.columns !== null, 'field columns is missing');
  need(r.summary === undefined || (Array.isArray(r.summary) && r.summary.every((l) => typeof l === 'string')), 'field summary must be a list of strings');
  r.tables!.forEach((t, i) => {
    need(typeof t.id === 'string' && Array.isArray(t.rows) && Array.isArray(t.columns), `table ${i} lacks id, rows or columns`);
    for (const c of t.columns) need(c in r.columns!, `table ${t.id} has unknown column ${c}`);
    t.rows.forEach((row, j) => need(typeof row.id === 'string' && typeof row.label === 'string',
      `table ${t.id} row ${j} lacks id or label`));
  });
  return r as Results;
}
