// One motion-futures instance: wires viewer, player, panels, keyboard and sharing into the parts
// a widget gives it (web/src/embed/widget.ts). The main page, embed.html and every
// <motion-futures> on a project page run this same code.
import type { Manifest, ModelEntry } from '../contract/types';
import { sharedManifest, newViewId } from '../embed/shared';
import { EMBED_SCRIPT } from '../embed/site';
import type { Motion } from '../motion/clip';
import { movingStart } from '../motion/moving-start';
import { MAX_SEED } from '../rng/prng';
import { embedSnippet, iframeSnippet, permalink } from '../share/links';
import { mountSharePanel, type Shareable } from '../share/share-panel';
import {
  decodeState, encodeSearch, shortHash, unlinkableReason, UrlStateError, type HistorySource, type LinkState,
  type Problem, type ShareState, stageModel,
} from '../share/url-state';
import { SITE_VERSION } from '../share/version';
import { olderRelease } from '../share/versions';
import type { LayoutMode } from '../viewer/layout';
import { tintColour, type Rgb } from '../viewer/palette';
import type { TrackRole } from '../viewer/tracks';
import { mountViewer } from '../viewer/mount';
import type { Track } from '../viewer/tracks';
import type { SkeletonView } from '../viewer/viewer';
import { ClipBrowser } from './clip-browser';
import { mountClipInfo } from './clip-info';
import { clipTitle, motionTitle } from './clip-name';
import { el, type StatusSink } from './dom';
import { bindKeyboard } from './keyboard';
import type { KeyAction } from './keys';
import { catchUncaught, MessageBanner } from './messages';
import { addSection } from './panel';
import { mountPlaybackBar } from './playback-bar';
import { Player } from './player';
import { PredictController } from './predict-controller';
import { seconds } from './prediction-panel';
import { shownFromRuns } from '../export/shown';
import { mountExportPanel } from './export-panel';
import { mountImportPanel } from './import-panel';
import { mountCapturePanel } from './capture';
import { mountViewSummary } from './view-summary';
import { mountPhaseLabel, mountRangeNotice, mountStageStatus, mountStageToolbar } from './stage-parts';
import { mountStageView, type StageChoices } from './stage-view';
import { startWorker, workerClient } from './predictor-start';
import { mountComparePanel, type ComparePanel } from './compare-panel';
import { exportRuns, shortLabel } from './compare';
import { mountRefusalNotice } from './refusal-notice';

/** How an instance looks and starts, apart from the prediction state. */
export interface ViewOptions {
  /** 'full': side panel with every input and Share; 'minimal': stage, playback and one bar. */
  controls: 'full' | 'minimal';
  /** Play the clip and the futures as soon as they are in. */
  autoplay: boolean;
  /** Predict once the clip and the manifest are in (and again on every change); false: wait to be asked. */
  autoPredict: boolean;
  /** The instance is the whole page: reads and keeps the page URL, takes unfocused keys, catches uncaught errors. */
  page: boolean;
}

/** The DOM an instance draws into (inside its widget's shadow root). */
export interface AppParts {
  /** The instance root: keys bind here, focus lands here. */
  host: HTMLElement;
  /** Messages, laid over the top of the stage. */
  messages: HTMLElement;
  viewer: HTMLElement;
  playback: HTMLElement;
  panel: HTMLElement;
  /** The one-line bar of the minimal controls. */
  bar: HTMLElement;
  /** The line above the stage: legend, layout, reset view, offline state. */
  toolbar: HTMLElement;
  /** The out-of-range notice, laid over the bottom of the stage. */
  notice: HTMLElement;
  /** The line below the stage that names what is shown. */
  status: HTMLElement;
}

export interface AppOptions {
  siteRoot: string;
  view: ViewOptions;
  /** What the link or the element's attributes ask for (name/value pairs, see share/url-state.ts). */
  link: [string, string][];
  status: StatusSink;
  /** Called with the state's URL query whenever it changes (null when it cannot be linked). */
  onLink?(search: string | null): void;
}

/** The offline state of a page that registers the service worker (web/src/embed/offline.ts). */
export interface OfflineState {
  state: 'saving' | 'ready' | 'failed';
  /** Bytes the precache holds, once ready. */
  bytes?: number;
  files?: number;
}

