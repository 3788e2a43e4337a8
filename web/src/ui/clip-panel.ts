// The clip list, grouped by split role with the test clips first.
import type { ClipIndexEntry, Role } from '../contract/types';
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

export function mountClipPanel(
  container: HTMLElement, clips: readonly ClipIndexEntry[], onSelect: (entry: ClipIndexEntry) => void,
): ClipPanel {
  const buttons = new Map<string, HTMLButtonElement>();
  const groups = GROUPS.map(({ role, title }) => {
    const entries = clips.filter((c) => c.role === role);
    if (!entries.length) return null;
    const headingId = `clips-${role.replace('+', '-')}`;
    return el('div', { class: 'clip-group', role: 'group', 'aria-labelledby': headingId },
      el('h3', { id: headingId }, title),
      el('ul', { class: 'clip-list' }, ...entries.map((entry) => {
        const button = el('button', {
          type: 'button', class: 'clip-button', 'data-clip': entry.name,
          title: `${entry.name}: ${entry.action}, ${entry.frames} frames`,
        },
        el('span', { class: 'clip-name' }, entry.name),
        el('span', { class: `role-badge role-${role.replace('+', '-')}` }, role),
        el('span', { class: 'clip-meta' }, `${entry.frames} f`));
        button.addEventListener('click', () => onSelect(entry));
        buttons.set(entry.name, button);
        return el('li', {}, button);
      })));
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
