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
import { mountViewPanel } from './view-panel';

export interface App {
  view: SkeletonView;
  player: Player;
  /** The side panel; later features add sections with addSection(panel, ...). */
  panel: HTMLElement;
  banner: MessageBanner;
  clips: ClipBrowser;
}

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

export function startApp(): App {
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
    }
  });

  const clips = new ClipBrowser({
    baseUrl: siteBase(), list, info, banner,
    onMotion(m) {
      if (!m) { view.clear(); player.load(0); return; }
      view.setTracks([clipTrack(m)], m.skeleton);
      player.load(m.frames, m.fps);
      player.play();
    },
  });
  void clips.start();
  return { view, player, panel, banner, clips };
}
