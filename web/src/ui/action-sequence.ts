// The action-sequence composer: an ordered list of actions, built from the manifest's actions.
import { el } from './dom';

export interface ActionSequence {
  root: HTMLElement;
  value(): string[];
  set(actions: string[]): void;
}

export function mountActionSequence(id: string, label: string, actions: string[], initial: string[], maxLength: number,
  onChange: () => void): ActionSequence {
  let chosen = initial.filter((a) => actions.includes(a)).slice(0, maxLength);
  const list = el('ol', { class: 'action-chips', 'aria-label': `${label}: chosen actions in order` });
  const select = el('select', { id: `${id}-pick`, 'aria-label': 'Action to add' },
    ...actions.map((a) => el('option', { value: a }, a.replace(/_/g, ' '))));
  const add = el('button', { type: 'button', class: 'text-button add-action' }, 'Add');
  const clear = el('button', { type: 'button', class: 'text-button' }, 'Clear');
  const count = el('span', { class: 'muted action-count' });

  const render = () => {
    list.replaceChildren(...chosen.map((a, i) => {
      const remove = el('button', { type: 'button', class: 'chip-remove', 'aria-label': `Remove ${a} (step ${i + 1})` }, '×');
      remove.addEventListener('click', () => { chosen.splice(i, 1); render(); onChange(); });
      return el('li', { class: 'action-chip' }, el('span', {}, `${i + 1}. ${a.replace(/_/g, ' ')}`), remove);
    }));
    if (!chosen.length) list.append(el('li', { class: 'muted' }, 'No actions yet: add at least one.'));
    add.disabled = chosen.length >= maxLength;
    count.textContent = `${chosen.length} / ${maxLength}`;
  };
  add.addEventListener('click', () => {
    if (chosen.length < maxLength) { chosen.push(select.value); render(); onChange(); }
  });
  clear.addEventListener('click', () => { chosen = []; render(); onChange(); });
  render();
  const root = el('fieldset', { class: 'control control-actions' },
    el('legend', {}, label), list,
    el('div', { class: 'action-add' }, select, add, clear, count));
  return {
    root,
    value: () => [...chosen],
    set(next) { chosen = next.filter((a) => actions.includes(a)).slice(0, maxLength); render(); },
  };
}
