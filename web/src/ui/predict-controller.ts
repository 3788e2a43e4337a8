// Runs predictions for the page: manifest in, history window out of the current clip, futures
// from the worker onto the stage and into the panel. Nothing here knows which method runs.
import type { Manifest, ModelEntry } from '../contract/types';
import { window as clipWindow, type Motion } from '../motion/clip';
import { ModelLoadError, type PredictorClient } from '../predictor/client';
import { PredictError, Superseded, type Prediction } from '../predictor/types';
import type { Track } from '../viewer/tracks';
import type { SkeletonView } from '../viewer/viewer';
import type { ControlValue } from './controls';
import type { StatusSink } from './dom';
import type { MessageBanner } from './messages';
import { addSection } from './panel';
import type { Player } from './player';
import { mountPredictionPanel, type PredictionPanel } from './prediction-panel';
import { mountPredictPanel, type PredictPanel } from './predict-panel';
import { buildRequest } from './request-builder';

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
}

/** The inputs that make a request, as the share code reads and sets them. */
export interface PredictInputs {
  model: ModelEntry;
  seed: number;
  start: number;
  controls: Record<string, ControlValue>;
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
    tracks.push({ id: `sample:${i}`, role: 'prediction', positions: p.futures.slice(from, from + len * stride), frames: len, joints: p.joints, startFrame: n, sample: i, label: `#${i + 1}` });
  }
  return tracks;
}

export class PredictController {
  manifest: Manifest | null = null;
  last: { prediction: Prediction; ms: number; model: string; start: number } | null = null;
  private client: PredictorClient | null = null;
  private inputs: PredictPanel | null = null;
  private results: PredictionPanel | null = null;
  private loaded = new Set<string>();

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
    this.results = mountPredictionPanel(out.body, (s) => this.select(s));
    this.results.clear();
    this.inputs = mountPredictPanel(body, this.manifest, model, {
      onModel: (entry) => { this.clipChanged(this.o.currentClip(), entry); this.o.onChange?.(); },
      onPredict: () => { void this.predict(); },
      onChange: () => { this.o.onChange?.(); },
      status: this.o.status,
    });
    this.o.status('predictStatus', 'idle');
  }

  /** Start loading the chosen model while the clip loads, when a prediction follows at once: the
   * worker's wasm start-up and session creation then overlap the page's own loading. */
  warm(): void {
    if (!this.inputs || !this.manifest) return;
    const entry = this.inputs.model();
    // Nothing is reported here (no worker, a failed load): the prediction that follows tries again
    // and reports it.
    try {
      this.client ??= this.o.client(this.manifest);
    } catch {
      return;
    }
    void this.client.load(entry.id).then(() => { this.loaded.add(entry.id); performance.mark('mf:model-loaded'); }, () => undefined);
  }

  /** The current inputs, or null before the manifest is in. */
  inputsNow(): PredictInputs | null {
    if (!this.inputs) return null;
    return { model: this.inputs.model(), seed: this.inputs.seed(), start: this.inputs.history.start(), controls: this.inputs.controls().values() };
  }

  /** Set inputs (a permalink's); unknown models are left to the caller to report. */
  setInputs(s: { model?: string; seed?: number; controls?: Record<string, ControlValue> }): void {
    if (!this.inputs) return;
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
    this.inputs.history.setClip(m, entry.params.history_frames);
  }

  setStart(frame: number): void {
    this.inputs?.history.setStart(frame);
  }

  /** The sample picked in the list or by a digit key; null when none is. */
  selected: number | null = null;

  select(sample: number | null): void {
    this.selected = sample;
    this.o.view.setSelected(sample);
    this.results?.select(sample);
    this.o.onSelect?.(sample);
  }

  async predict(): Promise<void> {
    const m = this.o.currentClip();
    if (!this.inputs || !this.manifest) return;
    if (!m) { this.inputs.setStatus('Pick a clip for the history first.'); return; }
    const entry = this.inputs.model();
    const n = entry.params.history_frames;
    const start = this.inputs.history.start();
    if (m.frames < start + n) { this.inputs.setStatus(`${m.name} is too short for a ${n}-frame history from frame ${start}.`); return; }
    const request = buildRequest(entry, this.inputs.controls().values(), this.inputs.seed(), this.manifest.fps);
    const history = { positions: clipWindow(m, start, n), frames: n, joints: m.joints };
    try {
      this.client ??= this.o.client(this.manifest);
      const loading = !this.loaded.has(entry.id);
      this.inputs.setBusy(loading ? `Loading ${entry.label}…` : 'Predicting…', loading ? 0 : undefined);
      performance.mark('mf:predict-asked'); // marks: the benchmark's first-prediction timeline
      const { prediction, ms } = await this.client.predict(this.o.viewId, entry.id, history, request,
        (loaded, total) => this.inputs?.setBusy(`Loading ${entry.label}… ${(loaded / 1e6).toFixed(1)} MB`, total ? loaded / total : undefined));
      this.loaded.add(entry.id);
      performance.mark('mf:prediction-received');
      if (this.o.currentClip() !== m) { this.inputs.setBusy(null); return; } // the user moved on to another clip
      this.show(m, start, n, prediction, ms, entry);
    } catch (err) {
      if (err instanceof Superseded) return;
      this.inputs.setBusy(null);
      if (err instanceof PredictError) {
        this.inputs.setStatus(err.message);
        this.o.banner.show(`Cannot predict: ${err.message}`, 'warning', 'predict');
      } else {
        const text = err instanceof ModelLoadError ? err.message : `Prediction failed: ${(err as Error).message ?? err}`;
        this.inputs.setStatus(text);
        this.o.banner.show(text, 'error', 'predict');
      }
      this.o.status('predictStatus', 'error');
    }
  }

  private show(m: Motion, start: number, n: number, p: Prediction, ms: number, entry: ModelEntry): void {
    this.o.banner.clear('predict');
    this.last = { prediction: p, ms, model: entry.id, start };
    this.o.view.setTracks(predictionTracks(m, start, n, p), m.skeleton, { keepView: true });
    this.o.view.setSelected(null);
    this.o.player.load(n + Math.max(...p.lengths), m.fps, 0);
    this.o.player.play();
    this.results?.show(p, m.fps, ms);
    this.inputs?.setBusy(null);
    this.inputs?.setStatus(`${entry.label}: ${p.k} ${p.k === 1 ? 'future' : 'futures'} from frames ${start}–${start + n - 1} of ${m.name}.`);
    this.o.status('predictionModel', entry.id);
    this.o.status('predictionK', String(p.k));
    this.o.status('predictionLengths', Array.from(p.lengths).join(','));
    this.o.status('predictStatus', 'done');
    this.o.onShown?.();
  }
}