export interface App {
  host: HTMLElement;
  view: SkeletonView;
  player: Player;
  /** The side panel; later features add sections with addSection(panel, ...). */
  panel: HTMLElement;
  banner: MessageBanner;
  clips: ClipBrowser;
  predictor: PredictController;
  /** Settles once the first clip, the manifest and the first prediction (unless predict=0) are done. */
  ready: Promise<void>;
  /** The motion the history is taken from, and where it came from. */
  onStage(): { motion: Motion | null; source: HistorySource };
  /** The state a link would carry now, or null with the reason it cannot be linked. */
  shareState(): { state: ShareState } | { unlinkable: string };
  /**
   * Put a motion on stage as the history source. The file-drop feature calls
   * showMotion(m, { kind: 'dropped', name }) for a dropped file: the Share buttons then say such
   * a history cannot be linked. Picking a clip in the list makes the source a clip again.
   */
  showMotion(m: Motion | null, source: HistorySource): void;
  /** Show the offline state (the page's service worker reports it). */
  offline(s: OfflineState): void;
}

/** The history clip shown first when the clip index names no default: a test clip, so the first
 *  futures come from unseen motion. */
export const DEFAULT_CLIP = 'deepmimic_walker_walk_forward';   // only when the index names no default
/** K of the first view: few enough that side by side each sample stays readable. */
export const FIRST_VIEW_K = 5;
export { stageModel };


/**
 * What a link without a model opens on (the first view, and an embed without a model): the stage's
 * model with K = FIRST_VIEW_K (within the control's range) unless the link sets K. A link that names
 * a model keeps the manifest's defaults.
 */
export function withStageDefaults(link: [string, string][], manifest: Manifest): [string, string][] {
  if (!manifest.models.length || link.some(([k]) => k === 'model')) return link;
  // a compare list without a model opens on its first model this site serves
  const compared = (link.find(([k]) => k === 'compare')?.[1] ?? '').split(',').map((id) => id.trim())
    .map((id) => manifest.models.find((m) => m.id === id)).find(Boolean);
  const entry = compared ?? stageModel(manifest);
  const out: [string, string][] = [['model', entry.id], ...link];
  const k = entry.controls.find((c) => c.id === 'k');
  if (k && !link.some(([name]) => name === 'k')) {
    out.push(['k', String(Math.min(k.max ?? FIRST_VIEW_K, Math.max(k.min ?? 1, FIRST_VIEW_K)))]);
  }
  return out;
}

/** The layout a prediction of K samples opens in (until the user picks one): apart beyond 3. */
export function defaultLayout(k: number): LayoutMode {
  return k > 3 ? 'side' : 'overlay';
}

/** The legend's left/right swatches as the figures draw their limbs: one step per figure colour
 *  family on stage (each sample's own pair, or the clip's), as CSS backgrounds. */
export function limbSwatches(role: TrackRole, k: number, shown = 10): { left: string; right: string } {
  const css = ([r, g, b]: Rgb) => `rgb(${Math.round(r * 255)} ${Math.round(g * 255)} ${Math.round(b * 255)})`;
  const side = (s: 'left' | 'right') => {
    const n = role === 'prediction' ? Math.max(1, Math.min(k, shown)) : 1;
    const colours = Array.from({ length: n }, (_, i) => css(tintColour(s, { role, sample: i })));
    if (n === 1) return colours[0];
    return `linear-gradient(90deg, ${colours.map((c, i) => `${c} ${((100 * i) / n).toFixed(1)}% ${((100 * (i + 1)) / n).toFixed(1)}%`).join(', ')})`;
  };
  return { left: side('left'), right: side('right') };
}

export function clipTrack(m: Motion): Track {
  return { id: `clip:${m.name}`, role: 'clip', positions: m.positions, frames: m.frames, joints: m.joints, startFrame: 0, label: m.name };
}

function showProblems(banner: MessageBanner, problems: Problem[]): void {
  problems.forEach((p, i) => banner.show(p.text, p.level, `link-${i}`));
}

const megabytes = (b: number) => `${(b / 1e6).toFixed(b >= 1e7 ? 0 : 1)} MB`;

