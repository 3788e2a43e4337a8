// What a prediction produced, method-independent: per-sample lengths, segments and numbers, the
// read-out of the whole set with a button that copies it as JSON, read-outs and curves from the
// predictor, and which sample is selected. Each sample's swatch is its figure's identity colour.
// The read-out leads with numbers in centimetres (per-joint error, pose spread); the field's
// whole-pose ADE, FDE and APD follow as "field units". Every number says what it is on hover (title)
// and on keyboard focus (a tooltip), and to screen readers (aria-describedby).
import { apdFactor } from '../metrics/readout';
import type { Prediction, SampleInfo } from '../predictor/types';
import { identityCss } from '../viewer/palette';
import { curvePlot } from './curve-plot';
import { el } from './dom';
import type { StageReadout } from './readout';

export interface PredictionExtras {
  /** The evaluation's numbers for this prediction (web/src/ui/readout.ts). */
  readout?: StageReadout | null;
  /** The read-out as JSON for the clipboard. */
  readoutJson?: () => string;
  /** The history lies outside the model's training envelope. */
  outOfRange?: boolean;
}

export interface PredictionPanelOptions {
  /** Where "how the numbers are defined" links to (the explainer's section on them). */
  numbersHelp?: string;
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
  if (unit === '%') return `${Number(v.toFixed(1))} %`;   // a share of K samples: "0 %", "33.3 %", "100 %"
  const digits = Math.abs(v) >= 10 ? 1 : Math.abs(v) >= 1 ? 2 : 3;
  return `${v.toFixed(digits)}${unit ? ` ${unit}` : ''}`;
}

const metres = (v: number) => v.toFixed(3);
/** Centimetres with one decimal: "8.4 cm". */
export const cm = (v: number) => `${v.toFixed(1)} cm`;
const percent = (v: number) => `${(100 * v).toFixed(v > 0 && v < 0.01 ? 2 : 1)}%`;

/** How a sample ended: Eq. 8's stop, the maximum length, or a cut at a bound (issue 19), which is not a stop. */
export function ending(s: SampleInfo): string {
  if (s.cut) return ' · cut (out of bounds)';
  const missed = s.segments.filter((g) => g.stopped === false).length;
  if (!missed) return s.stopped ? ' · stopped' : '';
  return s.segments.length === 1 ? ' · never stopped' : ` · did not stop in ${missed} of ${s.segments.length} actions`;
}

/** What each number is, in one line (the title, the focus tooltip and the accessible description). */
export const TIPS = {
  perJoint: 'Mean distance between each predicted joint and the ground truth\'s, over the joints and frames, for the closest of the K samples (root-relative: the body\'s travel is left out).',
  perJointEnd: 'The same mean per-joint distance to the ground truth at the last predicted frame, for the closest sample.',
  spread: 'How far apart the samples\' poses are: the mean per-joint distance between two samples, over every pair and frame (root-relative).',
  spreadEnd: 'The same mean per-joint distance between two samples, at the last predicted frame.',
  adeRel: 'Field ADE: the whole-pose L2 distance (18 joints x 3 coordinates) to the ground truth, averaged over frames, best of K, root-relative.',
  adeWorld: 'Field ADE in the world frame: the whole-pose L2 distance averaged over frames, best of K, with the body\'s travel.',
  fdeRel: 'Field FDE: the whole-pose L2 distance to the ground truth at the last frame, best of K, root-relative.',
  fdeWorld: 'Field FDE in the world frame: the whole-pose L2 distance at the last frame, best of K, with the body\'s travel.',
  apd: 'Field APD (DLow): the whole-pose L2 distance between two samples\' whole futures, over every pair; it grows with the futures\' length.',
  sample: 'This sample: its mean per-joint error to the ground truth (cm), its field ADE (m, root-relative), how much its bones change length against the history\'s, and the share of frames with a foot more than 3 cm below the floor.',
  sampleNoTruth: 'This sample: how much its bones change length against the history\'s, and the share of frames with a foot more than 3 cm below the floor.',
} as const;

let tipCount = 0;

/** A number with its explanation: title for the mouse, focusable (the panel shows a tooltip on focus), and
 *  described by a hidden element holding the same sentence. */
function metric(text: string, tip: string, tips: HTMLElement, attrs: Record<string, string> = {}): HTMLElement {
  const id = `mf-number-tip-${++tipCount}`;
  tips.append(el('span', { id }, tip));
  return el('strong', { class: 'metric', tabindex: 0, title: tip, 'data-tip': tip, 'aria-describedby': id, ...attrs }, text);
}

/** Show the focused number's explanation under it (hover has the title). */
function focusTooltips(container: HTMLElement): void {
  const tooltip = el('span', { class: 'metric-tooltip', role: 'tooltip', 'aria-hidden': 'true', hidden: true });
  container.addEventListener('focusin', (e) => {
    const target = (e.target as HTMLElement).closest?.('[data-tip]') as HTMLElement | null;
    if (!target || !container.contains(target)) { tooltip.hidden = true; return; }
    if (!tooltip.isConnected) container.append(tooltip);
    tooltip.textContent = target.dataset.tip ?? '';
    const box = container.getBoundingClientRect();
    const r = target.getBoundingClientRect();
    tooltip.style.top = `${r.bottom - box.top + 4}px`;
    tooltip.style.left = `${Math.max(0, Math.min(r.left - box.left, box.width - 260))}px`;
    tooltip.hidden = false;
  });
  container.addEventListener('focusout', () => { tooltip.hidden = true; });
}

