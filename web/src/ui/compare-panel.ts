// The side panel's "Compare methods" section: which other models run beside the page's on the same
// history end, seed, K and horizon (ui/compare.ts), and each row's read-out in units people read (the
// per-joint error against the ground truth and the pose spread, in cm: ui/readout.ts).
import type { ModelEntry } from '../contract/types';
import { MAX_COMPARED, rowNumbers, type CompareRow } from './compare';
import { el } from './dom';

export interface ComparePanel {
  /** The other models chosen (ids, in the manifest's order), beside the page's. */
  chosen(): string[];
  /** Choose these (a link's); the page's own model is left out. */
  set(ids: string[]): void;
  /** The page's model changed: it cannot also be a companion. */
  setPrimary(id: string): void;
  /** The rows on stage (null: compare mode is off or nothing is shown). */
  show(rows: readonly CompareRow[] | null, historyEnd?: number): void;
  stale(on: boolean): void;
}

const cm = (v: number | null) => (v === null ? '–' : `${v.toFixed(1)} cm`);

export function mountComparePanel(container: HTMLElement, models: readonly ModelEntry[], primary: string,
  onChange: () => void): ComparePanel {
  let page = primary;
  const boxes = new Map<string, HTMLInputElement>();
  // one model a line (the page's styles are not this file's: the layout is set here)
  const list = el('div', { class: 'compare-models', style: 'display: flex; flex-direction: column; gap: 0.2rem; margin: 0.3rem 0' });
  const rowsView = el('ol', { class: 'compare-rows', 'data-testid': 'compare-rows', hidden: true });
  for (const m of models) {
    const box = el('input', { type: 'checkbox', id: `compare-${m.id}`, value: m.id });
    box.addEventListener('change', () => { limit(); onChange(); });
    boxes.set(m.id, box);
    list.append(el('label', { class: 'compare-model', for: `compare-${m.id}` }, box, ` ${m.label}`));
  }
  /** The page's model is always on stage; at most MAX_COMPARED models in all. */
  const limit = () => {
    const n = [...boxes.values()].filter((b) => b.checked).length;
    for (const [id, b] of boxes) {
      b.disabled = id === page || (!b.checked && n >= MAX_COMPARED - 1);
      (b.parentElement as HTMLElement).hidden = id === page;
    }
  };
  container.replaceChildren(
    el('p', { class: 'muted' }, `Run up to ${MAX_COMPARED - 1} more models beside the one above on the same history end, seed, K and horizon: `
      + 'one labelled row per model on stage, each read out below (per-joint error against the ground truth, spread between samples). '
      + 'A model with another history length reads its own last frames; a deterministic one shows one future.'),
    list, rowsView);
  limit();
  return {
    chosen: () => models.filter((m) => m.id !== page && boxes.get(m.id)!.checked).map((m) => m.id),
    set(ids) {
      for (const [id, b] of boxes) b.checked = id !== page && ids.includes(id);
      limit();
    },
    setPrimary(id) {
      page = id;
      const b = boxes.get(id);
      if (b) b.checked = false;
      limit();
    },
    show(rows) {
      rowsView.hidden = !rows;
      rowsView.classList.remove('stale');
      rowsView.style.opacity = '';
      rowsView.title = '';
      if (!rows) { rowsView.replaceChildren(); return; }
      rowsView.replaceChildren(...rows.map((r, i) => {
        const numbers = rowNumbers(r);
        const body = numbers
          ? el('span', { class: 'compare-numbers' },
            el('span', { title: 'Mean per-joint error of the best of the K samples against the ground truth (root-relative, cm)' },
              `per-joint error ${cm(numbers.perJointCm)}`),
            ' · ',
            el('span', { title: 'Mean per-joint distance between pairs of samples, averaged over the frames (cm); one future has none' },
              numbers.k > 1 ? `spread ${cm(numbers.spreadCm)}` : 'one future (deterministic)'))
          : el('span', { class: 'compare-error' }, r.error ?? 'no futures');
        return el('li', { class: 'compare-row', 'data-model': r.entry.id, 'data-row': String(i), 'data-plant-feet': String(r.plantFeet) },
          el('strong', {}, r.entry.label),
          ` · K = ${numbers?.k ?? '–'} · frames ${r.start}–${r.start + r.entry.params.history_frames - 1}`,
          r.plantFeet ? '' : el('span', { title: 'The method\'s own root travel: the feet were not planted on the floor' }, ' · own root'),
          ': ', body);
      }));
    },
    stale(on) {
      rowsView.classList.toggle('stale', on);
      rowsView.title = on ? 'Out of date: new futures are on their way' : '';
      rowsView.style.opacity = on ? '0.55' : '';
    },
  };
}
