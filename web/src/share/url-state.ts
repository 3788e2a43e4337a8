// The whole prediction state as URL parameters (permalinks) or element attributes (embeds):
// site version, model and its hash, clip and history start, seed, and every control the
// manifest declares for the model. Generic over the manifest: nothing here knows a method.
//
// Format (one name per field; controls by their manifest id, verbatim):
//   v=0.1.0 &model=ID &hash=<first 12 hex of the model's sha256> &clip=NAME &start=F &seed=S
//   &<control id>=VALUE ...   int/number: decimal; bool: 1|0; actions: comma-separated names
//   &sample=N &frame=F &layout=overlay|side   what the stage shows of it (each optional): the selected
//   sample as the labels number it (#N, from 1), the paused timeline frame, the layout
//   &compare=ID,ID[,ID]   compare mode (ui/compare.ts): every model on stage, the link's model first
//   &feet=own   the method's own root travel (absent: planted feet, predictor/foot-plant.ts)
//   &camera=front|side|top|follow &closest=1 &truth=0   the stage bar (ui/stage-view.ts), each optional
import type { ControlSpec, Manifest, ModelEntry } from '../contract/types';
import { MAX_SEED } from '../rng/prng';
import type { ControlValue } from '../ui/controls';
import type { LayoutMode } from '../viewer/layout';
import { CAMERA_PRESETS, type CameraPreset } from '../viewer/viewer';
import { MAX_COMPARED, parseCompare } from '../ui/compare';

export type { ControlValue };

/** Where the history comes from. A dropped file never leaves the computer, so it has no link. */
export type HistorySource =
  | { kind: 'clip' }
  | { kind: 'dropped'; name: string };

/** Everything a permalink reproduces. */
export interface ShareState {
  /** Site version that made the link (package.json version). */
  version: string;
  model: string;
  /** First HASH_CHARS hex digits of the model's manifest hash. */
  hash: string;
  clip: string;
  start: number;
  seed: number;
  /** One value per control the model declares, keyed by control id. */
  controls: Record<string, ControlValue>;
  /** Default: a clip. A dropped file makes the state unlinkable. */
  source?: HistorySource;
  /** What the stage shows of the prediction; each part is optional. */
  view?: StageView;
  /** Compare mode: every model on stage, `model` first (absent: one model). */
  compare?: string[];
  /** 'own': the method's own root travel; absent: feet on the floor carry the root. */
  feet?: FeetMode;
}

/** How the root travels: planted feet (the site's default, predictor/foot-plant.ts) or the method's own. */
export type FeetMode = 'planted' | 'own';
export const FEET_MODES: readonly FeetMode[] = ['planted', 'own'];

export const LAYOUTS: readonly LayoutMode[] = ['overlay', 'side'];

/** The selected sample (0-based; the link writes it from 1, as the labels number it), the paused
 *  timeline frame (history frames first), and the layout. */
export interface StageView {
  sample?: number;
  frame?: number;
  layout?: LayoutMode;
  /** The stage bar (ui/stage-view.ts): a camera other than "fit all", the closest sample highlighted,
   *  the ground truth hidden. */
  camera?: CameraPreset;
  closest?: boolean;
  truth?: boolean;
}

/** The model the page opens on, and what a link naming no model (or an unknown one) shows: WAT
 *  (action-conditioned, stochastic, variable length), else the first model that draws K samples,
 *  else the first one. */
export function stageModel(manifest: Manifest): ModelEntry {
  return manifest.models.find((m) => m.method === 'wat')
    ?? manifest.models.find((m) => m.controls.some((c) => c.id === 'k'))
    ?? manifest.models[0];
}

/** What a link or an embed's attributes ask for; anything absent keeps the page's default. */
export interface LinkState {
  version?: string;
  model: string;
  hash?: string;
  clip?: string;
  start?: number;
  seed?: number;
  controls: Record<string, ControlValue>;
  view?: StageView;
  /** Compare mode: the models on stage, `model` first. */
  compare?: string[];
  feet?: FeetMode;
}

export interface Problem {
  level: 'warning' | 'info';
  text: string;
}

export const HASH_CHARS = 12;
/** Names of the state's own fields, and of the view options that share the same parameter space. */
export const STATE_KEYS = ['v', 'model', 'hash', 'clip', 'start', 'seed', 'sample', 'frame', 'layout', 'compare', 'feet', 'camera', 'closest', 'truth'] as const;
export const VIEW_KEYS = ['controls', 'autoplay', 'predict', 'page'] as const;
const RESERVED = new Set<string>([...STATE_KEYS, ...VIEW_KEYS]);
/** The action-sequence composer's length when the manifest gives no max_length (controls.ts). */
export const DEFAULT_MAX_ACTIONS = 5;

export class UrlStateError extends Error {
  constructor(message: string) {
    super(message);
    this.name = 'UrlStateError';
  }
}

