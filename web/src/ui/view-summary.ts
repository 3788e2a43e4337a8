// The 3D view in words, for screen readers and for anyone: what is on stage (clip or history),
// the model, the actions, K and the futures' lengths, and the selected sample. Kept up to date in
// a polite live region that also describes the canvas (aria-describedby).
import type { Prediction } from '../predictor/types';
import { el } from './dom';

export interface ViewState {
  clip: string | null;
  clipFrames?: number;
  fps: number;
  prediction?: { model: string; start: number; historyFrames: number; p: Prediction } | null;
  selected: number | null;
  /** The samples list is shown (full controls); otherwise the labels over the figures number them. */
  list?: boolean;
}

const secs = (frames: number, fps: number) => `${(frames / fps).toFixed(2)} s`;
const pretty = (s: string) => s.replace(/_/g, ' ');

export function viewSummary(v: ViewState): string {
  if (!v.clip) return 'Nothing is on stage: pick a clip.';
  const pr = v.prediction;
  if (!pr) return `On stage: the clip ${pretty(v.clip)}${v.clipFrames ? `, ${v.clipFrames} frames (${secs(v.clipFrames, v.fps)})` : ''}. No prediction yet.`;
  const { p } = pr;
  const lengths = Array.from(p.lengths);
  const lo = Math.min(...lengths);
  const hi = Math.max(...lengths);
  const span = lo === hi ? `${secs(lo, v.fps)} each` : `${secs(lo, v.fps)} to ${secs(hi, v.fps)} long`;
  const actions = p.samples[0]?.segments.map((s) => s.action).filter((a): a is string => Boolean(a)) ?? [];
  const parts = [
    `History: frames ${pr.start}–${pr.start + pr.historyFrames - 1} of ${pretty(v.clip)}.`,
    `${pr.model}: ${p.k} ${p.k === 1 ? 'future' : 'futures'}, ${span}${actions.length ? `, actions ${actions.map(pretty).join(' then ')}` : ''}.`,
    p.warnings?.length ? `The history lies outside the model's training range (${p.warnings.map((w) => w.quantity).join(', ')}); the futures are shown anyway.` : '',
    p.k > 1 ? `Futures are numbered 1 to ${p.k} ${v.list === false ? 'by the labels over the figures' : 'in the list and over the figures'}; keys 1–9 select one, 0 shows all.` : '',
    v.selected !== null && v.selected < p.k ? `Future #${v.selected + 1} is selected (${secs(p.lengths[v.selected], v.fps)}).` : '',
  ];
  return parts.filter(Boolean).join(' ');
}

/** A visible, polite live summary below the stage; returns its updater. */
export function mountViewSummary(container: HTMLElement, describes: () => Element | null): (v: ViewState) => void {
  const id = 'view-summary';
  // A fixed height (scrolling when the text is long, so it takes focus) keeps the stage above from moving.
  const node = el('p', { id, class: 'view-summary muted', 'aria-live': 'polite', 'data-testid': 'view-summary', tabindex: 0 });
  container.append(node);
  return (v) => {
    const text = viewSummary(v);
    if (node.textContent !== text) node.textContent = text;
    const target = describes();
    if (target && target.getAttribute('aria-describedby') !== id) target.setAttribute('aria-describedby', id);
  };
}
