// Compare mode (issue 29 item 2): 2-3 models on the same history end, seed, K and horizon, one row per
// method on stage, each with its own read-out. The pure parts: which models a link or the panel asks
// for, each model's controls taken from the page's, and the tracks of every row on one timeline.
// The page's model is the first row; its futures are the ones the Futures list and Share describe,
// while the export and the closest-to-truth highlight cover every row.
import type { ModelEntry } from '../contract/types';
import type { RunPrediction } from '../export/shown';
import { window as clipWindow, type Motion } from '../motion/clip';
import type { Prediction } from '../predictor/types';
import { sampleTrackInfo, type Track } from '../viewer/tracks';
import type { ControlValue } from './controls';
import type { StageReadout } from './readout';

/** Models on stage at once in compare mode, the page's own included. */
export const MAX_COMPARED = 3;

/** Controls the other rows take from the page's model, when they have them: the rest keep their defaults. */
export const SHARED_CONTROLS = ['k', 'horizon'];

/** One method's row: its futures, or why it has none. */
export interface CompareRow {
  entry: ModelEntry;
  /** First frame of this model's history: its own history length, ending where the page's ends. */
  start: number;
  controls: Record<string, ControlValue>;
  /** Whether the feet carried the root (the page's foot-planting option, the same for every row). */
  plantFeet: boolean;
  prediction?: Prediction;
  readout?: StageReadout | null;
  /** Why this model shows no futures (a refusal, a clip too short for its history). */
  error?: string;
}

/**
 * The models a compare list names, in its order: known ids, each once, at most MAX_COMPARED, with a
 * sentence for each id dropped. Fewer than two known models is no comparison (an empty list).
 */
export function parseCompare(text: string, models: readonly ModelEntry[]): { ids: string[]; problems: string[] } {
  const asked = text.split(',').map((s) => s.trim()).filter(Boolean);
  const problems: string[] = [];
  const ids: string[] = [];
  const unknown = asked.filter((id) => !models.some((m) => m.id === id));
  if (unknown.length) {
    problems.push(`This link compares ${unknown.map((id) => `'${id}'`).join(', ')}, which this site does not serve `
      + `(it serves ${models.map((m) => m.id).join(', ')}).`);
  }
  for (const id of asked) if (!unknown.includes(id) && !ids.includes(id)) ids.push(id);
  if (ids.length > MAX_COMPARED) {
    problems.push(`Compare mode shows at most ${MAX_COMPARED} models; showing ${ids.slice(0, MAX_COMPARED).join(', ')}.`);
    ids.length = MAX_COMPARED;
  }
  if (ids.length < 2) {
    if (asked.length) problems.push(`Compare mode needs two models this site serves; the link names ${ids.length ? `only ${ids[0]}` : 'none'}, so one model is shown.`);
    return { ids: [], problems };
  }
  return { ids, problems };
}

/** The nearest value of `spec`'s range and grid to `v`. */
function fit(v: number, spec: ModelEntry['controls'][number]): number {
  let x = Math.max(spec.min ?? -Infinity, Math.min(spec.max ?? Infinity, v));
  if (spec.step) x = (spec.min ?? 0) + Math.round((x - (spec.min ?? 0)) / spec.step) * spec.step;
  if (spec.type === 'int') x = Math.round(x);
  return Number(x.toPrecision(12));
}

/** A row's control values: its defaults, with K and the horizon of the page's model where it has them
 *  (within its own range). A deterministic model has no K: it shows one future. */
export function rowControls(entry: ModelEntry, page: Record<string, ControlValue>): Record<string, ControlValue> {
  const out: Record<string, ControlValue> = {};
  for (const spec of entry.controls) {
    const mine = page[spec.id];
    if (SHARED_CONTROLS.includes(spec.id) && typeof mine === 'number') out[spec.id] = fit(mine, spec);
    else if (spec.default !== undefined) out[spec.id] = spec.default as ControlValue;
  }
  return out;
}

/** The history start of a model with `frames` of history ending where the page's ends (null: the clip
 *  holds fewer frames before that end). */
export function rowStart(pageStart: number, pageFrames: number, frames: number): number | null {
  const start = pageStart + pageFrames - frames;
  return start >= 0 ? start : null;
}

/**
 * Every row's tracks on one timeline: the futures of all rows start at the same frame (the longest
 * history's length), each history ends there, and each row's figures carry its model's name.
 */
export function compareTracks(m: Motion, rows: readonly CompareRow[]): { tracks: Track[]; origin: number } {
  const shown = rows.filter((r) => r.prediction);
  const origin = Math.max(...shown.map((r) => r.entry.params.history_frames));
  const tracks: Track[] = [];
  rows.forEach((r, group) => {
    const p = r.prediction;
    if (!p) return;
    const n = r.entry.params.history_frames;
    const name = shortLabel(r.entry);
    const stride = p.joints * 3;
    tracks.push({ id: `history:${group}`, role: 'history', positions: clipWindow(m, r.start, n), frames: n, joints: p.joints,
      startFrame: origin - n, label: 'history', group, groupLabel: name });
    const truthFrames = Math.min(m.frames - r.start - n, Math.max(...p.lengths));
    if (truthFrames > 0) {
      tracks.push({ id: `truth:${group}`, role: 'truth', positions: clipWindow(m, r.start + n, truthFrames), frames: truthFrames,
        joints: p.joints, startFrame: origin, label: 'ground truth', group, groupLabel: name });
    }
    for (let i = 0; i < p.k; i++) {
      const len = p.lengths[i];
      const from = i * p.frames * stride;
      tracks.push({
        id: `sample:${group}:${i}`, role: 'prediction', positions: p.futures.slice(from, from + len * stride), frames: len,
        joints: p.joints, startFrame: origin, sample: i, label: `#${i + 1}`, cut: Boolean(p.samples[i]?.cut), group, groupLabel: name,
        ...sampleTrackInfo(p.samples[i]),
      });
    }
  });
  return { tracks, origin };
}

/** The rows with futures as an export's runs, in row order: what each model was asked, so the export
 *  can make them again. The page's model alone is one row (single view and compare: one path). */
export function exportRuns(rows: readonly CompareRow[], seed: number): RunPrediction[] {
  return rows.flatMap((r) => (r.prediction ? [{
    model: r.entry.id, hash: r.entry.hash, label: shortLabel(r.entry), start: r.start, historyFrames: r.entry.params.history_frames,
    seed, controls: r.controls, plantFeet: r.plantFeet, prediction: r.prediction,
  }] : []));
}

/** A model's name without its description, after a colon or in a parenthesis of several words
 *  ("WAT (RNN): action sequences" -> "WAT (RNN)", "LCP-VAE (learned conditional prior)" -> "LCP-VAE"):
 *  figure labels stay short enough to sit over their figures, six or more to a row. */
export function shortLabel(entry: Pick<ModelEntry, 'label'>): string {
  const name = entry.label.split(':')[0].trim();
  return name.replace(/\s*\([^()]*\s[^()]*\)$/, '').trim() || name;
}

/** "8.1 cm" from a read-out's per-joint error, best of K (null: no ground truth covers the futures). */
export function rowNumbers(r: CompareRow): { perJointCm: number | null; spreadCm: number | null; k: number } | null {
  if (!r.prediction) return null;
  const ro = r.readout;
  return {
    k: r.prediction.k,
    perJointCm: ro?.bestPerJointCm?.ade ?? null,
    spreadCm: ro && r.prediction.k > 1 ? ro.spreadCm.overFrames : null,
  };
}
