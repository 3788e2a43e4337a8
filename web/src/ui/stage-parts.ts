// What sits on and beside the stage: the toolbar (legend of every figure, the layout switch, reset
// view, the offline state), the phase label over the figures, the status line naming what is shown,
// and the out-of-range notice. None of them moves or resizes the stage: the toolbar has one line,
// and whatever lies over the stage is absolutely placed.
import type { RangeWarning } from '../predictor/types';
import type { LayoutMode } from '../viewer/layout';
import { identityCss } from '../viewer/palette';
import { el } from './dom';
import { icon } from './icons';
import { phaseLabel } from './timeline';

export interface LegendState {
  clip?: string | null;
  history: boolean;
  truth: boolean;
  /** Samples on stage, and which are cut. */
  k: number;
  cut?: number[];
}

export interface StageToolbar {
  root: HTMLElement;
  setLayout(mode: LayoutMode): void;
  setLegend(s: LegendState | null): void;
  setOffline(text: string | null, state?: string): void;
}

const LAYOUTS: { mode: LayoutMode; label: string }[] = [
  { mode: 'overlay', label: 'Overlaid' },
  { mode: 'side', label: 'Side by side' },
];
/** Samples the legend names one by one; more are summarised. */
const LEGEND_SAMPLES = 10;

const swatch = (colour: string, cls = '') => el('span', { class: `swatch figure-swatch ${cls}`.trim(), style: `background: ${colour}`, 'aria-hidden': 'true' });

