// A small SVG plot of per-sample curves with threshold levels and marked frames (e.g. WAT's
// variance v_i with delta and T_min).
import type { Curve } from '../predictor/types';
import { identityCss } from '../viewer/palette';

const NS = 'http://www.w3.org/2000/svg';

/** A sample's line colour: its figure's identity colour (viewer/palette.ts). */
export function sampleColour(sample: number): string {
  return identityCss('prediction', sample);
}

function svg<K extends keyof SVGElementTagNameMap>(tag: K, attrs: Record<string, string | number>): SVGElementTagNameMap[K] {
  const node = document.createElementNS(NS, tag);
  for (const [k, v] of Object.entries(attrs)) node.setAttribute(k, String(v));
  return node;
}

/** `marks[i]`: frames where sample i's next action starts (WAT's transitions), drawn as dots on its curve. */
export function curvePlot(curve: Curve, selected: number | null, width = 300, height = 140, marks: (number[] | undefined)[] = []): SVGSVGElement {
  const pad = { l: 34, r: 6, t: 8, b: 18 };
  const frames = Math.max(2, ...curve.series.map((s) => s.length));
  const all = curve.series.flatMap((s) => Array.from(s)).concat((curve.levels ?? []).map((l) => l.value)).filter((v) => Number.isFinite(v));
  const tf = (v: number) => (curve.log ? Math.log10(Math.max(v, 1e-9)) : v);
  const lo = Math.min(...all.map(tf));
  const hi = Math.max(...all.map(tf));
  const span = hi - lo || 1;
  const x = (f: number) => pad.l + (f / (frames - 1)) * (width - pad.l - pad.r);
  const y = (v: number) => pad.t + (1 - (tf(v) - lo) / span) * (height - pad.t - pad.b);
  const root = svg('svg', { viewBox: `0 0 ${width} ${height}`, class: 'curve-plot', role: 'img' });
  root.setAttribute('aria-label', `${curve.title}: ${curve.series.length} samples`);
  root.append(svg('rect', { x: pad.l, y: pad.t, width: width - pad.l - pad.r, height: height - pad.t - pad.b, class: 'plot-frame' }));
  curve.series.forEach((s, i) => {
    const d = Array.from(s).map((v, f) => `${f ? 'L' : 'M'}${x(f).toFixed(1)},${y(v).toFixed(1)}`).join('');
    const path = svg('path', { d, fill: 'none', stroke: sampleColour(i), 'stroke-width': selected === i ? 2.4 : 1.1,
      opacity: selected === null || selected === i ? 0.95 : 0.35 });
    root.append(path);
    for (const f of marks[i] ?? []) {
      if (f < 0 || f >= s.length) continue;
      root.append(svg('circle', { cx: x(f).toFixed(1), cy: y(s[f]).toFixed(1), r: selected === i ? 3 : 2, fill: sampleColour(i),
        class: 'plot-transition', opacity: selected === null || selected === i ? 0.95 : 0.35 }));
    }
  });
  for (const level of curve.levels ?? []) {
    root.append(svg('line', { x1: pad.l, x2: width - pad.r, y1: y(level.value), y2: y(level.value), class: 'plot-level' }));
    const t = svg('text', { x: width - pad.r - 2, y: y(level.value) - 3, 'text-anchor': 'end', class: 'plot-label' });
    t.textContent = level.label;
    root.append(t);
  }
  for (const mark of curve.frames ?? []) {
    root.append(svg('line', { x1: x(mark.frame), x2: x(mark.frame), y1: pad.t, y2: height - pad.b, class: 'plot-mark' }));
    const t = svg('text', { x: x(mark.frame) + 3, y: height - pad.b - 4, class: 'plot-label' });
    t.textContent = mark.label;
    root.append(t);
  }
  const axis = svg('text', { x: pad.l, y: height - 4, class: 'plot-label' });
  axis.textContent = `frame 0 – ${frames - 1}`;
  root.append(axis);
  return root;
}