export function mountPredictionPanel(container: HTMLElement, onSelect: (sample: number | null) => void,
  options: PredictionPanelOptions = {}): PredictionPanel {
  focusTooltips(container);
  let current: { p: Prediction; fps: number; ms: number; extras: PredictionExtras } | null = null;
  let selected: number | null = null;
  const render = () => {
    if (!current) return;
    const { p, fps, ms, extras } = current;
    const r = extras.readout ?? null;
    const summary = el('p', { class: 'muted prediction-summary', 'aria-live': 'polite' },
      `${p.k} ${p.k === 1 ? 'future' : 'futures'}, ${seconds(p.frames, fps)} at most, predicted in ${Math.round(ms)} ms.`,
      extras.outOfRange ? el('strong', { class: 'out-of-range-mark' }, ' Out of the training range.') : null);
    const tips = el('div', { class: 'metric-tips', hidden: true });
    // the predictor's own numbers explain themselves as the read-out's do (hover, focus, screen readers)
    const readouts = (p.readouts ?? []).map((x) => el('li', {}, el('span', { class: 'readout-label' }, x.label), ' ',
      metric(fmt(x.value, x.unit), x.about ?? `${x.label}, as the method measures it on these futures.`, tips)));
    const numbers = r ? readoutBlock(r, fps, tips, options.numbersHelp, extras.readoutJson) : null;
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
      const num = (text: string, tip: string, kind: string) => el('span', { class: 'sample-number', 'data-kind': kind, title: tip }, text);
      const tip = n?.perJointCm ? TIPS.sample : TIPS.sampleNoTruth;
      const line = n ? el('p', { class: 'sample-numbers muted', 'data-sample': i, tabindex: 0, 'data-tip': tip, title: tip,
        'aria-label': `Numbers of sample #${i + 1}` },
      ...(n.perJointCm ? [num(cm(n.perJointCm.ade), 'Mean per-joint error to the ground truth, over the frames (root-relative)', 'per_joint_cm'), ' per joint · ',
        'ADE ', num(`${metres(n.rootRelative!.ade)} m`, 'Field ADE: whole-pose L2 to the ground truth, over the frames (root-relative)', 'ade'), ' · '] : []),
      'bones ±', num(percent(n.boneLengthError), 'Mean change of bone length against the history\'s bones', 'bones'),
      ' · feet below floor ', num(percent(n.footBelowFloor), 'Share of frames with a foot more than 3 cm below the floor', 'feet')) : null;
      const cut = s.cut ? el('p', { class: 'sample-cut-note' }, `Cut at its last good frame, +${seconds(s.length, fps)} (${s.cut.reason}): ${s.cut.detail}`) : null;
      // One action: its line would repeat the button's length and ending, so its smoothness goes in the
      // button's title (unless flagged rough); a sequence lists every action.
      const single = s.segments.length === 1 && !s.segments[0].flagged;
      if (single && s.segments[0].smoothness !== undefined) button.title = `smoothness ${s.segments[0].smoothness.toExponential(1)} m²`;
      return el('li', { class: 'sample-item' }, button, line, cut, !single && (segs.length > 1 || s.segments.some((g) => g.smoothness !== undefined))
        ? el('ul', { class: 'segment-list' }, ...segs) : null);
    });
    // Transitions (where a sample's next action starts) as dots on its curve, when there are any.
    const marks = p.samples.map((s) => s.segments.length > 1 ? s.segments.slice(1).map((g) => g.start) : undefined);
    const dotted = marks.some((m) => m?.length);
    const curves = (p.curves ?? []).map((c) => el('figure', { class: 'curve' }, curvePlot(c, selected, undefined, undefined, marks),
      el('figcaption', {}, c.title, dotted ? '; dots: where the next action starts' : '')));
    const notes = p.notes.map((x) => el('p', { class: 'muted' }, x));
    // Up to 10 samples the list grows with the panel (no box scrolling inside the scrolling panel);
    // longer lists (K = 50) keep a short box of their own, which lays out only the rows in view.
    container.replaceChildren(summary, numbers ?? '',
      readouts.length ? el('ul', { class: 'readouts' }, ...readouts) : '',
      el('ol', { class: `sample-list${p.k > LONG_LIST ? ' sample-list-long' : ''}`, 'aria-label': 'Predicted samples' }, ...samples),
      ...curves, ...notes, tips);
  };
  return {
    show(p, fps, ms, extras = {}) { current = { p, fps, ms, extras }; selected = null; container.classList.remove('is-stale'); render(); },
    clear(text = 'No prediction yet.') { current = null; container.classList.remove('is-stale'); container.replaceChildren(el('p', { class: 'muted' }, text)); },
    stale(on) { container.classList.toggle('is-stale', on && current !== null); },
    select(sample) { selected = sample; render(); },
  };
}

