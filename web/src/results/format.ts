// Number formatting and plot geometry for the Results page: pure functions, tested in Node.
import type { Stat } from './data';

/** A number with as many digits as its size needs (percentages with one decimal). */
export function fmt(value: number | null | undefined, unit = ''): string {
  if (value === null || value === undefined || !Number.isFinite(value)) return '—';
  const a = Math.abs(value);
  if (unit === '%') return value.toFixed(1);
  if (a === 0) return '0';
  if (a >= 100) return value.toFixed(0);
  if (a >= 10) return value.toFixed(1);
  if (a >= 0.01) return value.toFixed(3);
  return value.toExponential(1);
}

/** "mean ± std" (the std combines the take bootstrap and the seed std); just the mean when the std is 0. */
export function cell(stat: Stat | null | undefined, unit = ''): string {
  if (!stat) return '—';
  return stat.std > 0 ? `${fmt(stat.mean, unit)} ± ${fmt(stat.std, unit)}` : fmt(stat.mean, unit);
}

export interface Scale { (v: number): number; domain: [number, number]; ticks: number[] }

/** Round tick steps (1, 2, 5 × 10^k) covering [lo, hi] with about `count` ticks. */
export function niceTicks(lo: number, hi: number, count = 5): number[] {
  if (!(hi > lo)) { hi = lo + 1; }
  const raw = (hi - lo) / Math.max(1, count);
  const mag = 10 ** Math.floor(Math.log10(raw));
  const step = [1, 2, 5, 10].map((m) => m * mag).find((s) => s >= raw) ?? 10 * mag;
  const out: number[] = [];
  // From the last tick at or below lo to the first at or above hi.
  for (let v = Math.floor(lo / step) * step; v < hi + step * (1 - 1e-9); v += step) out.push(Number(v.toPrecision(12)));
  return out;
}

/** A linear map from a data interval (widened to nice ticks) onto [r0, r1] pixels. */
export function linearScale(lo: number, hi: number, r0: number, r1: number, count = 5): Scale {
  const ticks = niceTicks(lo, hi, count);
  const d0 = Math.min(lo, ticks[0]);
  const d1 = Math.max(hi, ticks[ticks.length - 1], d0 + 1e-12);
  const f = ((v: number) => r0 + ((v - d0) / (d1 - d0)) * (r1 - r0)) as Scale;
  f.domain = [d0, d1];
  f.ticks = ticks.filter((t) => t >= d0 - 1e-9 && t <= d1 + 1e-9);
  return f;
}

/** Data extent of mean ± std over points, padded so markers are not on the frame. */
export function extent(stats: Stat[], pad = 0.08): [number, number] {
  if (stats.length === 0) return [0, 1];
  const lo = Math.min(...stats.map((s) => s.mean - s.std));
  const hi = Math.max(...stats.map((s) => s.mean + s.std));
  const span = hi - lo || Math.abs(hi) || 1;
  return [lo - span * pad, hi + span * pad];
}

export interface Bar { x: number; width: number; height: number; count: number; from: number; to: number }

/** Bars of a histogram with bin edges drawn into a box of width × height pixels, tallest = height. */
export function histogramBars(counts: number[], edges: number[], width: number, height: number): Bar[] {
  if (counts.length !== edges.length - 1) throw new Error(`histogram: ${counts.length} counts need ${counts.length + 1} edges, got ${edges.length}`);
  const top = Math.max(1, ...counts);
  const x = linearScaleNoTicks(edges[0], edges[edges.length - 1], 0, width);
  return counts.map((count, i) => ({
    x: x(edges[i]), width: Math.max(1, x(edges[i + 1]) - x(edges[i]) - 1),
    height: (count / top) * height, count, from: edges[i], to: edges[i + 1],
  }));
}

function linearScaleNoTicks(d0: number, d1: number, r0: number, r1: number): (v: number) => number {
  return (v) => r0 + ((v - d0) / (d1 - d0 || 1)) * (r1 - r0);
}
