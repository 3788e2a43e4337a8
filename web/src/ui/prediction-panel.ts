// What a prediction produced, method-independent: per-sample lengths, segments and numbers, the
// read-out of the whole set (best of K, APD) with a button that copies it as JSON, read-outs and
// curves from the predictor, and which sample is selected. Each sample's swatch is its figure's
// identity colour.
import type { Prediction, SampleInfo } from '../predictor/types';
import { identityCss } from '../viewer/palette';
import { curvePlot } from './curve-plot';
import { el } from './dom';
import type { Errors, StageReadout } from './readout';

export interface PredictionExtras {
  /** The evaluation's numbers for this prediction (web/src/ui/readout.ts). */
  readout?: StageReadout | null;
  /** The read-out as JSON for the clipboard. */
  readoutJson?: () => string;
  /** The history lies outside the model's training envelope. */
  outOfRange?: boolean;
}

export interface PredictionPanel {
  show(p: Prediction, fps: number, ms: number, extras?: PredictionExtras): void;
  clear(text?: string): void;
  /** The futures listed no longer match the inputs (a new prediction is on its way). */
  stale(on: boolean): void;
  select(sample: number | null): void;
}

/** Seconds, always with two decimals: "0.97 s", "1.00 s", "1.50 s". */
export function seconds(frames: number, fps: number): string {
  return `${(frames / fps).toFixed(2)} s`;
}

function fmt(v: number, unit?: string): string {
  if (!unit && Number.isInteger(v)) return String(v);   // counts, e.g. flagged transitions
  const digits = Math.abs(v) >= 10 ? 1 : Math.abs(v) >= 1 ? 2 : 3;
  return `${v.toFixed(digits)}${unit ? ` ${unit}` : ''}`;
}

const metres = (v: number) => v.toFixed(3);
const percent = (v: number) => `${(100 * v).toFixed(v > 0 && v < 0.01 ? 2 : 1)}%`;

/** How a sample ended: Eq. 8's stop, the maximum length, or a cut at a bound (issue 19), which is not a stop. */
export function ending(s: SampleInfo): string {
  if (s.cut) return ' · cut (out of bounds)';
  const missed = s.segments.filter((g) => g.stopped === false).length;
  if (!missed) return s.stopped ? ' · stopped' : '';
  return s.segments.length === 1 ? ' · never stopped' : ` · did not stop in ${missed} of ${s.segments.length} actions`;
}

const pair = (rr?: Errors, world?: Errors, key: 'ade' | 'fde' = 'ade') =>
  (rr && world ? `${metres(rr[key])} / ${metres(world[key])}` : '–');

