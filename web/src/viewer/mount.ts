// Put a viewer into a container; without WebGL, a notice there instead and an inert view.
import type { LayoutMode } from './layout';
import { Viewer, type CameraPreset, type SkeletonView } from './viewer';
import { WebGLUnavailableError } from './webgl';

export interface MountedViewer {
  view: SkeletonView;
  /** Why there is no 3D view, or null when there is one. */
  problem: string | null;
}

export function mountViewer(container: HTMLElement): MountedViewer {
  container.replaceChildren();
  const notice = document.createElement('p');
  notice.className = 'viewer-notice';
  notice.setAttribute('role', 'status');
  notice.hidden = true;
  container.append(notice);
  const say = (text: string | null) => { notice.textContent = text ?? ''; notice.hidden = text === null; };
  try {
    const view = new Viewer(container, (lost) => say(lost ? 'The graphics context was lost; waiting for the browser to restore it…' : null));
    return { view, problem: null };
  } catch (err) {
    const message = err instanceof WebGLUnavailableError ? err.message : `The 3D viewer failed to start: ${(err as Error).message}`;
    say(`${message} The clip list and playback controls still work.`);
    notice.classList.add('viewer-notice-error');
    return { view: new InertView(), problem: message };
  }
}

/** Keeps the page's bookkeeping (layout mode) when nothing can be drawn. */
class InertView implements SkeletonView {
  layout: LayoutMode = 'overlay';
  camera: CameraPreset = 'auto';
  setTracks(): void {}
  clear(): void {}
  setCamera(preset: CameraPreset): void { this.camera = preset; }
  setBestShown(): void {}
  setTruthShown(): void {}
  best(): null { return null; }
  bestRows(): [] { return []; }
  viewDirection(): null { return null; }
  shownTracks(): [] { return []; }
  onTracks(): void {}
  setLayout(mode: LayoutMode): void { this.layout = mode; }
  setFrame(): void {}
  setSelected(): void {}
  onPick(): void {}
  figures(): [] { return []; }
  resetView(): void {}
  dispose(): void {}
}
