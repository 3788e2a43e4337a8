// Runs predictions for the page: manifest in, history window out of the current clip, futures
// from the worker onto the stage and into the panel. Nothing here knows which method runs.
// Never stale: once predictions run on their own (the page's first view, or after the user's first
// Predict), any change of the request (model, seed, controls, history start, clip, a dropped file)
// predicts again after a short pause; only the newest request's futures are shown, and until they
// are in, the futures on stage are marked as out of date.
import type { Manifest, ModelEntry } from '../contract/types';
import { window as clipWindow, type Motion } from '../motion/clip';
import { ModelLoadError, type PredictorClient } from '../predictor/client';
import { PredictError, Superseded, type Prediction } from '../predictor/types';
import { sampleTrackInfo, type Track } from '../viewer/tracks';
import type { SkeletonView } from '../viewer/viewer';
import type { ControlValue } from './controls';
import type { StatusSink } from './dom';
import type { MessageBanner } from './messages';
import { addSection } from './panel';
import type { TimelineMarks } from './playback-bar';
import { timelineMarks } from './timeline-marks';
import type { Player } from './player';
import { mountPredictionPanel, type PredictionPanel } from './prediction-panel';
import { mountPredictPanel, type PredictPanel } from './predict-panel';
import { readoutAfter, readoutJson, type StageReadout } from './readout';
import { buildRequest } from './request-builder';
import { followedSequence } from './follow-action';
import type { ShownState } from './stage-parts';
import { checkRequest } from '../predictor/request';
import { compareTracks, rowControls, rowStart, shortLabel, type CompareRow } from './compare';
import { refusalSentence, type RefusalNotice } from './refusal-notice';
import { candidateStarts, nearestAccepted } from './start-search';

/** Pause after the last change before predicting again (ms). */
export const REPREDICT_DELAY = 300;

export interface PredictOptions {
  baseUrl: string;
  panel: HTMLElement;
  view: SkeletonView;
  player: Player;
  banner: MessageBanner;
  currentClip(): Motion | null;
  /** Insert the predictor sections before this panel section. */
  before?: string;
  /** The manifest and the worker, shared by every instance on the page (web/src/embed/shared.ts). */
  manifest(): Promise<Manifest>;
  client(manifest: Manifest): PredictorClient;
  /** This instance's view id: its requests supersede only its own earlier ones. */
  viewId: string;
  /** Receives predictStatus and, after each prediction, predictionModel/K/Lengths. */
  status: StatusSink;
  /** Any input changed (model, seed, controls, history start). */
  onChange?(): void;
  /** A prediction is on stage. */
  onShown?(): void;
  /** The selected sample changed (null: none). */
  onSelect?(sample: number | null): void;
  /** The stage's status line (what is shown, and whether it is still what the inputs ask for). */
  stageStatus?(text: string, state: ShownState): void;
  /** The scrubber's history shading and stop/cut marks. */
  timeline?(marks: TimelineMarks | null): void;
  /** Called with K before a prediction goes on stage (the page picks its layout). */
  beforeShow?(k: number): void;
  /** A clip's readable name (ui/clip-name.ts) for the texts that name it; default: its name. */
  clipTitle?(name: string): string;
  /** The page's model was picked in the list. */
  onModel?(entry: ModelEntry): void;
  /** Compare mode (ui/compare.ts): the other models to run beside the page's (none: compare mode is off). */
  compare?(): ModelEntry[];
  /** Every row on stage, the page's model first (null: compare mode is off or nothing is shown). */
  onCompare?(rows: CompareRow[] | null): void;
  /** The rows' read-outs no longer match the inputs (new futures are on their way). */
  compareStale?(on: boolean): void;
  /** The notice a refusal shows over the stage (ui/refusal-notice.ts). */
  refusal?: RefusalNotice;
}

/** The inputs that make a request, as the share code reads and sets them. */
export interface PredictInputs {
  model: ModelEntry;
  seed: number;
  start: number;
  controls: Record<string, ControlValue>;
  /** Feet on the floor carry the root (predictor/foot-plant.ts); false: the method's own root. */
  plantFeet: boolean;
}

/** What is on stage: the prediction and everything it was made from. */
export interface Shown {
  prediction: Prediction;
  ms: number;
  model: string;
  start: number;
  clip: string;
  seed: number;
  controls: Record<string, ControlValue>;
  /** False: the method's own root travel (feet not planted). */
  plantFeet?: boolean;
  readout: StageReadout | null;
  /** Compare mode: every row on stage, this prediction's first. */
  compare?: CompareRow[];
}

