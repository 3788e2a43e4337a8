// Small SVG charts for the explainer's figures: axes with ticks, lines, points and labels. The
// figures redraw by replacing their chart, so nothing here keeps state.
import { linearScale, niceTicks } from '../results/format';

const NS = 'http://www.w3.org/2000/svg';
type Attrs = Record<string, string | number | undefined>;

export function svg<K extends keyof SVGElementTagNameMap>(tag: K, attrs: Attrs = {}, text?: string): SVGElementTagNameMap[K] {
  const node = document.createElementNS(NS, tag);
  for (const [k, v] of Object.entries(attrs)) if (v !== undefined) node.setAttribute(k, String(v));
  if (text !== undefined) node.textContent = text;
  return node;
}

export interface ChartOptions {
  width?: number;
  height?: number;
  x: [number, number];
  y: [number, number];
  xLabel: string;
  yLabel: string;
  /** log10 y axis (values must be positive). */
  logY?: boolean;
  /** The accessible name of the chart: what it shows, in words. */
  label: string;
  /** Numbered ticks on the x axis (off for bar charts that label their bars). */
  xTicks?: boolean;
}

/** A drawing width that keeps the text at about its CSS size: the container's width, within limits. */
export function fitWidth(container: HTMLElement, max = 720): number {
  return Math.round(Math.max(300, Math.min(max, container.clientWidth || max)));
}

export interface Chart {
  root: SVGSVGElement;
  x(v: number): number;
  y(v: number): number;
  box: { l: number; r: number; t: number; b: number };
  add(...nodes: SVGElement[]): void;
}

const fmtTick = (v: number) => (Math.abs(v) >= 1000 || (Math.abs(v) < 0.01 && v !== 0) ? v.toExponential(0) : String(Number(v.toPrecision(3))));

export function chart(o: ChartOptions): Chart {
  const width = o.width ?? 560;
  const height = o.height ?? 260;
  const box = { l: 52, r: width - 12, t: 10, b: height - 38 };
  const root = svg('svg', { viewBox: `0 0 ${width} ${height}`, class: 'chart', role: 'img', 'aria-label': o.label });
  const xs = linearScale(o.x[0], o.x[1], box.l, box.r, 8);
  let y: (v: number) => number;
  let yTicks: { v: number; text: string }[];
  if (o.logY) {
    const lo = Math.floor(Math.log10(Math.max(o.y[0], 1e-12)));
    const hi = Math.ceil(Math.log10(Math.max(o.y[1], 1e-12)));
    const top = hi > lo ? hi : lo + 1;
    y = (v) => box.b - ((Math.log10(Math.max(v, 1e-12)) - lo) / (top - lo)) * (box.b - box.t);
    yTicks = Array.from({ length: top - lo + 1 }, (_, i) => ({ v: 10 ** (lo + i), text: `1e${lo + i}` }));
  } else {
    const ys = linearScale(o.y[0], o.y[1], box.b, box.t, 5);
    y = ys;
    yTicks = ys.ticks.map((v) => ({ v, text: fmtTick(v) }));
  }
  root.append(svg('rect', { x: box.l, y: box.t, width: box.r - box.l, height: box.b - box.t, class: 'chart-frame' }));
  for (const t of o.xTicks === false ? [] : xs.ticks) {
    root.append(svg('line', { x1: xs(t), x2: xs(t), y1: box.b, y2: box.b + 4, class: 'chart-tick' }));
    root.append(svg('text', { x: xs(t), y: box.b + 15, 'text-anchor': 'middle', class: 'chart-tick-label' }, fmtTick(t)));
  }
  for (const t of yTicks) {
    root.append(svg('line', { x1: box.l - 4, x2: box.l, y1: y(t.v), y2: y(t.v), class: 'chart-tick' }));
    root.append(svg('text', { x: box.l - 6, y: y(t.v) + 3, 'text-anchor': 'end', class: 'chart-tick-label' }, t.text));
  }
  root.append(svg('text', { x: (box.l + box.r) / 2, y: height - 4, 'text-anchor': 'middle', class: 'chart-axis-label' }, o.xLabel));
  root.append(svg('text', { x: 12, y: (box.t + box.b) / 2, 'text-anchor': 'middle', class: 'chart-axis-label',
    transform: `rotate(-90 12 ${(box.t + box.b) / 2})` }, o.yLabel));
  return { root, x: xs, y, box, add: (...nodes) => root.append(...nodes) };
}

/** An SVG path through points; NaN points break the line. */
export function line(c: Chart, xs: ArrayLike<number>, ys: ArrayLike<number>, attrs: Attrs = {}): SVGPathElement {
  let d = '';
  let pen = false;
  for (let i = 0; i < xs.length; i++) {
    if (!Number.isFinite(ys[i])) { pen = false; continue; }
    d += `${pen ? 'L' : 'M'}${c.x(xs[i]).toFixed(1)},${c.y(ys[i]).toFixed(1)}`;
    pen = true;
  }
  return svg('path', { d, fill: 'none', ...attrs });
}

export function hRule(c: Chart, v: number, label: string, cls = 'chart-level'): SVGGElement {
  const g = svg('g', { class: cls });
  g.append(svg('line', { x1: c.box.l, x2: c.box.r, y1: c.y(v), y2: c.y(v) }));
  g.append(svg('text', { x: c.box.r - 3, y: c.y(v) - 4, 'text-anchor': 'end', class: 'chart-note' }, label));
  return g;
}

export function vRule(c: Chart, v: number, label: string, cls = 'chart-mark'): SVGGElement {
  const g = svg('g', { class: cls });
  g.append(svg('line', { x1: c.x(v), x2: c.x(v), y1: c.box.t, y2: c.box.b }));
  g.append(svg('text', { x: c.x(v) + 3, y: c.box.t + 11, class: 'chart-note' }, label));
  return g;
}

/** Range of finite values, widened a little so lines do not sit on the frame. */
export function extentOf(values: Iterable<number>, pad = 0.06): [number, number] {
  let lo = Infinity;
  let hi = -Infinity;
  for (const v of values) if (Number.isFinite(v)) { lo = Math.min(lo, v); hi = Math.max(hi, v); }
  if (!Number.isFinite(lo)) return [0, 1];
  const span = hi - lo || Math.abs(hi) || 1;
  return [lo - span * pad, hi + span * pad];
}

export { niceTicks };
