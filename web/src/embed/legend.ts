// The minimal embed's key to its figures: the history, the ground truth and each sample by number,
// in the colours the viewer draws them (viewer/palette.ts is the one place they are defined). It
// follows what is on stage (the ground truth hidden, K changed), wraps in a narrow widget, and is not
// a control, so it takes no tab stop.
import { el } from '../ui/dom';
import { identityCss } from '../viewer/palette';
import type { TrackRole } from '../viewer/tracks';
import type { SkeletonView } from '../viewer/viewer';

/** Samples named one by one; more are counted. */
const SAMPLES_NAMED = 10;
const NAMES: Record<Exclude<TrackRole, 'prediction'>, string> = { history: 'history', truth: 'ground truth', clip: 'clip' };

function entry(colour: string, text: string, data: Record<string, string>): HTMLLIElement {
  const swatch = el('span', { class: 'mini-swatch', 'aria-hidden': 'true' });
  swatch.style.background = colour; // CSSOM, not a style attribute: a strict style-src allows it
  const li = el('li', {}, swatch, text);
  Object.assign(li.dataset, data);
  return li;
}

/** The entries for what is on stage, in the order history, ground truth, clip, samples by number. */
export function legendEntries(shown: readonly { role: TrackRole; sample?: number }[]): HTMLLIElement[] {
  const out: HTMLLIElement[] = [];
  for (const role of ['history', 'truth', 'clip'] as const) {
    if (shown.some((t) => t.role === role)) out.push(entry(identityCss(role), NAMES[role], { role }));
  }
  // compare mode shows each method's samples in the same colours: one entry per number
  const samples = [...new Set(shown.filter((t) => t.role === 'prediction').map((t) => t.sample ?? 0))].sort((a, b) => a - b);
  for (const s of samples.slice(0, SAMPLES_NAMED)) out.push(entry(identityCss('prediction', s), `#${s + 1}`, { role: 'prediction', sample: String(s) }));
  if (samples.length > SAMPLES_NAMED) out.push(el('li', { class: 'mini-legend-more' }, `+${samples.length - SAMPLES_NAMED} more`));
  return out;
}

export function mountMiniLegend(container: HTMLElement, view: SkeletonView): void {
  const list = el('ul', { class: 'mini-legend', 'aria-label': 'Figures on stage', 'data-testid': 'mini-legend' });
  container.replaceChildren(list);
  let last = '';
  const refresh = () => {
    const shown = view.shownTracks();
    const key = shown.map((t) => `${t.role}${t.sample ?? ''}`).join(' ');
    if (key === last) return;
    last = key;
    list.replaceChildren(...legendEntries(shown));
  };
  view.onTracks(refresh);
  refresh();
}