/** The tracks a prediction shows: history, each sample up to its own length, and the truth. */
export function predictionTracks(m: Motion, start: number, n: number, p: Prediction): Track[] {
  const stride = p.joints * 3;
  const tracks: Track[] = [{ id: 'history', role: 'history', positions: clipWindow(m, start, n), frames: n, joints: p.joints, startFrame: 0, label: 'history' }];
  const truthFrames = Math.min(m.frames - start - n, Math.max(...p.lengths));
  if (truthFrames > 0) {
    tracks.push({ id: 'truth', role: 'truth', positions: clipWindow(m, start + n, truthFrames), frames: truthFrames, joints: p.joints, startFrame: n, label: 'ground truth' });
  }
  for (let i = 0; i < p.k; i++) {
    const len = p.lengths[i];
    const from = i * p.frames * stride;
    tracks.push({
      id: `sample:${i}`, role: 'prediction', positions: p.futures.slice(from, from + len * stride), frames: len, joints: p.joints,
      startFrame: n, sample: i, label: `#${i + 1}`, cut: Boolean(p.samples[i]?.cut),
      ...sampleTrackInfo(p.samples[i]),
    });
  }
  return tracks;
}

/** The scrubber's marks (timeline-marks.ts). */
export { timelineMarks };

/** "K = 5, actions = walk → run": a model's control values, in the manifest's order. */
export function describeControls(entry: ModelEntry, values: Record<string, ControlValue>): string {
  return entry.controls.filter((c) => values[c.id] !== undefined).map((c) => {
    const v = values[c.id];
    const text = Array.isArray(v) ? (v.length ? v.map((a) => a.replace(/_/g, ' ')).join(' → ') : 'none') : typeof v === 'boolean' ? (v ? 'on' : 'off') : String(v);
    return `${c.id === 'k' ? 'K' : c.id.replace(/_/g, ' ')} = ${text}`;
  }).join(', ');
}

export class PredictController {
  manifest: Manifest | null = null;
  last: Shown | null = null;
  private client: PredictorClient | null = null;
  private inputs: PredictPanel | null = null;
  private results: PredictionPanel | null = null;
  private loaded = new Set<string>();
  /** Predict again on every change of the request. */
  private live = false;
  private timer: ReturnType<typeof setTimeout> | null = null;
  /** Incremented by every prediction asked for: only the newest one's futures are shown. */
  private ticket = 0;
  /** The request last asked for, and the one on stage (requestKey): a change that leads back to
   *  either asks for nothing new. */
  private asked: string | null = null;
  private shownKey: string | null = null;
  /** Whether a new clip or model sets the action sequence to the clip's action (followClip), and the
   *  sequence the page set that way last. */
  private followsClip = false;
  private pageSequence: string[] | null = null;

  constructor(private readonly o: PredictOptions) {}

  async start(model?: string): Promise<void> {
    const { body } = addSection(this.o.panel, 'predict', 'Predict', this.o.before);
    const out = addSection(this.o.panel, 'prediction', 'Futures', this.o.before);
    body.textContent = 'Loading the models…';
    try {
      this.manifest = await this.o.manifest();
    } catch (err) {
      body.textContent = 'The models could not be loaded, so the page can show clips but not predict.';
      this.o.banner.error(err, 'manifest');
      this.o.status('predictStatus', 'unavailable');
      return;
    }
    if (!this.manifest.models.length) {
      body.textContent = 'The manifest lists no models.';
      return;
    }
    this.results = mountPredictionPanel(out.body, (s) => this.select(s), { numbersHelp: `${this.o.baseUrl}explainer.html#numbers` });
    this.results.clear();
    this.inputs = mountPredictPanel(body, this.manifest, model, {
      onModel: (entry) => { this.clipChanged(this.o.currentClip(), entry); this.o.onModel?.(entry); this.o.onChange?.(); },
      onPredict: () => { this.setLive(true); void this.predict(); },
      onChange: () => { this.o.onChange?.(); this.changed(); },
      status: this.o.status,
    });
    this.o.status('predictStatus', 'idle');
  }

