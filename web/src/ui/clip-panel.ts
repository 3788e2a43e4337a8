// The clip list, grouped by split role with the test clips first, then by action (with the index's
// note on how the action's held-out people differ), each clip with its person and take when the
// index names them, by its readable name (ui/clip-name.ts). The list grows with the page: it does not scroll inside the scrolling panel.
import type { ClipIndexEntry, Role } from '../contract/types';
import { clipShortTitle, clipTitle } from './clip-name';
import { el } from './dom';

const GROUPS: { role: Role; title: string }[] = [
  { role: 'test', title: 'Test clips (held out)' },
  { role: 'train+test', title: 'Train + test (tail held out)' },
  { role: 'train', title: 'Training clips' },
];

export interface ClipPanel {
  /** Mark a clip as the current one (does not load it). */
  select(name: string | null): void;
}

const pretty = (s: string) => s.replace(/_/g, ' ');

function clipButton(entry: ClipIndexEntry, role: Role, onSelect: (entry: ClipIndexEntry) => void): HTMLButtonElement {
  const title = clipTitle(entry);
  const button = el('button', {
    type: 'button', class: 'clip-button', 'data-clip': entry.name, 'data-title': title,
    title: `${title}: ${entry.name}, ${entry.frames} frames`,
  },
  // The readable name (its action and split are the headings above it), the file's own name below it.
  el('span', { class: 'clip-name' }, clipShortTitle(entry), el('span', { class: 'clip-who' }, entry.name)),
  el('span', { class: `role-badge role-${role.replace('+', '-')}` }, role),
  el('span', { class: 'clip-meta' }, `${entry.frames} f`));
  button.addEventListener('click', () => onSelect(entry));
  return button;
}

export function mountClipPanel(
  container: HTMLElement, clips: readonly ClipIndexEntry[], onSelect: (entry: ClipIndexEntry) => void,
  notes: Record<string, string> = {},
): ClipPanel {
  const buttons = new Map<string, HTMLButtonElement>();
  const groups = GROUPS.map(({ role, title }) => {
    const entries = clips.filter((c) => c.role === role);
    if (!entries.length) return null;
    const headingId = `clips-${role.replace('+', '-')}`;
    const actions = [...new Set(entries.map((c) => c.action))];
    // Sub-headings by action only when a group holds several clips of one action.
    const byAction = actions.length < entries.length;
    const list = (items: ClipIndexEntry[]) => el('ul', { class: 'clip-list' }, ...items.map((entry) => {
      const button = clipButton(entry, role, onSelect);
      buttons.set(entry.name, button);
      return el('li', {}, button);
    }));
    return el('div', { class: 'clip-group', role: 'group', 'aria-labelledby': headingId },
      el('h3', { id: headingId }, title, el('span', { class: 'clip-count muted' }, ` ${entries.length}`)),
      ...(byAction
        ? actions.map((a) => el('div', { class: 'clip-action', 'data-action': a },
          el('h4', {}, pretty(a)),
          role !== 'train' && notes[a] ? el('p', { class: 'muted clip-note' }, notes[a]) : null,
          list(entries.filter((c) => c.action === a))))
        : [list(entries)]));
  });
  container.replaceChildren(el('div', { class: 'clip-groups', 'data-testid': 'clip-list' }, ...groups));

  return {
    select(name) {
      for (const [n, b] of buttons) {
        if (n === name) b.setAttribute('aria-current', 'true');
        else b.removeAttribute('aria-current');
      }
    },
  };
}