/** The short hash a link carries for a manifest hash 'sha256:<hex>'. */
export function shortHash(hash: string): string {
  return hash.replace(/^sha256:/, '').slice(0, HASH_CHARS);
}

function checkIds(entry: ModelEntry): void {
  for (const spec of entry.controls) {
    if (RESERVED.has(spec.id)) {
      throw new UrlStateError(`model ${entry.id} declares a control '${spec.id}', a name links reserve for their own fields`);
    }
  }
}

function onGrid(v: number, spec: ControlSpec): boolean {
  if (!spec.step) return true;
  const k = (v - (spec.min ?? 0)) / spec.step;
  return Math.abs(k - Math.round(k)) <= 1e-6;
}

/** Why a control value is not valid for its spec, or null when it is. */
export function controlProblem(spec: ControlSpec, value: ControlValue, actions: readonly string[]): string | null {
  const name = `${spec.label} (${spec.id})`;
  if (spec.type === 'actions') {
    if (!Array.isArray(value)) return `${name} must be a list of actions`;
    const max = spec.max_length ?? DEFAULT_MAX_ACTIONS;
    if (value.length > max) return `${name} takes at most ${max} actions, got ${value.length}`;
    const bad = value.find((a) => !actions.includes(a));
    return bad === undefined ? null : `${name}: unknown action '${bad}'`;
  }
  if (spec.type === 'bool') return typeof value === 'boolean' ? null : `${name} must be 1 or 0`;
  if (typeof value !== 'number' || !Number.isFinite(value)) return `${name} must be a number`;
  if (spec.type === 'int' && !Number.isInteger(value)) return `${name} must be a whole number, got ${value}`;
  if ((spec.min !== undefined && value < spec.min) || (spec.max !== undefined && value > spec.max)) {
    return `${name} must be between ${spec.min ?? '-∞'} and ${spec.max ?? '∞'}, got ${value}`;
  }
  if (!onGrid(value, spec)) return `${name} must be ${spec.min ?? 0} plus a multiple of ${spec.step}, got ${value}`;
  return null;
}

function encodeValue(spec: ControlSpec, value: ControlValue): string {
  if (spec.type === 'actions') return (value as string[]).join(',');
  if (spec.type === 'bool') return value ? '1' : '0';
  return String(value); // shortest round-trip decimal of the double
}