  /** Start loading the chosen model while the clip loads, when a prediction follows at once: the
   * worker's wasm start-up and session creation then overlap the page's own loading. */
  warm(early?: { manifest: Manifest; model: string }): void {
    // `early`: the manifest and the link's model, before start() has built the panels (the worker's
    // onnxruntime start-up then overlaps that too)
    const manifest = early?.manifest ?? this.manifest;
    const id = early?.model ?? this.inputs?.model().id;
    if (!manifest || id === undefined || this.warming.has(id)) return;
    // Nothing is reported here (no worker, a failed load): the prediction that follows tries again
    // and reports it.
    try {
      this.client ??= this.o.client(manifest);
    } catch {
      return;
    }
    this.warming.add(id);
    void this.client.load(id).then(() => { this.loaded.add(id); performance.mark('mf:model-loaded'); },
      () => { this.warming.delete(id); });
  }

  /** Models warm() has asked the worker to load. */
  private warming = new Set<string>();

  /** The current inputs, or null before the manifest is in. */
  inputsNow(): PredictInputs | null {
    if (!this.inputs) return null;
    return { model: this.inputs.model(), seed: this.inputs.seed(), start: this.inputs.history.start(), controls: this.inputs.controls().values(),
      plantFeet: this.inputs.plantFeet() };
  }

  /** Set inputs (a permalink's); unknown models are left to the caller to report. Does not predict. */
  setInputs(s: { model?: string; seed?: number; controls?: Record<string, ControlValue>; plantFeet?: boolean }): void {
    if (!this.inputs) return;
    if (s.plantFeet !== undefined) this.inputs.setPlantFeet(s.plantFeet);
    if (s.model !== undefined) this.inputs.selectModel(s.model);
    if (s.seed !== undefined) this.inputs.setSeed(s.seed);
    for (const [id, v] of Object.entries(s.controls ?? {})) this.inputs.controls().set(id, v);
  }

  /** The history start frame (after clamping to the clip). */
  historyStart(): number | null {
    return this.inputs ? this.inputs.history.start() : null;
  }

  /** Keep the history picker in step with the clip on stage. */
  clipChanged(m: Motion | null, entry: ModelEntry | null = this.inputs?.model() ?? null): void {
    if (!this.inputs || !entry) return;
    this.inputs.history.setClip(m, entry.params.history_frames, m ? this.o.clipTitle?.(m.name) : undefined);
    if (this.followsClip) this.followAction(m, entry);
  }

  /** From now on, a new clip or model asks for the clip's action while the sequence is still the
   *  page's (ui/follow-action.ts); `now`: also for the clip on stage (a first view, not a link). */
  followClip(now: boolean): void {
    this.followsClip = true;
    if (now) this.followAction(this.o.currentClip(), this.inputs?.model() ?? null);
  }

  private followAction(m: Motion | null, entry: ModelEntry | null): void {
    const spec = entry?.controls.find((c) => c.type === 'actions');
    if (!m || !spec || !this.inputs || !this.manifest) return;
    const current = (this.inputs.controls().values()[spec.id] as string[] | undefined) ?? [];
    const next = followedSequence(current, this.pageSequence, (spec.default as string[] | undefined) ?? [], m.action,
      this.manifest.actions);
    if (!next) return;
    this.inputs.controls().set(spec.id, next);
    this.pageSequence = next;
  }

  setStart(frame: number): void {
    this.inputs?.history.setStart(frame);
  }

  /** The stage went back to a clip alone: nothing predicted is shown any more. */
  clearShown(): void {
    this.last = null;
    this.shownKey = null;
    this.selected = null;
    this.results?.clear();
    this.o.refusal?.show(null);
    this.o.onCompare?.(null);
    this.o.status('stale', undefined);
    this.o.status('refusalSearch', undefined);
  }

  /** Whether changes predict again on their own. */
  get predictsOnChange(): boolean { return this.live; }

  /** Let every later change of the request predict again on its own. */
  setLive(on: boolean): void { this.live = on; }

  /** Something the request is made of changed: predict again soon (when live), and say that what
   *  is on stage is out of date until then. */
  changed(): void {
    if (!this.live || !this.inputs || !this.manifest) return;
    const key = this.requestKey();
    if (key !== null && key === this.shownKey && this.timer === null && this.asked === key) {
      this.o.status('stale', undefined);
      this.results?.stale(false);
      return; // back to what is on stage (e.g. a change event for a value already predicted)
    }
    if (key !== null && key === this.asked && this.timer === null) return; // already on its way
    this.markStale();
    if (this.timer !== null) clearTimeout(this.timer);
    this.timer = setTimeout(() => { this.timer = null; void this.predict(); }, REPREDICT_DELAY);
  }

