// Facts about the current clip, including the licence line of its source.
import type { Motion } from '../motion/clip';
import { el } from './dom';

export interface ClipInfo {
  show(motion: Motion): void;
  /** A short status in place of the facts (loading, failed). */
  status(text: string): void;
}

export function mountClipInfo(container: HTMLElement): ClipInfo {
  const root = el('div', { class: 'clip-info', 'data-testid': 'clip-info', 'aria-live': 'polite' });
  container.replaceChildren(root);
  return {
    show(m) {
      const loop = m.loops ? `yes${m.cycleFrames ? ` (cycle ${m.cycleFrames} frames)` : ''}` : 'no';
      const rows: [string, string][] = [
        ['Name', m.name], ['Action', m.action], ['Frames', `${m.frames} (${(m.frames / m.fps).toFixed(2)} s)`],
        ['FPS', String(m.fps)], ['Loops', loop],
        ['Split', m.origin?.kind === 'dropped-file' ? `none: your file ${m.origin.file}` : m.role],
      ];
      root.replaceChildren(
        el('dl', {}, ...rows.flatMap(([k, v]) => [el('dt', {}, k), el('dd', { 'data-field': k.toLowerCase() }, v)])),
        el('p', { class: 'licence', 'data-field': 'licence' }, m.license ? `Licence: ${m.license}` : m.origin ? 'Your own motion: it stays in this browser.' : 'Licence: not stated'),
      );
    },
    status(text) {
      root.replaceChildren(el('p', { class: 'muted' }, text));
    },
  };
}
