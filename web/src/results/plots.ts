// The two figures: diversity against context (like LCP-VAE Fig. 1) and per-action length
// histograms (WAT sec. 3.3). SVG sized by viewBox, coloured through CSS classes.
import type { Row, Table } from './data';
import { svg } from './dom';
import { extent, fmt, histogramBars, linearScale } from './format';

/** One colour per plotted row (eight, then repeating); the ground truth in the text colour. */
export function markClass(row: Row, index: number): string {
  return row.kind === 'oracle' ? 'mark-oracle' : `mark-${index % 8}`;
}

/** Diversity (y) against context = pose-classifier accuracy (x) of every row that has both; whiskers ±1 std. */
export function contextPlot(table: Table): SVGSVGElement | null {
  const rows = table.rows.filter((r) => !r.skipped && r.values?.acc_pose && r.values?.div);
  if (rows.length === 0) return null;
  // The legend sits below the axes in two columns of full labels (a side legend cut long labels off).
  const legendRows = Math.ceil(rows.length / 2);
  const LEGEND_LINE = 17;
  const W = 620, plotH = 300, H = plotH + 14 + legendRows * LEGEND_LINE, m = { l: 64, r: 16, t: 16, b: 48 + 14 + legendRows * LEGEND_LINE };
  const xs = rows.map((r) => r.values!.acc_pose), ys = rows.map((r) => r.values!.div);
  const [x0, x1] = extent(xs), [, y1] = extent(ys);
  const x = linearScale(Math.max(0, x0), Math.min(100, Math.max(x1, x0 + 5)), m.l, W - m.r);
  // Diversity is a distance: the axis starts at 0 (deterministic rows sit on it).
  const y = linearScale(0, Math.max(y1, 0.01), H - m.b, m.t);
  const plot = svg('svg', { viewBox: `0 0 ${W} ${H}`, class: 'plot context-plot', role: 'img',
    'aria-label': `Diversity against context, table ${table.id}`, 'data-table': table.id });
  axes(plot, x, y, W, H, m, 'context: pose-classifier accuracy (%)', 'diversity (m)');
  rows.forEach((r, i) => {
    const cx = x(r.values!.acc_pose.mean), cy = y(r.values!.div.mean);
    const sx = r.values!.acc_pose.std, sy = r.values!.div.std;
    const g = svg('g', { class: `point ${markClass(r, i)}`, 'data-row': r.id });
    g.append(
      svg('line', { x1: x(r.values!.acc_pose.mean - sx), x2: x(r.values!.acc_pose.mean + sx), y1: cy, y2: cy, class: 'whisker' }),
      svg('line', { x1: cx, x2: cx, y1: y(r.values!.div.mean - sy), y2: y(r.values!.div.mean + sy), class: 'whisker' }),
      svg('circle', { cx, cy, r: 5 }, svg('title', {}, `${r.label}: accuracy ${fmt(r.values!.acc_pose.mean, '%')} %, diversity ${fmt(r.values!.div.mean)} m`)),
    );
    plot.append(g);
    // Legend instead of labels at the points, which overlap when rows coincide.
    const lx = m.l + (i % 2) * ((W - m.l - m.r) / 2);
    const ly = plotH + 18 + Math.floor(i / 2) * LEGEND_LINE;
    plot.append(svg('g', { class: `legend ${markClass(r, i)}` },
      svg('circle', { cx: lx + 6, cy: ly - 4, r: 4 }),
      svg('text', { x: lx + 16, y: ly, class: 'legend-text' }, r.label)));
  });
  return plot;
}

function axes(plot: SVGSVGElement, x: ReturnType<typeof linearScale>, y: ReturnType<typeof linearScale>,
  W: number, H: number, m: { l: number; r: number; t: number; b: number }, xLabel: string, yLabel: string): void {
  const g = svg('g', { class: 'axes' });
  g.append(svg('rect', { x: m.l, y: m.t, width: W - m.l - m.r, height: H - m.t - m.b, class: 'frame' }));
  for (const t of x.ticks) {
    g.append(svg('line', { x1: x(t), x2: x(t), y1: H - m.b, y2: H - m.b + 4, class: 'tick' }));
    g.append(svg('text', { x: x(t), y: H - m.b + 16, 'text-anchor': 'middle', class: 'tick-label' }, fmt(t)));
  }
  for (const t of y.ticks) {
    g.append(svg('line', { x1: m.l - 4, x2: m.l, y1: y(t), y2: y(t), class: 'tick' }));
    g.append(svg('text', { x: m.l - 6, y: y(t) + 4, 'text-anchor': 'end', class: 'tick-label' }, fmt(t)));
  }
  g.append(svg('text', { x: (m.l + W - m.r) / 2, y: H - m.b + 36, 'text-anchor': 'middle', class: 'axis-label' }, xLabel));
  g.append(svg('text', { x: 14, y: (m.t + H - m.b) / 2, 'text-anchor': 'middle', class: 'axis-label',
    transform: `rotate(-90 14 ${(m.t + H - m.b) / 2})` }, yLabel));
  plot.append(g);
}

/** One small histogram of predicted lengths per action, for one row. */
export function lengthHistograms(row: Row, edges: number[]): SVGSVGElement | null {
  const actions = Object.keys(row.lengths ?? {});
  if (actions.length === 0) return null;
  const cols = Math.min(5, actions.length), cw = 120, ch = 78, bw = 104, bh = 44;
  const rowsN = Math.ceil(actions.length / cols);
  const plot = svg('svg', { viewBox: `0 0 ${cols * cw} ${rowsN * ch}`, class: 'plot length-plot', role: 'img',
    'aria-label': `Predicted lengths per action, ${row.label}`, 'data-row': row.id });
  actions.forEach((a, i) => {
    const gx = (i % cols) * cw + 8, gy = Math.floor(i / cols) * ch + 4;
    const counts = row.lengths![a];
    const total = counts.reduce((s, c) => s + c, 0);
    const g = svg('g', { transform: `translate(${gx} ${gy})`, class: 'hist', 'data-action': a });
    g.append(svg('text', { x: 0, y: 10, class: 'hist-title' }, `${a} (${total})`));
    for (const b of histogramBars(counts, edges, bw, bh)) {
      g.append(svg('rect', { x: b.x, y: 14 + bh - b.height, width: b.width, height: b.height, class: 'bar' },
        svg('title', {}, `${a}: ${b.count} of ${total} samples with length ${b.from}–${b.to} frames`)));
    }
    g.append(svg('line', { x1: 0, x2: bw, y1: 14 + bh, y2: 14 + bh, class: 'tick' }));
    g.append(svg('text', { x: 0, y: 14 + bh + 12, class: 'tick-label' }, String(edges[0])));
    g.append(svg('text', { x: bw, y: 14 + bh + 12, 'text-anchor': 'end', class: 'tick-label' }, `${edges[edges.length - 1]} fr`));
    plot.append(g);
  });
  return plot;
}