  /** The sample picked in the list, on the stage or by a digit key; null when none is. */
  selected: number | null = null;

  select(sample: number | null): void {
    if (sample !== null && this.last && sample >= this.last.prediction.k) sample = null;
    this.selected = sample;
    this.o.view.setSelected(sample);
    this.results?.select(sample);
    this.o.onSelect?.(sample);
  }

  /** Put a prediction on stage as if the worker had returned it for the current inputs (a replay:
   *  tests and the console use it to show a prediction with warnings or cut samples). */
  present(p: Prediction, ms = 0): Promise<void> {
    const m = this.o.currentClip();
    const inputs = this.inputsNow();
    if (!m || !inputs) return Promise.resolve();
    return this.show(m, inputs.start, inputs.model.params.history_frames, p, ms, inputs.model, inputs);
  }

  /** Everything a request is made of, as one string (null before the manifest or without a clip). */
  requestKey(): string | null {
    const inputs = this.inputsNow();
    const m = this.o.currentClip();
    if (!inputs || !m) return null;
    return this.keyOf(inputs.model.id, inputs.seed, inputs.start, inputs.controls, m, inputs.plantFeet);
  }

  private keyOf(model: string, seed: number, start: number, controls: Record<string, ControlValue>, m: Motion, plantFeet = true): string {
    const compare = this.o.compare?.().map((e) => e.id) ?? [];
    return JSON.stringify([model, seed, start, controls, m.name, m.frames, m.origin?.file ?? null, compare, plantFeet]);
  }

  async predict(): Promise<void> {
    const ticket = ++this.ticket;
    this.asked = this.requestKey();
    if (this.timer !== null) { clearTimeout(this.timer); this.timer = null; }
    const m = this.o.currentClip();
    if (!this.inputs || !this.manifest) return;
    if (!m) { this.inputs.setStatus('Pick a clip for the history first.'); return; }
    const inputs = this.inputsNow()!;
    const entry = inputs.model;
    const n = entry.params.history_frames;
    const start = inputs.start;
    if (m.frames < start + n) {
      const text = `${m.name} is too short for a ${n}-frame history from frame ${start}.`;
      this.inputs.setStatus(text);
      this.o.stageStatus?.(text, 'error');
      return;
    }
    const request = buildRequest(entry, inputs.controls, inputs.seed, this.manifest.fps, inputs.plantFeet);
    const history = { positions: clipWindow(m, start, n), frames: n, joints: m.joints };
    try {
      this.client ??= this.o.client(this.manifest);
      const loading = !this.loaded.has(entry.id);
      this.inputs.setBusy(loading ? `Loading ${entry.label}…` : 'Predicting…', loading ? 0 : undefined);
      this.markStale(loading ? `Loading ${entry.label}…` : 'Predicting…');
      performance.mark('mf:predict-asked'); // marks: the benchmark's first-prediction timeline
      const { prediction, ms, readout, readoutError } = await this.client.predict(this.o.viewId, entry.id, history, request,
        (loaded, total) => this.inputs?.setBusy(`Loading ${entry.label}… ${(loaded / 1e6).toFixed(1)} MB`, total ? loaded / total : undefined),
        { truth: truthAfter(m, start, n), skeleton: m.skeleton });
      this.loaded.add(entry.id);
      performance.mark('mf:prediction-received');
      if (ticket !== this.ticket) return; // a newer request replaces this one
      if (this.o.currentClip() !== m) { this.inputs.setBusy(null); return; } // the user moved on to another clip
      const companions = this.o.compare?.() ?? [];
      const rows = companions.length ? await this.compareRows(m, start, n, inputs, companions, ticket) : undefined;
      if (ticket !== this.ticket || this.o.currentClip() !== m) return;
      await this.show(m, start, n, prediction, ms, entry, inputs, readout ? { readout } : readoutError ? { error: readoutError } : undefined, rows);
    } catch (err) {
      if (err instanceof Superseded || ticket !== this.ticket) return;
      this.inputs.setBusy(null);
      let text: string;
      if (err instanceof PredictError) {
        // a refusal leaves nothing of another request on stage, and looks for a start that works
        text = err.message;
        this.inputs.setStatus(text);
        this.refuse(m, start, n, entry, request, text, ticket);
        return;
      } else {
        text = err instanceof ModelLoadError ? err.message : `Prediction failed: ${(err as Error).message ?? err}`;
        this.o.banner.show(text, 'error', 'predict');
      }
      this.inputs.setStatus(text);
      this.o.stageStatus?.(this.last ? `Not updated (${text}). Still shown, out of date: ${this.describe(this.last)}` : `Cannot predict: ${text}`, 'error');
      this.o.status('predictStatus', 'error');
    }
  }

