// What a prediction produced, method-independent: per-sample lengths and segments, read-outs,
// curves, and which sample is selected.
import type { Prediction, SampleInfo } from '../predictor/types';
import { curvePlot, sampleColour } from './curve-plot';
import { el } from './dom';

export interface PredictionPanel {
  show(p: Prediction, fps: number, ms: number): void;
  clear(text?: string): void;
  select(sample: number | null): void;
}

function fmt(v: number, unit?: string): string {
  if (!unit && Number.isInteger(v)) return String(v);   // counts, e.g. flagged transitions
  const digits = Math.abs(v) >= 10 ? 1 : Math.abs(v) >= 1 ? 2 : 3;
  return `${v.toFixed(digits)}${unit ? ` ${unit}` : ''}`;
}

/** ' · never stopped' (one segment) or ' · did not stop in 2 of 3 actions'; '' when every segment stopped. */
function notStopped(s: SampleInfo): string {
  const missed = s.segments.filter((g) => g.stopped === false).length;
  if (!missed) return '';
  return s.segments.length === 1 ? ' · never stopped' : ` · did not stop in ${missed} of ${s.segments.length} actions`;
}

export function mountPredictionPanel(container: HTMLElement, onSelect: (sample: number | null) => void): PredictionPanel {
  let current: { p: Prediction; fps: number; ms: number } | null = null;
  let selected: number | null = null;
  const render = () => {
    if (!current) return;
    const { p, fps, ms } = current;
    const summary = el('p', { class: 'muted prediction-summary', 'aria-live': 'polite' },
      `${p.k} ${p.k === 1 ? 'future' : 'futures'}, ${fmt(p.frames / fps)} s at most, predicted in ${Math.round(ms)} ms.`);
    const readouts = (p.readouts ?? []).map((r) => el('li', {}, el('span', { class: 'readout-label' }, r.label), ' ', el('strong', {}, fmt(r.value, r.unit))));
    const samples = p.samples.map((s, i) => {
      const segs = s.segments.map((g) => {
        const bits = [g.action ? g.action.replace(/_/g, ' ') : null, `${fmt(g.length / fps)} s`,
          g.smoothness !== undefined ? `smoothness ${g.smoothness.toExponential(1)} m²${g.flagged ? ' (rough)' : ''}` : null,
          g.stopped === false ? 'did not stop' : null];
        return el('li', { class: g.flagged ? 'segment-flagged' : '' }, bits.filter(Boolean).join(' · '));
      });
      const button = el('button', { type: 'button', class: 'sample-button', 'aria-pressed': String(selected === i),
        'data-sample': i }, el('span', { class: 'sample-swatch', style: `background:${sampleColour(i)}`, 'aria-hidden': 'true' }),
      `#${i + 1} · ${fmt(s.length / fps)} s${notStopped(s)}`);
      button.addEventListener('click', () => onSelect(selected === i ? null : i));
      return el('li', { class: 'sample-item' }, button, segs.length > 1 || s.segments.some((g) => g.smoothness !== undefined)
        ? el('ul', { class: 'segment-list' }, ...segs) : null);
    });
    // Transitions (where a sample's next action starts) as dots on its curve, when there are any.
    const marks = p.samples.map((s) => s.segments.length > 1 ? s.segments.slice(1).map((g) => g.start) : undefined);
    const dotted = marks.some((m) => m?.length);
    const curves = (p.curves ?? []).map((c) => el('figure', { class: 'curve' }, curvePlot(c, selected, undefined, undefined, marks),
      el('figcaption', {}, c.title, dotted ? '; dots: where the next action starts' : '')));
    const notes = p.notes.map((n) => el('p', { class: 'muted' }, n));
    container.replaceChildren(summary,
      readouts.length ? el('ul', { class: 'readouts' }, ...readouts) : '',
      el('ol', { class: 'sample-list', 'aria-label': 'Predicted samples' }, ...samples), ...curves, ...notes);
  };
  return {
    show(p, fps, ms) { current = { p, fps, ms }; selected = null; render(); },
    clear(text = 'No prediction yet.') { current = null; container.replaceChildren(el('p', { class: 'muted' }, text)); },
    select(sample) { selected = sample; render(); },
  };
}