export function mountPredictionPanel(container: HTMLElement, onSelect: (sample: number | null) => void): PredictionPanel {
  let current: { p: Prediction; fps: number; ms: number; extras: PredictionExtras } | null = null;
  let selected: number | null = null;
  const render = () => {
    if (!current) return;
    const { p, fps, ms, extras } = current;
    const r = extras.readout ?? null;
    const summary = el('p', { class: 'muted prediction-summary', 'aria-live': 'polite' },
      `${p.k} ${p.k === 1 ? 'future' : 'futures'}, ${seconds(p.frames, fps)} at most, predicted in ${Math.round(ms)} ms.`,
      extras.outOfRange ? el('strong', { class: 'out-of-range-mark' }, ' Out of the training range.') : null);
    const readouts = (p.readouts ?? []).map((x) => el('li', {}, el('span', { class: 'readout-label' }, x.label), ' ', el('strong', {}, fmt(x.value, x.unit))));
    const numbers = r ? readoutBlock(r, fps, extras.readoutJson) : null;
    const samples = p.samples.map((s, i) => {
      const segs = s.segments.map((g) => {
        const bits = [g.action ? g.action.replace(/_/g, ' ') : null, seconds(g.length, fps),
          g.smoothness !== undefined ? `smoothness ${g.smoothness.toExponential(1)} m²${g.flagged ? ' (rough)' : ''}` : null,
          g.stopped === false ? 'did not stop' : null];
        return el('li', { class: g.flagged ? 'segment-flagged' : '' }, bits.filter(Boolean).join(' · '));
      });
      const button = el('button', { type: 'button', class: `sample-button${s.cut ? ' sample-cut' : ''}`, 'aria-pressed': String(selected === i),
        'data-sample': i, 'data-cut': s.cut ? 'true' : undefined },
      el('span', { class: 'sample-swatch', style: `background:${identityCss('prediction', i)}`, 'aria-hidden': 'true', 'data-testid': 'sample-swatch' }),
      `#${i + 1} · ${seconds(s.length, fps)}${ending(s)}`);
      button.addEventListener('click', () => onSelect(selected === i ? null : i));
      const n = r?.samples[i];
      const line = n ? el('p', { class: 'sample-numbers muted', 'data-sample': i },
        n.rootRelative ? `ADE ${pair(n.rootRelative, n.world)} m · FDE ${pair(n.rootRelative, n.world, 'fde')} m · ` : '',
        `bones ±${percent(n.boneLengthError)} · feet below floor ${percent(n.footBelowFloor)}`) : null;
      const cut = s.cut ? el('p', { class: 'sample-cut-note' }, `Cut at its last good frame, +${seconds(s.length, fps)} (${s.cut.reason}): ${s.cut.detail}`) : null;
      return el('li', { class: 'sample-item' }, button, line, cut, segs.length > 1 || s.segments.some((g) => g.smoothness !== undefined)
        ? el('ul', { class: 'segment-list' }, ...segs) : null);
    });
    // Transitions (where a sample's next action starts) as dots on its curve, when there are any.
    const marks = p.samples.map((s) => s.segments.length > 1 ? s.segments.slice(1).map((g) => g.start) : undefined);
    const dotted = marks.some((m) => m?.length);
    const curves = (p.curves ?? []).map((c) => el('figure', { class: 'curve' }, curvePlot(c, selected, undefined, undefined, marks),
      el('figcaption', {}, c.title, dotted ? '; dots: where the next action starts' : '')));
    const notes = p.notes.map((x) => el('p', { class: 'muted' }, x));
    container.replaceChildren(summary, numbers ?? '',
      readouts.length ? el('ul', { class: 'readouts' }, ...readouts) : '',
      el('ol', { class: 'sample-list', 'aria-label': 'Predicted samples' }, ...samples), ...curves, ...notes);
  };
  return {
    show(p, fps, ms, extras = {}) { current = { p, fps, ms, extras }; selected = null; container.classList.remove('is-stale'); render(); },
    clear(text = 'No prediction yet.') { current = null; container.classList.remove('is-stale'); container.replaceChildren(el('p', { class: 'muted' }, text)); },
    stale(on) { container.classList.toggle('is-stale', on && current !== null); },
    select(sample) { selected = sample; render(); },
  };
}

/** Best of K, APD and what they mean, with "Copy numbers". */
function readoutBlock(r: StageReadout, fps: number, json?: () => string): HTMLElement {
  const copy = el('button', { type: 'button', class: 'text-button copy-numbers', 'data-testid': 'copy-numbers' }, 'Copy numbers (JSON)');
  const note = el('span', { class: 'muted copy-status', role: 'status' });
  copy.addEventListener('click', () => {
    const text = json?.() ?? '';
    const done = navigator.clipboard?.writeText(text);
    if (!done) { note.textContent = 'This browser gives the page no clipboard.'; return; }
    done.then(() => { note.textContent = 'Copied.'; }, () => { note.textContent = 'The clipboard refused.'; });
  });
  const rows: [string, string, string][] = r.best
    ? [['best-of-K ADE', metres(r.best.rootRelative.ade), metres(r.best.world.ade)],
      ['best-of-K FDE', metres(r.best.rootRelative.fde), metres(r.best.world.fde)]]
    : [];
  return el('div', { class: 'stage-readout', 'data-testid': 'readout' },
    rows.length
      ? el('table', { class: 'readout-table' },
        el('thead', {}, el('tr', {}, el('th', { scope: 'col' }, `K = ${r.k}`), el('th', { scope: 'col' }, 'root-relative'), el('th', { scope: 'col' }, 'world'))),
        el('tbody', {}, ...rows.map(([label, rel, world]) => el('tr', { 'data-metric': label },
          el('th', { scope: 'row' }, label), el('td', { 'data-kind': 'root_relative' }, `${rel} m`), el('td', { 'data-kind': 'world' }, `${world} m`)))))
      : el('p', { class: 'muted readout-uncovered' },
        `No ADE or FDE: the clip's ground truth covers ${seconds(r.truthFrames, fps)} of the ${seconds(r.frames, fps)} predicted.`),
    el('p', { class: 'readout-apd' }, el('span', { class: 'readout-label' }, 'APD (root-relative) '), el('strong', {}, `${metres(r.apd)} m`)),
    el('p', { class: 'muted readout-about' }, 'As the evaluation defines them (export/eval/metrics.py): whole-pose L2 in metres, each best of K on its own; per sample below: ADE and FDE root-relative / world, bone-length error, feet below the floor.'),
    el('div', { class: 'share-row' }, copy, note));
}
