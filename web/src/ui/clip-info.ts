// Facts about the current clip, including the licence line of its source.
import type { ClipIndexEntry } from '../contract/types';
import type { Motion } from '../motion/clip';
import { motionTitle } from './clip-name';
import { el } from './dom';

export interface ClipInfo {
  /** The clip's facts; its index entry adds the person and take, `note` how its action's held-out people differ. */
  show(motion: Motion, entry?: ClipIndexEntry, note?: string): void;
  /** A short status in place of the facts (loading, failed). */
  status(text: string): void;
}

export function mountClipInfo(container: HTMLElement): ClipInfo {
  const root = el('div', { class: 'clip-info', 'data-testid': 'clip-info', 'aria-live': 'polite' });
  container.replaceChildren(root);
  return {
    show(m, entry, note) {
      const loop = m.loops ? `yes${m.cycleFrames ? ` (cycle ${m.cycleFrames} frames)` : ''}` : 'no';
      const own = entry?.name === m.name ? entry : undefined;
      const rows: [string, string][] = [
        ['Clip', motionTitle(m, own)], ['Name', m.name], ['Action', m.action],
        ...(own?.subject !== undefined ? [['Person', `subject ${own.subject}`] as [string, string]] : []),
        ...(own?.take ? [['Take', own.take] as [string, string]] : []),
        ['Frames', `${m.frames} (${(m.frames / m.fps).toFixed(2)} s)`],
        ['FPS', String(m.fps)], ['Loops', loop],
        ['Split', m.origin?.kind === 'dropped-file' ? `none: your file ${m.origin.file}` : m.role],
      ];
      root.replaceChildren(
        el('dl', {}, ...rows.flatMap(([k, v]) => [el('dt', {}, k), el('dd', { 'data-field': k.toLowerCase() }, v)])),
        ...(own && note ? [el('p', { class: 'muted clip-note', 'data-field': 'note' }, `${m.action.replace(/_/g, ' ')}: ${note}`)] : []),
        el('p', { class: 'licence', 'data-field': 'licence' }, m.license ? `Licence: ${m.license}` : m.origin ? 'Your own motion: it stays in this browser.' : 'Licence: not stated'),
      );
    },
    status(text) {
      root.replaceChildren(el('p', { class: 'muted' }, text));
    },
  };
}