  /** Compare mode: the other models' futures from the same history end, seed, K and horizon, each
   *  from its own history length; a refusal or a clip too short for a history is that row's message. */
  private async compareRows(m: Motion, start: number, n: number, inputs: PredictInputs, companions: ModelEntry[],
    ticket: number): Promise<CompareRow[]> {
    const fps = this.manifest!.fps;
    return Promise.all(companions.map(async (entry): Promise<CompareRow> => {
      const frames = entry.params.history_frames;
      const controls = rowControls(entry, inputs.controls);
      const from = rowStart(start, n, frames);
      if (from === null) {
        return { entry, start: 0, controls, plantFeet: inputs.plantFeet, error: `${entry.label} needs ${frames} frames of history; the clip has ${start + n} before the futures.` };
      }
      const history = { positions: clipWindow(m, from, frames), frames, joints: m.joints };
      try {
        const r = await this.client!.predict(`${this.o.viewId}:compare:${entry.id}`, entry.id, history,
          buildRequest(entry, controls, inputs.seed, fps, inputs.plantFeet), undefined, { truth: truthAfter(m, from, frames), skeleton: m.skeleton });
        this.loaded.add(entry.id);
        return { entry, start: from, controls, plantFeet: inputs.plantFeet, prediction: r.prediction, readout: r.readout ?? null };
      } catch (err) {
        if (err instanceof Superseded || ticket !== this.ticket) throw err instanceof Superseded ? err : new Superseded();
        return { entry, start: from, controls, plantFeet: inputs.plantFeet, error: `${entry.label} cannot predict from this history: ${(err as Error).message}` };
      }
    }));
  }

  /** A refusal: the stage keeps only the refused history (nothing another request predicted), the
   *  notice says so in one sentence and, when the history is what was refused, looks for the nearest
   *  start the method accepts with the same predictor (ui/start-search.ts). */
  private refuse(m: Motion, start: number, n: number, entry: ModelEntry, request: ReturnType<typeof buildRequest>,
    reason: string, ticket: number): void {
    this.clearShown();
    this.o.view.setTracks([{ id: 'history', role: 'history', positions: clipWindow(m, start, n), frames: n, joints: m.joints, startFrame: 0, label: 'history' }], m.skeleton);
    this.o.player.load(n, m.fps, 0);
    this.o.timeline?.(null);
    let searchable = true;
    try {
      checkRequest(request, entry, this.manifest!.actions, this.manifest!.fps);
    } catch {
      searchable = false; // the request itself is refused: another start would not help
    }
    const refusal = { model: entry.label, start, frames: n, clip: this.o.clipTitle?.(m.name) ?? m.name, reason, searchable };
    this.o.refusal?.show(refusal);
    const why = reason.charAt(0).toUpperCase() + reason.slice(1);
    this.o.stageStatus?.(`${refusalSentence(refusal)} ${why}${/[.!?]$/.test(why) ? '' : '.'}`, 'error');
    this.o.status('predictStatus', 'error');
    if (!searchable) return;
    this.o.status('refusalSearch', 'searching');
    // K = 1: a refusal is the history's (predictor/history.ts, the methods' own checks), not K's
    const probe = { ...request, k: 1 };
    const tryStart = async (s: number) => {
      if (ticket !== this.ticket || this.o.currentClip() !== m) throw new Superseded();
      try {
        await this.client!.predict(`${this.o.viewId}:search`, entry.id, { positions: clipWindow(m, s, n), frames: n, joints: m.joints }, probe);
        return 'accepted' as const;
      } catch (err) {
        if (err instanceof PredictError) return 'refused' as const;
        throw err;
      }
    };
    const starts = candidateStarts(start, m.frames - n);
    void nearestAccepted(starts, tryStart, (tried, of) => { if (ticket === this.ticket) this.o.refusal?.search({ kind: 'searching', tried, of }); })
      .then((found) => {
        if (ticket !== this.ticket) return;
        this.o.refusal?.search(found === null ? { kind: 'none', tried: starts.length } : { kind: 'found', start: found });
        this.o.status('refusalSearch', found === null ? 'none' : String(found));
      }, (err) => {
        if (err instanceof Superseded || ticket !== this.ticket) return;
        this.o.refusal?.search({ kind: 'none', tried: 0 });
        this.o.status('refusalSearch', 'failed');
      });
  }