/** Samples the list shows in full; more get a scrolling box of their own. */
export const LONG_LIST = 10;

/** The numbers in cm, then the field's in metres, what each means, and "Copy numbers". */
function readoutBlock(r: StageReadout, fps: number, tips: HTMLElement, help?: string, json?: () => string): HTMLElement {
  const copy = el('button', { type: 'button', class: 'text-button copy-numbers', 'data-testid': 'copy-numbers' }, 'Copy numbers (JSON)');
  const note = el('span', { class: 'muted copy-status', role: 'status' });
  copy.addEventListener('click', () => {
    const text = json?.() ?? '';
    const done = navigator.clipboard?.writeText(text);
    if (!done) { note.textContent = 'This browser gives the page no clipboard.'; return; }
    done.then(() => { note.textContent = 'Copied.'; }, () => { note.textContent = 'The clipboard refused.'; });
  });
  // The numbers people read first: a small table, average and last frame side by side.
  const leadRows: HTMLElement[] = [];
  if (r.bestPerJointCm) {
    leadRows.push(el('tr', { 'data-metric': 'per-joint' }, el('th', { scope: 'row' }, 'Per-joint error', el('span', { class: 'readout-sub' }, r.k > 1 ? `best of ${r.k}, vs. ground truth` : 'vs. ground truth')),
      el('td', { 'data-kind': 'over_frames' }, metric(cm(r.bestPerJointCm.ade), TIPS.perJoint, tips)),
      el('td', { 'data-kind': 'last' }, metric(cm(r.bestPerJointCm.fde), TIPS.perJointEnd, tips))));
  }
  if (r.k > 1) {
    leadRows.push(el('tr', { 'data-metric': 'spread' }, el('th', { scope: 'row' }, 'Pose spread', el('span', { class: 'readout-sub' }, `between the ${r.k} samples`)),
      el('td', { 'data-kind': 'over_frames' }, metric(cm(r.spreadCm.overFrames), TIPS.spread, tips)),
      el('td', { 'data-kind': 'last' }, metric(cm(r.spreadCm.last), TIPS.spreadEnd, tips))));
  }
  const lead = leadRows.length
    ? el('table', { class: 'readout-lead' },
      el('thead', {}, el('tr', {}, el('td', {}), el('th', { scope: 'col' }, 'average'), el('th', { scope: 'col' }, 'at the end'))),
      el('tbody', {}, ...leadRows))
    : null;
  const uncovered = r.best ? null : el('p', { class: 'muted readout-uncovered' },
    `No error against the ground truth: the clip's ground truth covers ${seconds(r.truthFrames, fps)} of the ${seconds(r.frames, fps)} predicted.`);
  const rows: [string, number, number, string, string][] = r.best
    ? [['best-of-K ADE', r.best.rootRelative.ade, r.best.world.ade, TIPS.adeRel, TIPS.adeWorld],
      ['best-of-K FDE', r.best.rootRelative.fde, r.best.world.fde, TIPS.fdeRel, TIPS.fdeWorld]]
    : [];
  const field = el('div', { class: 'readout-field' },
    el('p', { class: 'readout-field-title' }, 'Field units (whole-pose L2, metres)'),
    rows.length
      ? el('table', { class: 'readout-table' },
        el('thead', {}, el('tr', {}, el('th', { scope: 'col' }, `K = ${r.k}`), el('th', { scope: 'col' }, 'root-relative'), el('th', { scope: 'col' }, 'world'))),
        el('tbody', {}, ...rows.map(([label, rel, world, relTip, worldTip]) => el('tr', { 'data-metric': label },
          el('th', { scope: 'row' }, label),
          el('td', { 'data-kind': 'root_relative' }, metric(`${metres(rel)} m`, relTip, tips)),
          el('td', { 'data-kind': 'world' }, metric(`${metres(world)} m`, worldTip, tips))))))
      : null,
    // APD needs two samples (one future has none)
    r.k > 1 ? el('p', { class: 'readout-apd' }, el('span', { class: 'readout-label' }, 'APD (root-relative) '), metric(`${metres(r.apd)} m`, TIPS.apd, tips)) : null);
  const about = el('p', { class: 'muted readout-about' },
    'The field\'s ADE and FDE add the 18 joints\' distances into one whole-pose distance: about √18 ≈ 4.2 × the per-joint mean (more when a few joints carry the error). ',
    r.k > 1 ? `APD puts each sample's whole future, ${r.frames} frames × 18 joints, into one vector: at least √(18 × ${r.frames}) ≈ ${apdFactor(r.frames).toFixed(0)} × the pose spread. ` : '',
    help ? el('a', { href: help, target: '_blank', rel: 'noopener', class: 'readout-help' }, 'How the numbers are defined') : null);
  return el('div', { class: 'stage-readout', 'data-testid': 'readout' }, lead, uncovered, field, about, el('div', { class: 'share-row' }, copy, note));
}