/** The stage bar's choices as a link writes them: only what differs from the page's defaults. */
function barChoices(c: StageChoices): Pick<NonNullable<ShareState['view']>, 'camera' | 'closest' | 'truth'> {
  return { ...(c.camera !== 'auto' ? { camera: c.camera } : {}), ...(c.closest ? { closest: true } : {}), ...(c.truth ? {} : { truth: false }) };
}

export function startApp(parts: AppParts, o: AppOptions): App {
  const { view: options, siteRoot } = o;
  performance.mark('mf:app-start'); // marks: the benchmark's first-futures timeline (bench/browser.ts)
  if (options.autoPredict) startWorker(siteRoot); // onnxruntime starts while the stage is built
  const banner = new MessageBanner(parts.messages);
  if (options.page) catchUncaught(banner);
  const { view } = mountViewer(parts.viewer);
  const setPhase = mountPhaseLabel(parts.viewer);
  // camera presets, closest-to-truth and ground-truth toggles; what they show is part of the link
  const stageBar = mountStageView(parts.viewer, view, () => refreshShare());
  const player = new Player(30);
  const playback = mountPlaybackBar(parts.playback, player);
  /** The first predicted frame of what is on stage; null for a clip alone. */
  let origin: number | null = null;
  // A paused frame is part of the link (web/src/share/url-state.ts); a playing one is not.
  let pausedFrame: number | null = null;
  let shareTimer: ReturnType<typeof setTimeout> | null = null;
  player.subscribe((s) => {
    view.setFrame(s.position); setPhase(s.frame, s.fps, origin);
    const frame = s.playing ? null : s.frame;
    if (frame !== pausedFrame) {
      pausedFrame = frame;
      if (shareTimer !== null) clearTimeout(shareTimer);
      shareTimer = setTimeout(() => { shareTimer = null; refreshShare(); }, 250); // not on every step of a drag
    }
  });

  // The layout follows K until the user picks one.
  let layoutChosen = false;
  const setLayout = (mode: LayoutMode) => { view.setLayout(mode); toolbar.setLayout(mode); };
  const chooseLayout = (mode: LayoutMode) => { layoutChosen = true; setLayout(mode); refreshShare(); };
  const toolbar = mountStageToolbar(parts.toolbar, view.layout, { onLayout: chooseLayout, onResetView: () => view.resetView() });
  const stageStatus = mountStageStatus(parts.status);
  /** The legend's limb swatches follow the figures on stage (the toolbar reads --left and --right). */
  const limbLegend = (role: TrackRole, k: number) => {
    const { left, right } = limbSwatches(role, k);
    parts.toolbar.style.setProperty('--left', left);
    parts.toolbar.style.setProperty('--right', right);
  };
  /** The export's last "Saved …" belongs to what was on stage then: a new clip or prediction clears it. */
  const clearExportStatus = () => exporter.clearStatus();
  const rangeNotice = mountRangeNotice(parts.notice);
  // A refusal's notice sits where the range notice does (they never show together).
  const refusalNotice = mountRefusalNotice(parts.notice.parentElement ?? parts.notice, (start) => {
    predictor.setStart(start);
    refreshShare();
    askFutures();
  });
  /** A refusal leaves the refused history alone on stage: nothing else describes older futures. */
  const refusal: typeof refusalNotice = {
    show(r) {
      if (r) {
        rangeNotice(null, '');
        shown = null;
        toolbar.setLegend({ history: true, truth: false, k: 0 });
        clearExportStatus(); exporter.refresh(); summarise(); refreshShare();
      }
      refusalNotice.show(r);
    },
    search: (st) => refusalNotice.search(st),
  };
  let compare: ComparePanel | null = null;

  const panel = parts.panel;
  panel.replaceChildren();
  const info = mountClipInfo(addSection(panel, 'clip', 'Clip').body);
  const list = addSection(panel, 'clips', 'Clips').body;
  const share = mountSharePanel(addSection(panel, 'share', 'Share').body);

  let motion: Motion | null = null;
  let source: HistorySource = { kind: 'clip' };
  // Until the link's own state is applied, changes are start-up noise, not the user's state.
  let linking = false;
  const linkParams = new Map(o.link);
  const firstView = !linkParams.has('model');
  /** A clip's readable name (ui/clip-name.ts): the index entry's facts, else what its name says. */
  const titleOf = (name: string): string => {
    if (motion && motion.name === name) return motionTitle(motion, clips.entry(name));
    const entry = clips.entry(name);
    return entry ? clipTitle(entry) : name;
  };

  // The first futures follow at once: until they are in (or cannot be), the clip waits on its first
  // frame, as its frames would take the CPU the worker starts onnxruntime on (make bench: futures drawn).
  let holdPlayback = options.autoPredict && options.autoplay;
  const askFutures = () => { predictor.setLive(true); void predictor.predict(); };
  const bar = mountMinimalBar(parts.bar, {
    onNewFutures() {
      if (predictor.last && stochastic()) predictor.setInputs({ seed: Math.floor(Math.random() * MAX_SEED) });
      askFutures();
    },
  });
  const stochastic = () => Boolean(predictor.inputsNow()?.model.controls.some((c) => c.id === 'k'));

  const predictor = new PredictController({
    baseUrl: siteRoot, panel, view, player, banner, before: 'clip', currentClip: () => motion,
    manifest: () => sharedManifest(siteRoot), client: (m) => workerClient(siteRoot, m), viewId: newViewId(),
    status: o.status, onChange: () => refreshShare(),
    stageStatus: (text, state) => { stageStatus(text, state); },
    timeline: (marks) => { origin = marks?.origin ?? null; playback.setTimeline(marks); },
    beforeShow: (k) => { if (!layoutChosen) setLayout(defaultLayout(k)); },
    clipTitle: (name) => titleOf(name),
    refusal,
    onModel: (entry) => compare?.setPrimary(entry.id),
    compare: (): ModelEntry[] => (compare?.chosen() ?? []).flatMap((id) => predictor.manifest?.models.filter((e) => e.id === id) ?? []),
    compareStale: (on) => compare?.stale(on),
    onCompare: (rows) => {
      compare?.show(rows);
      o.status('compareModels', rows ? rows.map((r) => r.entry.id).join(',') : undefined);
    },
    onShown: () => {
      shown = predictor.last;
      const p = shown!.prediction;
      toolbar.setLegend({
        history: true, truth: Boolean(motion && shown && motion.frames > shown.start + (modelOf(shown.model)?.params.history_frames ?? 0)),
        k: p.k, cut: p.samples.flatMap((s, i) => (s.cut ? [i] : [])),
      });
      limbLegend('prediction', p.k);
      clearExportStatus();
      rangeNotice(p.warnings ?? null, modelOf(shown!.model)?.label ?? shown!.model);
      refreshShare(); exporter.refresh(); summarise();
    },
    onSelect: (sample) => { playback.select(sample); exporter.refresh(); summarise(); refreshShare(); },
  });
  // A click on a figure or its label selects it, a second click (or a click on nothing) lets go.
  view.onPick((sample) => predictor.select(sample !== null && sample === predictor.selected ? null : sample));
  const modelOf = (id: string) => predictor.manifest?.models.find((e) => e.id === id);

  // The 3D view in words (model, actions, K, lengths), below the stage and describing the canvas.
  const stageArea = parts.viewer.closest('.stage-area') as HTMLElement | null ?? parts.host;
  const updateSummary = mountViewSummary(stageArea, () => parts.viewer.querySelector('canvas'));
  let shown: PredictController['last'] = null; // the prediction on stage (a new clip clears it)
  function summarise(): void {
    const entry = shown && modelOf(shown.model);
    updateSummary({
      clip: motion ? titleOf(motion.name) : null, clipFrames: motion?.frames, fps: motion?.fps ?? player.state.fps, selected: predictor.selected,
      prediction: shown && entry ? { model: entry.label, start: shown.start, historyFrames: entry.params.history_frames, p: shown.prediction } : null,
      list: options.controls === 'full',
    });
  }
  // Capture for slides: the view as a PNG, the futures as a WebM (keys S and R).
  const capture = mountCapturePanel(addSection(panel, 'capture', 'Capture for slides', 'share').body, {
    canvas: () => parts.viewer.querySelector('canvas'),
    info: () => {
      const entry = shown && modelOf(shown.model);
      return {
        model: entry?.label, clip: motion?.name, start: shown?.start, historyFrames: entry?.params.history_frames,
        k: shown?.prediction.k, seed: shown?.seed, selected: predictor.selected,
      };
    },
    player, render: () => view.setFrame(player.state.position), status: o.status,
  });

  const showMotion = (m: Motion | null, from: HistorySource) => {
    motion = m;
    source = from;
    shown = null;
    origin = null;
    predictor.clearShown();
    predictor.clipChanged(m);
    playback.setTimeline(null);
    rangeNotice(null, '');
    if (!m) {
      view.clear(); player.load(0); toolbar.setLegend(null); stageStatus('No clip on stage.', 'clip'); refreshShare(); return;
    }
    view.setTracks([clipTrack(m)], m.skeleton);
    toolbar.setLegend({ clip: titleOf(m.name), history: false, truth: false, k: 0 });
    limbLegend('clip', 0);
    clearExportStatus();
    player.load(m.frames, m.fps);
    if ((options.autoplay && !holdPlayback) || linking) player.play(); // a clip the user picked plays
    const what = from.kind === 'dropped' ? `your file ${from.name}` : `the clip ${titleOf(m.name)}`;
    stageStatus(`On stage: ${what}, ${m.frames} frames (${seconds(m.frames, m.fps)}).${predictor.predictsOnChange ? ' Predicting…'
      : options.controls === 'full' ? ' Press Predict (P) for its futures.' : ''}`, 'clip');
    refreshShare();
    summarise();
    exporter.refresh();
    predictor.changed(); // a new history predicts again (once predictions run on their own)
  };

  const clips = new ClipBrowser({
    baseUrl: siteRoot, list, info, banner, defaultClip: linkParams.get('clip') || undefined, fallbackClip: DEFAULT_CLIP, status: o.status,
    onMotion(m) { if (!motion) performance.mark('mf:clip-in'); showMotion(m, { kind: 'clip' }); },
  });

  // Bring your own motion: a dropped BVH becomes the history; what is shown can be saved.
  mountImportPanel(addSection(panel, 'import', 'Your motion', 'share').body, {
    skeleton: () => clips.index?.skeleton ?? null, banner, dropTarget: parts.host, status: o.status,
    onMotion: (m) => { info.show(m); showMotion(m, { kind: 'dropped', name: m.origin.file }); },
  });
  const exporter = mountExportPanel(addSection(panel, 'export', 'Export', 'share').body, {
    banner, status: o.status,
    // every row on stage: compare mode's, or the page's model alone as one row
    shown: () => {
      const last = predictor.last;
      const entry = last && modelOf(last.model);
      if (!last || !entry || !motion) return null;
      const rows = last.compare ?? [{ entry, start: last.start, controls: last.controls, plantFeet: last.plantFeet !== false, prediction: last.prediction }];
      return shownFromRuns(motion, exportRuns(rows, last.seed), { selected: predictor.selected });
    },
  });

  function shareState(): { state: ShareState } | { unlinkable: string } {
    const inputs = predictor.inputsNow();
    if (!predictor.manifest || !inputs) return { unlinkable: 'The models did not load, so there is no prediction to link.' };
    if (!motion) return { unlinkable: 'No clip is on stage, so there is nothing to link.' };
    const state: ShareState = {
      version: SITE_VERSION, model: inputs.model.id, hash: shortHash(inputs.model.hash), clip: motion.name,
      start: inputs.start, seed: inputs.seed, controls: inputs.controls, source, view: stageView(),
      ...(inputs.plantFeet ? {} : { feet: 'own' as const }),
    };
    const companions = compare?.chosen() ?? [];
    if (companions.length) state.compare = [inputs.model.id, ...companions];
    const why = unlinkableReason(state);
    return why ? { unlinkable: why } : { state };
  }

  /** What the stage shows of the prediction on it: the selected sample, a paused frame, the layout. */
  function stageView(): ShareState['view'] {
    if (!predictor.last) return undefined;
    return {
      sample: predictor.selected ?? undefined,
      frame: player.state.playing ? undefined : player.state.frame,
      layout: view.layout,
      ...barChoices(stageBar.choices()),
    };
  }

  function refreshShare(): void {
    if (!linking) return;
    const s = shareState();
    const manifest = predictor.manifest as Manifest;
    let shareable: Shareable;
    let search: string | null = null;
    if ('unlinkable' in s) shareable = s;
    else {
      try {
        search = encodeSearch(s.state, manifest);
        shareable = {
          link: permalink(siteRoot, s.state, manifest),
          snippet: embedSnippet(EMBED_SCRIPT, s.state, manifest, { controls: 'minimal', autoplay: true }),
          iframe: iframeSnippet(siteRoot, s.state, manifest, { controls: 'minimal', autoplay: true }),
        };
      } catch (err) {
        shareable = { unlinkable: `This view cannot be linked: ${(err as Error).message}` };
      }
    }
    share.update(shareable);
    bar.update(shareable, predictor.inputsNow()?.model.label ?? '', motion ? titleOf(motion.name) : '',
      predictor.last ? (stochastic() ? 'New futures' : null) : 'Show futures');
    o.onLink?.(search);
  }

  bindKeyboard(parts.host, (action: KeyAction) => {
    switch (action.kind) {
      case 'toggle': player.toggle(); break;
      case 'step': player.step(action.frames); break;
      case 'speed': if (action.direction > 0) player.faster(); else player.slower(); break;
      case 'first': player.seek(0); break;
      case 'last': player.seek(player.state.length - 1); break;
      case 'layout': chooseLayout(view.layout === 'overlay' ? 'side' : 'overlay'); break;
      case 'predict': askFutures(); break;
      case 'sample': predictor.select(action.index); break;
      case 'snapshot': void capture.png(); break;
      case 'record': capture.toggleRecording(); break;
    }
  }, { unfocused: options.page });

  // Both loads run at once; the first futures appear as soon as the clip and the manifest are in.
  const startPredictor = async (): Promise<LinkState | null> => {
    let asked: LinkState | null = null;
    try {
      const manifest = await sharedManifest(siteRoot);
      performance.mark('mf:manifest-in');
      const decoded = decodeState(withStageDefaults(o.link, manifest), manifest, SITE_VERSION, { reportUnknown: true });
      asked = decoded.state;
      // the model's load starts now, while the panels are built and the clip loads
      if (options.autoPredict && asked.model && manifest.models.some((e) => e.id === asked!.model)) {
        predictor.warm({ manifest, model: asked.model });
      }
      showProblems(banner, decoded.problems);
      if (options.page && decoded.state.version && decoded.state.version !== SITE_VERSION) {
        void olderRelease(siteRoot, decoded.state.version).then((url) => {
          if (url) banner.show(`This site keeps version ${decoded.state.version}: open the link there: ${url}${location.search}`, 'info', 'link-release');
        });
      }
    } catch (err) {
      if (err instanceof UrlStateError) banner.show(err.message, 'warning', 'link');
      // a manifest that does not load is reported by the predictor
    }
    await predictor.start(asked?.model);
    if (predictor.manifest?.models.length && predictor.inputsNow()) {
      compare = mountComparePanel(addSection(panel, 'compare', 'Compare methods', 'clip').body, predictor.manifest.models,
        predictor.inputsNow()!.model.id, () => { refreshShare(); predictor.changed(); });
    }
    if (asked) predictor.setInputs({ ...asked, plantFeet: asked.feet !== 'own' });
    if (asked?.compare) { compare?.setPrimary(asked.model); compare?.set(asked.compare); }
    if (asked?.view?.layout) { layoutChosen = true; setLayout(asked.view.layout); }
    if (asked?.view) stageBar.set({ camera: asked.view.camera, closest: asked.view.closest, truth: asked.view.truth });
    if (options.autoPredict) predictor.warm();
    return asked;
  };

  const started = startPredictor();
  performance.mark('mf:app-built'); // the widget's synchronous start-up is done
  const ready = Promise.all([started, clips.start()]).then(async ([asked]) => {
    predictor.clipChanged(motion);
    if (holdPlayback && !(options.autoPredict && motion && predictor.manifest)) {
      holdPlayback = false; // no first futures follow
      if (motion) player.play();
    }
    const clip = linkParams.get('clip');
    if (clip && motion && motion.name !== clip) {
      banner.show(`This link asks for the clip '${clip}', which this site does not have; showing ${motion.name} instead.`, 'warning', 'link-clip');
    }
    if (asked?.start !== undefined && motion) {
      predictor.setStart(asked.start);
      if (predictor.historyStart() !== asked.start) {
        banner.show(`The history cannot start at frame ${asked.start} of ${motion.name}; it starts at frame ${predictor.historyStart()}.`, 'warning', 'link-start');
      }
    } else if (motion && clips.defaultStart(motion.name) !== undefined) {
      // the index's default history, moved past a standing start (motion/moving-start.ts)
      predictor.setStart(movingStart(motion.positions, motion.frames, motion.joints, motion.fps, clips.defaultStart(motion.name)!));
    }
    // The first view predicts the action the history shows, when the model knows it; later clips and
    // models do too until the user composes a sequence. A link's sequence is kept as it came.
    const sequence = predictor.inputsNow()?.model.controls.find((c) => c.type === 'actions');
    predictor.followClip(firstView && !(sequence && linkParams.has(sequence.id)));
    linking = true;
    refreshShare();
    if (!options.autoPredict && motion) {
      stageStatus(`On stage: the clip ${titleOf(motion.name)}, ${motion.frames} frames (${seconds(motion.frames, motion.fps)}). `
        + `${options.controls === 'full' ? 'Press Predict (P) for its futures.' : 'Press "Show futures" for its futures.'}`, 'clip');
    }
    if (options.autoPredict && motion && predictor.manifest) {
      predictor.setLive(true);
      try {
        await predictor.predict();
      } finally {
        holdPlayback = false;
        if (!predictor.last && options.autoplay && motion) player.play(); // no futures: the clip plays
      }
      if (!options.autoplay && predictor.last) { player.pause(); player.seek(Math.floor(player.state.length / 2)); }
      // what the link's stage showed: its selected sample and its paused frame
      if (predictor.last && asked?.view) {
        if (asked.view.sample !== undefined) predictor.select(asked.view.sample);
        if (asked.view.frame !== undefined) { player.pause(); player.seek(asked.view.frame); }
      }
    }
  });

  return {
    host: parts.host, view, player, panel, banner, clips, predictor, ready,
    onStage: () => ({ motion, source }),
    shareState,
    showMotion,
    offline(s) {
      const text = s.state === 'ready'
        ? `Ready offline${s.bytes ? ` (${megabytes(s.bytes)} saved)` : ''}`
        : s.state === 'saving' ? 'Saving for offline use…' : 'Offline use is unavailable';
      toolbar.setOffline(text, s.state);
      bar.offline(s.state === 'ready' ? 'Ready offline' : null);
      o.status('offline', s.state);
      if (s.bytes !== undefined) o.status('offlineBytes', String(s.bytes));
    },
  };
}