  /** "WAT (RNN): 5 futures from frames 0–9 of walk_01, seed 1, K = 5, actions = walk." */
  describe(s: Pick<Shown, 'model' | 'start' | 'clip' | 'seed' | 'controls' | 'plantFeet'> & { prediction?: Prediction }): string {
    const entry = this.manifest?.models.find((e) => e.id === s.model);
    if (!entry) return s.model;
    const n = entry.params.history_frames;
    const k = s.prediction?.k ?? Number(s.controls.k ?? 1);
    const controls = describeControls(entry, s.controls);
    const seeded = entry.controls.some((c) => c.id === 'k'); // a deterministic model's futures do not depend on it
    return `${entry.label}: ${k} ${k === 1 ? 'future' : 'futures'} from frames ${s.start}–${s.start + n - 1} of ${this.o.clipTitle?.(s.clip) ?? s.clip}${seeded ? `, seed ${s.seed}` : ''}${controls ? `, ${controls}` : ''}${s.plantFeet === false ? ', own root (feet not planted)' : ''}.`;
  }

  /** The stage no longer shows what the inputs ask for: say so until the new futures are in. */
  private markStale(doing = 'Predicting…'): void {
    const inputs = this.inputsNow();
    const m = this.o.currentClip();
    this.o.status('stale', this.last ? 'true' : undefined);
    this.results?.stale(this.last !== null);
    this.o.compareStale?.(this.last?.compare !== undefined);
    if (!inputs || !m) return;
    const next = this.describe({ model: inputs.model.id, start: inputs.start, clip: m.name, seed: inputs.seed, controls: inputs.controls,
      plantFeet: inputs.plantFeet });
    this.o.stageStatus?.(this.last ? `${doing} ${next} (the figures still show the previous futures)` : `${doing} ${next}`, 'busy');
  }

  /** `computed`: the read-out the worker computed with the prediction, or why it could not; without
   *  it (a replay, a client that does not compute it) the read-out is computed here. */
  private show(m: Motion, start: number, n: number, p: Prediction, ms: number, entry: ModelEntry, inputs: PredictInputs,
    computed?: { readout: StageReadout } | { error: string }, rows?: CompareRow[]): Promise<void> {
    this.o.banner.clear('predict');
    this.o.refusal?.show(null);
    this.o.status('refusalSearch', undefined);
    let readout: StageReadout | null = null;
    if (computed && 'readout' in computed) readout = computed.readout;
    else if (computed) this.o.banner.show(`The read-out could not be computed: ${computed.error}`, 'warning', 'readout');
    else {
      try {
        readout = readoutAfter(p, clipWindow(m, start, n), truthAfter(m, start, n), m.skeleton);
      } catch (err) {
        this.o.banner.show(`The read-out could not be computed: ${(err as Error).message}`, 'warning', 'readout');
      }
    }
    const all = rows ? [{ entry, start, controls: inputs.controls, plantFeet: inputs.plantFeet, prediction: p, readout }, ...rows] : undefined;
    this.last = { prediction: p, ms, model: entry.id, start, clip: m.name, seed: inputs.seed, controls: inputs.controls, plantFeet: inputs.plantFeet, readout, compare: all };
    this.shownKey = this.keyOf(entry.id, inputs.seed, start, inputs.controls, m);
    this.selected = null;
    performance.mark('mf:show-start');
    this.o.beforeShow?.(p.k);
    if (all) {
      // compare mode: one row per method, the futures of all starting on the same timeline frame
      const { tracks, origin } = compareTracks(m, all);
      this.o.view.setTracks(tracks, m.skeleton);
      this.o.player.load(origin + Math.max(...all.flatMap((r) => (r.prediction ? [...r.prediction.lengths] : []))), m.fps, 0);
      this.o.timeline?.(timelineMarks(origin, p, m.fps));
    } else {
      this.o.view.setTracks(predictionTracks(m, start, n, p), m.skeleton);
      this.o.player.load(n + Math.max(...p.lengths), m.fps, 0);
      this.o.timeline?.(timelineMarks(n, p, m.fps));
    }
    this.o.view.setSelected(null);
    this.o.onCompare?.(all ?? null);
    performance.mark('mf:tracks-set');
    const shown = this.last;
    // The list, the numbers and the statuses follow once the stage has drawn the new futures, and the
    // futures play once all is in: at K = 50 building everything in one task, with playback drawing
    // every frame, made the frames after a result miss two vsyncs (make bench's frame gaps).
    const ticket = this.ticket;
    return afterNextFrame().then(afterNextFrame).then(() => {
      if (this.last !== shown) return undefined; // a newer result took the stage
      // the stage drew its first frame with these tracks in the frame before (Stage.invalidateAfterNextFrame)
      performance.mark('mf:futures-drawn'); // make bench's navigation -> futures drawn
      this.describeShown(shown, m.fps, n, entry, ticket === this.ticket);
      // and the statuses after the list's own frame, for the same reason
      return afterNextFrame().then(() => { if (this.last === shown) this.settle(shown, entry, ticket === this.ticket); });
    });
  }

