// The clip browser page: wires viewer, player, panels and keyboard together.
import type { Motion } from '../motion/clip';
import type { LayoutMode } from '../viewer/layout';
import { mountViewer } from '../viewer/mount';
import type { Track } from '../viewer/tracks';
import type { SkeletonView } from '../viewer/viewer';
import { ClipBrowser } from './clip-browser';
import { mountClipInfo } from './clip-info';
import { bindKeyboard } from './keyboard';
import type { KeyAction } from './keys';
import { catchUncaught, MessageBanner } from './messages';
import { addSection } from './panel';
import { mountPlaybackBar } from './playback-bar';
import { Player } from './player';
import { PredictController } from './predict-controller';
import { mountViewPanel } from './view-panel';

export interface App {
  view: SkeletonView;
  player: Player;
  /** The side panel; later features add sections with addSection(panel, ...). */
  panel: HTMLElement;
  banner: MessageBanner;
  clips: ClipBrowser;
  predictor: PredictController;
}

/** The history clip shown first: a test clip, so the first futures come from unseen motion. */
export const DEFAULT_CLIP = 'walker_walk_forward';

function byId(id: string): HTMLElement {
  const node = document.getElementById(id);
  if (!node) throw new Error(`index.html lacks #${id}`);
  return node;
}

/** The site root ('./' build base resolved against the page), ending in '/'. */
export function siteBase(): string {
  return new URL(import.meta.env.BASE_URL, document.baseURI).href;
}

export function clipTrack(m: Motion): Track {
  return { id: `clip:${m.name}`, role: 'clip', positions: m.positions, frames: m.frames, joints: m.joints, startFrame: 0, label: m.name };
}

/** Start-up choices from the page URL: ?clip=NAME&model=ID&start=F&predict=0 (no automatic first prediction). */
export function urlOptions(search = location.search): { clip?: string; model?: string; start?: number; autoPredict: boolean } {
  const q = new URLSearchParams(search);
  const start = q.get('start');
  return {
    clip: q.get('clip') ?? undefined,
    model: q.get('model') ?? undefined,
    start: start !== null && /^\d+$/.test(start) ? Number(start) : undefined,
    autoPredict: q.get('predict') !== '0',
  };
}

export function startApp(): App {
  const options = urlOptions();
  const banner = new MessageBanner(byId('messages'));
  catchUncaught(banner);
  const { view } = mountViewer(byId('viewer'));
  const player = new Player(30);
  mountPlaybackBar(byId('playback'), player);
  player.subscribe((s) => view.setFrame(s.position));

  const panel = byId('panel');
  panel.replaceChildren();
  const info = mountClipInfo(addSection(panel, 'clip', 'Clip').body);
  const list = addSection(panel, 'clips', 'Clips').body;
  const setLayout = (mode: LayoutMode) => { view.setLayout(mode); viewPanel.setLayout(mode); };
  const viewPanel = mountViewPanel(addSection(panel, 'view', 'View').body, view.layout, {
    onLayout: setLayout, onResetView: () => view.resetView(),
  });

  bindKeyboard(window, (action: KeyAction) => {
    switch (action.kind) {
      case 'toggle': player.toggle(); break;
      case 'step': player.step(action.frames); break;
      case 'speed': if (action.direction > 0) player.faster(); else player.slower(); break;
      case 'first': player.seek(0); break;
      case 'last': player.seek(player.state.length - 1); break;
      case 'layout': setLayout(view.layout === 'overlay' ? 'side' : 'overlay'); break;
      case 'predict': void predictor.predict(); break;
      case 'sample': predictor.select(action.index); break;
    }
  });

  const predictor = new PredictController({
    baseUrl: siteBase(), panel, view, player, banner, before: 'clip', currentClip: () => clips.current,
  });
  const clips = new ClipBrowser({
    baseUrl: siteBase(), list, info, banner, defaultClip: options.clip ?? DEFAULT_CLIP,
    onMotion(m) {
      predictor.clipChanged(m);
      if (!m) { view.clear(); player.load(0); return; }
      view.setTracks([clipTrack(m)], m.skeleton);
      player.load(m.frames, m.fps);
      player.play();
    },
  });
  // Both loads run at once; the first futures appear as soon as the clip and the manifest are in.
  void Promise.all([predictor.start(options.model), clips.start()]).then(() => {
    predictor.clipChanged(clips.current);
    if (options.start !== undefined) predictor.setStart(options.start);
    if (options.autoPredict && clips.current && predictor.manifest) void predictor.predict();
  });
  return { view, player, panel, banner, clips, predictor };
}
