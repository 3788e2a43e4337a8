// The notice over the stage when a method refuses a history (issue 29 item 7): one sentence saying so,
// the method's reason behind Details, and the way forward: the nearest start the method accepts in one
// click (ui/start-search.ts), or that the clip has none. It sits where the out-of-range notice sits;
// the two never show together (a refusal has no futures to warn about).
import { el } from './dom';
import { summarise } from './messages';

export interface Refusal {
  /** The model's readable name. */
  model: string;
  /** The refused history: first frame and length, and the clip's readable name. */
  start: number;
  frames: number;
  clip: string;
  /** The method's own reason. */
  reason: string;
  /** Whether another start could help: false when the request itself is refused (K, actions…). */
  searchable: boolean;
}

export type SearchState =
  | { kind: 'searching'; tried: number; of: number }
  | { kind: 'found'; start: number }
  | { kind: 'none'; tried: number };

export interface RefusalNotice {
  show(r: Refusal | null): void;
  search(s: SearchState): void;
}

/** The notice's one sentence. */
export function refusalSentence(r: Refusal): string {
  return r.searchable
    ? `${r.model} cannot predict from this history (frames ${r.start}–${r.start + r.frames - 1} of ${r.clip}), so no futures are shown.`
    : `${r.model} cannot predict with these settings, so no futures are shown.`;
}

export function mountRefusalNotice(container: HTMLElement, onStart: (start: number) => void): RefusalNotice {
  const node = el('div', { class: 'stage-notice refusal-notice-box', hidden: true });
  container.append(node);
  let current: Refusal | null = null;
  const way = el('p', { class: 'refusal-way', 'data-testid': 'refusal-way' });
  return {
    show(r) {
      current = r;
      node.hidden = !r;
      if (!r) { node.replaceChildren(); return; }
      const why = summarise(r.reason);
      way.replaceChildren(r.searchable ? `Looking for the nearest start ${r.model} accepts…` : why.summary);
      node.replaceChildren(el('div', { class: 'range-notice refusal-notice', role: 'status', 'data-testid': 'refusal-notice' },
        el('span', { class: 'refusal-text' }, refusalSentence(r)),
        way,
        el('details', { class: 'range-details' }, el('summary', {}, 'Why'), el('p', { class: 'muted' }, r.reason))));
    },
    search(s) {
      if (!current?.searchable) return;
      const model = current.model;
      if (s.kind === 'searching') way.replaceChildren(`Looking for the nearest start ${model} accepts… (${s.tried} of ${s.of} tried)`);
      else if (s.kind === 'none') {
        way.replaceChildren(s.tried > 0
          ? `${model} accepts none of the ${s.tried + 1} history starts tried across this clip: pick another clip or model.`
          : `The search for a start ${model} accepts stopped: pick another start, clip or model.`);
        way.dataset.found = 'none';
      } else {
        const go = el('button', { type: 'button', class: 'text-button refusal-go', 'data-testid': 'refusal-go', 'data-start': String(s.start) },
          `Start the history at frame ${s.start}`);
        go.addEventListener('click', () => onStart(s.start));
        way.replaceChildren(`The nearest start ${model} accepts is frame ${s.start}: `, go);
        way.dataset.found = String(s.start);
      }
    },
  };
}