  /** The second part of show(): the side panel's list and read-out. `current`: no newer prediction was
   *  asked for in between (else the panel stays marked as out of date). */
  private describeShown(shown: Shown, fps: number, n: number, entry: ModelEntry, current: boolean): void {
    const { prediction: p, readout } = shown;
    this.results?.show(p, fps, shown.ms, {
      readout, outOfRange: Boolean(p.warnings?.length),
      readoutJson: () => (readout ? readoutJson(readout, {
        model: entry.id, model_label: entry.label, model_hash: entry.hash, clip: shown.clip, history_start: shown.start,
        history_frames: n, seed: shown.seed, controls: shown.controls, plant_feet: shown.plantFeet !== false, fps,
        // compare mode: what each other row was asked (its numbers are in Compare methods)
        ...(shown.compare ? { compared_with: shown.compare.slice(1).map((r) => ({
          model: r.entry.id, model_hash: r.entry.hash, history_start: r.start, history_frames: r.entry.params.history_frames,
          controls: r.controls, plant_feet: r.plantFeet, ...(r.error ? { error: r.error } : {}),
        })) } : {}),
      }) : '{}'),
    });
    if (!current) this.results?.stale(true);
  }

  /** The last part of show(): the texts and statuses that say the futures are in, then 'done'. */
  private settle(shown: Shown, entry: ModelEntry, current: boolean): void {
    const p = shown.prediction;
    const others = (shown.compare ?? []).slice(1).map((r) => (r.prediction
      ? `${shortLabel(r.entry)} (frames ${r.start}–${r.start + r.entry.params.history_frames - 1}, K = ${r.prediction.k})`
      : `${shortLabel(r.entry)} (no futures: see Compare methods)`));
    const text = `${this.describe(shown)}${others.length ? ` Compared with ${others.join(' and ')}, same seed.` : ''}`;
    const out = p.warnings?.length ? ' Out of the training range: shown anyway.' : '';
    if (current) {
      this.inputs?.setBusy(null);
      this.inputs?.setStatus(`${text}${out}`);
      this.o.stageStatus?.(`${text}${out}`, 'shown');
      this.o.status('stale', undefined);
    } else {
      this.results?.stale(true);
    }
    this.o.status('predictionModel', entry.id);
    this.o.status('predictionK', String(p.k));
    this.o.status('predictionLengths', Array.from(p.lengths).join(','));
    this.o.status('predictionRange', p.warnings?.length ? 'out' : undefined);
    if (current) this.o.status('predictStatus', 'done');
    performance.mark('mf:prediction-shown');
    this.o.onShown?.();
    this.o.player.play();
  }
}

/** The clip's frames after an n-frame history from `start` (the read-out's truth), or null when none follow. */
function truthAfter(m: Motion, start: number, n: number): Float32Array | null {
  const rest = m.frames - start - n;
  return rest > 0 ? clipWindow(m, start + n, rest) : null;
}

/** Settles after the next frame has been drawn; a hidden page draws no frames, so at most 200 ms later. */
function afterNextFrame(): Promise<void> {
  return new Promise((done) => {
    requestAnimationFrame(() => setTimeout(done, 0));
    setTimeout(done, 200);
  });
}