/** Parse one control's text; throws a message naming the control when it does not parse. */
function decodeValue(spec: ControlSpec, text: string): ControlValue {
  const name = `${spec.label} (${spec.id})`;
  if (spec.type === 'actions') return text.split(',').map((a) => a.trim()).filter(Boolean);
  if (spec.type === 'bool') {
    // '' is an attribute given without a value (<motion-futures refine>).
    if (['1', 'true', ''].includes(text)) return true;
    if (['0', 'false'].includes(text)) return false;
    throw new Error(`${name} must be 1 or 0, got '${text}'`);
  }
  const re = spec.type === 'int' ? /^[-+]?\d+$/ : /^[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$/;
  if (!re.test(text.trim())) throw new Error(`${name} must be ${spec.type === 'int' ? 'a whole number' : 'a number'}, got '${text}'`);
  const v = Number(text);
  return Object.is(v, -0) ? 0 : v;
}

/** Check a complete state against the model; throws UrlStateError naming the first problem. */
export function validateState(state: ShareState, manifest: Manifest): ModelEntry {
  const entry = manifest.models.find((m) => m.id === state.model);
  if (!entry) throw new UrlStateError(`this site serves no model '${state.model}'`);
  checkIds(entry);
  if (!/^[0-9a-f]+$/.test(state.hash)) throw new UrlStateError(`the model hash must be hex digits, got '${state.hash}'`);
  if (!state.clip) throw new UrlStateError('the clip name is empty');
  if (!Number.isInteger(state.start) || state.start < 0) throw new UrlStateError(`the history start must be a frame number, got ${state.start}`);
  if (!Number.isInteger(state.seed) || state.seed < 0 || state.seed > MAX_SEED) {
    throw new UrlStateError(`the seed must be an integer from 0 to ${MAX_SEED}, got ${state.seed}`);
  }
  for (const spec of entry.controls) {
    if (!(spec.id in state.controls)) throw new UrlStateError(`the state has no value for ${spec.label} (${spec.id})`);
    const p = controlProblem(spec, state.controls[spec.id], manifest.actions);
    if (p) throw new UrlStateError(p);
  }
  const extra = Object.keys(state.controls).find((id) => !entry.controls.some((c) => c.id === id));
  if (extra) throw new UrlStateError(`${entry.label} has no control '${extra}'`);
  const v = state.view ?? {};
  const k = typeof state.controls.k === 'number' ? state.controls.k : 1;
  if (v.sample !== undefined && !(Number.isInteger(v.sample) && v.sample >= 0 && v.sample < k)) {
    throw new UrlStateError(`the selected sample must be one of #1–#${k}, got ${v.sample + 1}`);
  }
  if (v.frame !== undefined && !(Number.isInteger(v.frame) && v.frame >= 0)) throw new UrlStateError(`the frame must be a frame number, got ${v.frame}`);
  if (v.layout !== undefined && !LAYOUTS.includes(v.layout)) throw new UrlStateError(`the layout must be ${LAYOUTS.join(' or ')}, got '${v.layout}'`);
  if (v.camera !== undefined && !CAMERA_PRESETS.includes(v.camera)) throw new UrlStateError(`the camera must be ${CAMERA_PRESETS.join(', ')}, got '${v.camera}'`);
  if (state.compare !== undefined) {
    const c = state.compare;
    const bad = c.find((id) => !manifest.models.some((m) => m.id === id));
    if (bad !== undefined) throw new UrlStateError(`compare mode names '${bad}', which this site does not serve`);
    if (c.length < 2 || c.length > MAX_COMPARED || new Set(c).size !== c.length || c[0] !== state.model) {
      throw new UrlStateError(`compare mode takes 2 to ${MAX_COMPARED} different models, the link's model first, got ${c.join(',')}`);
    }
  }
  return entry;
}

/** Why this state cannot become a link, or null when it can. */
export function unlinkableReason(state: Pick<ShareState, 'source'>): string | null {
  if (state.source?.kind === 'dropped') {
    return `The history comes from a dropped file (${state.source.name}), which stays on this computer, so it cannot be linked. Pick a clip to share a link.`;
  }
  return null;
}

/** The state as ordered name/value pairs (URL parameters or element attributes). */
export function encodeState(state: ShareState, manifest: Manifest): [string, string][] {
  const why = unlinkableReason(state);
  if (why) throw new UrlStateError(why);
  const entry = validateState(state, manifest);
  const out: [string, string][] = [
    ['v', state.version], ['model', state.model], ['hash', state.hash], ['clip', state.clip],
    ['start', String(state.start)], ['seed', String(state.seed)],
  ];
  for (const spec of entry.controls) out.push([spec.id, encodeValue(spec, state.controls[spec.id])]);
  const v = state.view ?? {};
  if (v.sample !== undefined) out.push(['sample', String(v.sample + 1)]);
  if (v.frame !== undefined) out.push(['frame', String(v.frame)]);
  if (v.layout !== undefined) out.push(['layout', v.layout]);
  if (v.camera !== undefined && v.camera !== 'auto') out.push(['camera', v.camera]);
  if (v.closest) out.push(['closest', '1']);
  if (v.truth === false) out.push(['truth', '0']);
  if (state.compare?.length) out.push(['compare', state.compare.join(',')]);
  if (state.feet === 'own') out.push(['feet', 'own']);
  return out;
}

export function encodeSearch(state: ShareState, manifest: Manifest): string {
  return new URLSearchParams(encodeState(state, manifest)).toString();
}

function wholeNumber(text: string, max = Number.MAX_SAFE_INTEGER): number | null {
  if (!/^\d+$/.test(text.trim())) return null;
  const v = Number(text);
  return v <= max ? v : null;
}

export interface Decoded {
  state: LinkState;
  problems: Problem[];
}

/**
 * Read what a link asks for. Invalid fields are left out (the page keeps its default for them)
 * and each is named in `problems`, as is a link made against another model or site version.
 * `reportUnknown` names parameters that are neither state, view option nor any model's control.
 */
export function decodeState(params: Iterable<[string, string]>, manifest: Manifest, siteVersion: string,
  options: { reportUnknown?: boolean } = {}): Decoded {
  const q = new Map<string, string>();
  for (const [k, v] of params) q.set(k, v);
  const problems: Problem[] = [];
  const warn = (text: string) => problems.push({ level: 'warning', text });
  if (!manifest.models.length) throw new UrlStateError('the manifest lists no models');

  const asked = q.get('model');
  let entry = asked === undefined ? stageModel(manifest) : manifest.models.find((m) => m.id === asked);
  if (!entry) {
    entry = stageModel(manifest);
    warn(`This link asks for the model '${asked}', which this site does not serve; showing ${entry.label} instead, so the futures differ from the linked ones.`);
  }
  checkIds(entry);
  const state: LinkState = { model: entry.id, controls: {} };

  const version = q.get('v');
  if (version !== undefined) state.version = version;
  const hash = q.get('hash');
  if (hash !== undefined) {
    state.hash = hash;
    if (asked === entry.id && hash !== shortHash(entry.hash)) {
      warn(`This link was made with a different ${entry.label} (model hash ${hash}; this site's is ${shortHash(entry.hash)}). `
        + `The futures shown come from this site's model and will differ from the linked ones.`);
    }
  }
  if (version !== undefined && version !== siteVersion) {
    const sameModel = hash !== undefined && asked === entry.id && hash === shortHash(entry.hash);
    problems.push({
      level: sameModel ? 'info' : 'warning',
      text: `This link was made with motion-futures ${version}; this site is ${siteVersion}.`
        + (sameModel ? ' The model is the same, so the futures should match.' : ''),
    });
  }

  const clip = q.get('clip');
  if (clip !== undefined) { if (clip) state.clip = clip; else warn('The link has an empty clip name; showing the default clip.'); }
  const start = q.get('start');
  if (start !== undefined) {
    const v = wholeNumber(start);
    if (v === null) warn(`The history start must be a frame number, got '${start}'; using the default.`);
    else state.start = v;
  }
  const seed = q.get('seed');
  if (seed !== undefined) {
    const v = wholeNumber(seed, MAX_SEED);
    if (v === null) warn(`The seed must be an integer from 0 to ${MAX_SEED}, got '${seed}'; using the default.`);
    else state.seed = v;
  }

  for (const spec of entry.controls) {
    const text = q.get(spec.id);
    if (text === undefined) continue;
    try {
      const value = decodeValue(spec, text);
      const p = controlProblem(spec, value, manifest.actions);
      if (p) throw new Error(p);
      state.controls[spec.id] = value;
    } catch (err) {
      warn(`${(err as Error).message}; using the default ${spec.label.toLowerCase()}.`);
    }
  }

  // What the stage shows: a bad value is named and left at the page's default.
  const view: StageView = {};
  const sample = q.get('sample');
  if (sample !== undefined) {
    const v = wholeNumber(sample);
    const k = typeof state.controls.k === 'number' ? state.controls.k : undefined;
    if (v === null || v < 1) warn(`The selected sample must be a sample number from 1, got '${sample}'; none is selected.`);
    else if (k !== undefined && v > k) warn(`The link selects sample #${v}, but it asks for ${k} samples; none is selected.`);
    else view.sample = v - 1;
  }
  const frame = q.get('frame');
  if (frame !== undefined) {
    const v = wholeNumber(frame);
    if (v === null) warn(`The frame must be a frame number, got '${frame}'; the futures play from the start.`);
    else view.frame = v;
  }
  const layout = q.get('layout');
  if (layout !== undefined) {
    if ((LAYOUTS as readonly string[]).includes(layout)) view.layout = layout as LayoutMode;
    else warn(`The layout must be ${LAYOUTS.join(' or ')}, got '${layout}'; the page picks one.`);
  }
  const cam = q.get('camera');
  if (cam !== undefined) {
    if ((CAMERA_PRESETS as readonly string[]).includes(cam)) { if (cam !== 'auto') view.camera = cam as CameraPreset; }
    else warn(`The camera must be ${CAMERA_PRESETS.join(', ')}, got '${cam}'; the camera fits all.`);
  }
  /** A 1|0 option: its value, or undefined when absent or bad (a bad one is named). */
  const flag = (key: string, fallback: string): boolean | undefined => {
    const text = q.get(key);
    if (text === undefined || text === '1' || text === '0') return text === undefined ? undefined : text === '1';
    warn(`The ${key} option must be 1 or 0, got '${text}'; ${fallback}.`);
    return undefined;
  };
  if (flag('closest', 'the closest sample is not highlighted')) view.closest = true;
  if (flag('truth', 'the ground truth is shown') === false) view.truth = false;
  if (Object.keys(view).length) state.view = view;

  // Compare mode: known models only (each dropped one named), the link's model first.
  const compare = q.get('compare');
  if (compare !== undefined) {
    const parsed = parseCompare(compare, manifest.models);
    parsed.problems.forEach(warn);
    if (parsed.ids.length) {
      const ids = [entry.id, ...parsed.ids.filter((id) => id !== entry!.id)].slice(0, MAX_COMPARED);
      state.compare = ids;
    }
  }

  const feet = q.get('feet');
  if (feet !== undefined) {
    if ((FEET_MODES as readonly string[]).includes(feet)) state.feet = feet as FeetMode;
    else warn(`The feet option must be ${FEET_MODES.join(' or ')}, got '${feet}'; the feet are planted.`);
  }

  const known = new Set<string>([...RESERVED, ...entry.controls.map((c) => c.id)]);
  for (const key of q.keys()) {
    if (known.has(key)) continue;
    const owner = manifest.models.find((m) => m.controls.some((c) => c.id === key));
    if (owner) warn(`This link sets '${key}', a control of ${owner.label} that ${entry.label} does not have; it was made for another model.`);
    else if (options.reportUnknown) problems.push({ level: 'info', text: `Ignored the unknown link option '${key}'.` });
  }
  return { state, problems };
}