export function mountStageToolbar(container: HTMLElement, initial: LayoutMode,
  handlers: { onLayout(mode: LayoutMode): void; onResetView(): void }): StageToolbar {
  const legend = el('ul', { class: 'legend', 'aria-label': 'Figures on stage', 'data-testid': 'legend', tabindex: 0 });
  const radios = LAYOUTS.map(({ mode, label }) => {
    const input = el('input', { type: 'radio', name: 'layout', value: mode, checked: mode === initial });
    input.addEventListener('change', () => { if (input.checked) handlers.onLayout(mode); });
    return { mode, input, label: el('label', { class: 'segment' }, input, el('span', {}, label)) };
  });
  const reset = el('button', { type: 'button', class: 'icon-button small-icon-button', 'aria-label': 'Reset the camera', title: 'Reset the camera' }, icon('reset'));
  reset.addEventListener('click', () => handlers.onResetView());
  const offline = el('span', { class: 'offline-state muted', role: 'status', 'data-testid': 'offline-state', hidden: true });
  // Two parts that never wrap inside: the legend, and the controls; a narrow stage puts them on two lines.
  const root = el('div', { class: 'stage-toolbar' },
    legend,
    el('div', { class: 'toolbar-controls' },
      el('fieldset', { class: 'segmented layout-switch' }, el('legend', { class: 'visually-hidden' }, 'Layout (L)'),
        el('span', { class: 'layout-title', 'aria-hidden': 'true' }, 'Layout'), ...radios.map((r) => r.label)),
      reset, offline));
  container.replaceChildren(root);
  return {
    root,
    setLayout(mode) { for (const r of radios) r.input.checked = r.mode === mode; },
    setLegend(s) {
      const items: HTMLElement[] = [];
      if (!s) { legend.replaceChildren(); return; }
      if (s.clip) items.push(el('li', {}, swatch(identityCss('clip')), `clip ${s.clip.replace(/_/g, ' ')}`));
      if (s.history) items.push(el('li', { 'data-role': 'history' }, swatch(identityCss('history')), 'history'));
      if (s.truth) items.push(el('li', { 'data-role': 'truth' }, swatch(identityCss('truth')), 'ground truth'));
      if (s.k > 0) {
        const shown = Math.min(s.k, LEGEND_SAMPLES);
        items.push(el('li', { 'data-role': 'prediction' },
          el('span', { class: 'swatch-run', 'aria-hidden': 'true' }, ...Array.from({ length: shown }, (_, i) => swatch(identityCss('prediction', i), 'swatch-sample'))),
          s.k === 1 ? 'sample #1' : `samples #1–${s.k}${s.k > shown ? ` (first ${shown} shown)` : ''}`,
          s.cut?.length ? ` (${s.cut.length > 2 ? `${s.cut.length === s.k ? 'all' : s.cut.length}` : s.cut.map((i) => `#${i + 1}`).join(', ')} cut)` : ''));
      }
      items.push(el('li', { class: 'legend-limbs' }, swatch('var(--left)'), 'left', swatch('var(--right)'), 'right limbs'));
      legend.replaceChildren(...items);
    },
    setOffline(text, state) {
      offline.hidden = text === null;
      offline.textContent = text ?? '';
      if (state) offline.dataset.state = state; else delete offline.dataset.state;
    },
  };
}

/** "history" / "+0.8 s" over the stage's corner. */
export function mountPhaseLabel(viewer: HTMLElement): (frame: number, fps: number, origin: number | null) => void {
  const label = el('p', { class: 'phase-label', 'data-testid': 'phase', 'aria-hidden': 'true' });
  viewer.append(label);
  return (frame, fps, origin) => {
    const text = origin === null ? '' : phaseLabel(frame, fps, origin);
    if (label.textContent !== text) label.textContent = text;
    label.dataset.phase = origin !== null && origin > 0 && frame < origin ? 'history' : 'future';
    label.hidden = text === '';
  };
}

export type ShownState = 'shown' | 'stale' | 'busy' | 'error' | 'clip';

/** The line under the stage that always names what the figures are: model, history, seed, controls. */
export function mountStageStatus(container: HTMLElement): (text: string, state: ShownState) => void {
  const node = el('p', { class: 'stage-status', 'data-testid': 'stage-status', 'aria-live': 'polite' });
  container.replaceChildren(node);
  return (text, state) => {
    if (node.textContent !== text) { node.textContent = text; node.title = text; }
    node.dataset.state = state;
  };
}

/** Findings that are not a range (web/src/predictor/history.ts): their own sentence says what to do. */
const OWN_SENTENCE = new Set(['handedness', 'motion', 'body_scale']);

/** The notice's one sentence. The warnings come most likely cause first (history.ts ordered), so a
 *  reflected or frozen history, or a rescaled body, leads with its own sentence, not "out of range". */
export function rangeHeadline(warnings: RangeWarning[], model: string): string {
  const [first] = warnings;
  if (OWN_SENTENCE.has(first.quantity)) {
    const more = warnings.length > 1 ? ` (${warnings.length - 1} more under Details)` : '';
    return `${first.message}${more} The futures are shown anyway.`;
  }
  return `Out of range: this history lies outside what ${model} was trained on (${warnings.length === 1 ? first.quantity : `${warnings.length} quantities`}); the futures are shown anyway.`;
}

/** One sentence over the stage when the history lies outside the model's training envelope; the
 *  quantities, values and ranges behind a toggle. */
export function mountRangeNotice(container: HTMLElement): (warnings: RangeWarning[] | null, model: string) => void {
  container.replaceChildren();
  container.hidden = true;
  return (warnings, model) => {
    if (!warnings?.length) { container.replaceChildren(); container.hidden = true; return; }
    const fmt = (v: number) => (Math.abs(v) >= 100 ? v.toFixed(0) : Math.abs(v) >= 10 ? v.toFixed(1) : v.toFixed(2));
    const unit = (w: RangeWarning) => (w.unit ? ` ${w.unit}` : '');
    container.hidden = false;
    container.replaceChildren(el('div', { class: 'range-notice', role: 'status', 'data-testid': 'range-notice' },
      el('span', { class: 'range-notice-text' }, rangeHeadline(warnings, model)),
      el('details', { class: 'range-details' }, el('summary', {}, 'Details'),
        el('ul', {}, ...warnings.map((w) => el('li', { 'data-quantity': w.quantity },
          ...(OWN_SENTENCE.has(w.quantity) ? [] : [el('strong', {}, w.quantity), `: ${fmt(w.value)}${unit(w)}; training range ${fmt(w.min)}–${fmt(w.max)}${unit(w)}. `]),
          el('span', { class: 'muted' }, w.message)))))));
  };
}
