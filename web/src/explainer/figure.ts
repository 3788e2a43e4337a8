// The parts every figure has: a titled section with text, controls, a chart slot, read-outs and
// the citation of the paper and equation it shows.
import { el } from '../ui/dom';

export interface FigureShell {
  root: HTMLElement;
  controls: HTMLElement;
  chart: HTMLElement;
  readouts: HTMLElement;
  /** A line for model status ("not available", "loading…", errors). */
  status: HTMLElement;
}

export function figureShell(host: HTMLElement, id: string, title: string, intro: (Node | string)[], cite: string): FigureShell {
  const heading = el('h2', { id: `${id}-title` }, title);
  const controls = el('div', { class: 'fig-controls' });
  const chart = el('div', { class: 'fig-chart' });
  const readouts = el('dl', { class: 'fig-readouts', 'aria-live': 'polite' });
  const status = el('p', { class: 'fig-status', role: 'status' });
  const root = el('section', { class: 'fig', id, 'aria-labelledby': heading.id, 'data-figure': id },
    heading, el('p', { class: 'fig-intro' }, ...intro), controls, status, chart, readouts,
    el('p', { class: 'fig-cite' }, cite));
  host.append(root);
  return { root, controls, chart, readouts, status };
}

export interface Slider {
  row: HTMLElement;
  input: HTMLInputElement;
  value(): number;
}

/** A labelled range input with its value shown beside it (and given to screen readers). */
export function slider(o: { id: string; label: string; min: number; max: number; step: number; value: number;
  format(v: number): string; onInput(v: number): void }): Slider {
  const input = el('input', { type: 'range', id: o.id, min: o.min, max: o.max, step: o.step, value: String(o.value) });
  const out = el('output', { for: o.id, class: 'fig-value', 'data-testid': `${o.id}-value` });
  const show = () => {
    const text = o.format(Number(input.value));
    out.textContent = text;
    input.setAttribute('aria-valuetext', text);
  };
  input.addEventListener('input', () => { show(); o.onInput(Number(input.value)); });
  show();
  const row = el('div', { class: 'fig-control fig-control-range' }, el('label', { for: o.id }, o.label), el('div', { class: 'fig-range' }, input, out));
  return { row, input, value: () => Number(input.value) };
}

export function select(o: { id: string; label: string; options: { value: string; text: string }[]; value: string; onChange(v: string): void }):
  { row: HTMLElement; input: HTMLSelectElement } {
  const input = el('select', { id: o.id }, ...o.options.map((p) => el('option', { value: p.value }, p.text)));
  input.value = o.value;
  input.addEventListener('change', () => o.onChange(input.value));
  return { row: el('div', { class: 'fig-control' }, el('label', { for: o.id }, o.label), input), input };
}

/** A read-out: a term and its value, with a test id on the value. */
export function readout(host: HTMLElement, id: string, label: string): (text: string) => void {
  const dd = el('dd', { 'data-testid': id, id });
  host.append(el('div', { class: 'fig-readout' }, el('dt', {}, label), dd));
  return (text) => { dd.textContent = text; };
}

export const pretty = (name: string) => name.replace(/_/g, ' ');

/** Formats a number with about three significant digits. */
export function num(v: number, digits = 3): string {
  if (!Number.isFinite(v)) return '—';
  if (v === 0) return '0';
  const a = Math.abs(v);
  if (a >= 1e4 || a < 1e-3) return v.toExponential(digits - 1);
  return String(Number(v.toPrecision(digits)));
}