/** The minimal controls' bar: what is shown, new futures (when a seed changes them), and a link to
 *  the full page. It names only what it shows. */
function mountMinimalBar(container: HTMLElement, handlers: { onNewFutures(): void }) {
  const caption = el('span', { class: 'mini-caption muted' });
  const again = el('button', { type: 'button', class: 'text-button', 'data-testid': 'new-futures', title: 'Predict again with a new seed' }, 'New futures');
  const offline = el('span', { class: 'mini-offline muted', hidden: true });
  const open = el('a', { class: 'mini-open', target: '_blank', rel: 'noopener', hidden: true }, 'Open in motion-futures ↗');
  again.addEventListener('click', () => handlers.onNewFutures());
  container.replaceChildren(caption, again, offline, open);
  return {
    /** `action`: the button's text, or null to hide it (a deterministic model: a new seed changes nothing). */
    update(s: Shareable, model: string, clip: string, action: string | null) {
      // the model's short name on the line ("WAT (RNN)"), its whole label in the title
      caption.textContent = [model ? shortLabel({ label: model }) : '', clip].filter(Boolean).join(' · ');
      caption.title = [model, clip].filter(Boolean).join(' · ');
      open.hidden = 'unlinkable' in s;
      if (!('unlinkable' in s)) open.href = s.link;
      again.hidden = action === null;
      if (action) again.textContent = action;
    },
    offline(text: string | null) { offline.hidden = text === null; offline.textContent = text ?? ''; },
  };
}
