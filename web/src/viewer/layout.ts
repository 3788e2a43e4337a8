// Where each track's figure stands: all where they are (overlaid), or one cell per figure in a grid
// (side by side). Figures travel over the floor, so a cell is an offset added to a track's own world
// positions; the grid is laid out in the figures' own frame (columns across their heading, rows
// along it) and each cell is as large as the room the figures need at any one moment.
import type { TrackRole } from './tracks';

export type LayoutMode = 'overlay' | 'side';

export interface Placement {
  /** Index into the track list. */
  track: number;
  cell: number;
  x: number;
  z: number;
  /** A copy of a shared track (history) drawn in another track's cell. */
  shared: boolean;
}

export interface Layout {
  placements: Placement[];
  cells: number;
  cols: number;
  rows: number;
  spacing: number;
  rowSpacing: number;
}

export interface LayoutOptions {
  /** Smallest distance between columns / rows (metres). */
  spacing?: number;
  rowSpacing?: number;
  /** Angle about +y from +z to the figures' forward direction: columns run across it, rows along it. */
  heading?: number;
  /** The room one cell needs (metres), across the heading and along it; the spacings never go below these. */
  cellWidth?: number;
  cellDepth?: number;
  /** Width / height of the view, to choose the columns that let the grid fill it. */
  aspect?: number;
}

export const CELL_SPACING = 1.6;
/** Rows sit further apart than columns: seen from the front and above, a figure hides the row behind it. */
export const ROW_SPACING = 2.0;
/** The side-by-side camera's elevation (viewer.ts SIDE_VIEW): rows recede, so depth counts less than width. */
const SIDE_ELEVATION = Math.atan2(0.95, Math.hypot(0.25, 1));
const FIGURE_HEIGHT = 1.8;

const CELL_ORDER: Record<TrackRole, number> = { truth: 0, clip: 1, prediction: 2, history: 3 };

/** Columns for `cells` cells of width w and depth d that make the grid's picture fit a view of this aspect best. */
export function chooseColumns(cells: number, w: number, d: number, aspect: number): number {
  let best = 1;
  let bestSize = Infinity;
  for (let cols = 1; cols <= cells; cols++) {
    const rows = Math.ceil(cells / cols);
    const wide = (cols * w) / aspect;
    const tall = rows * d * Math.sin(SIDE_ELEVATION) + FIGURE_HEIGHT * Math.cos(SIDE_ELEVATION);
    const size = Math.max(wide, tall);
    if (size < bestSize - 1e-9) { best = cols; bestSize = size; }
  }
  return best;
}

/**
 * Side by side: ground truth first, then clips, then predictions by sample, row-major from the back-left
 * (seen from in front of the figures). History is the shared past of every cell, so it is drawn in each
 * cell rather than given its own (unless nothing else is on stage).
 */
export function layoutTracks(
  tracks: readonly { role: TrackRole; sample?: number; group?: number }[],
  mode: LayoutMode,
  options: LayoutOptions = {},
): Layout {
  const spacing = Math.max(options.spacing ?? CELL_SPACING, options.cellWidth ?? 0);
  const rowSpacing = Math.max(options.rowSpacing ?? ROW_SPACING, options.cellDepth ?? 0);
  if (tracks.some((t) => t.group !== undefined)) return groupedLayout(tracks, mode, spacing, rowSpacing, options.heading ?? 0);
  if (mode === 'overlay' || tracks.length === 0) {
    return {
      placements: tracks.map((_, track) => ({ track, cell: 0, x: 0, z: 0, shared: false })),
      cells: tracks.length ? 1 : 0, cols: 1, rows: 1, spacing, rowSpacing,
    };
  }
  const own = tracks.map((t, i) => ({ t, i })).filter(({ t }) => t.role !== 'history');
  const shared = tracks.map((t, i) => ({ t, i })).filter(({ t }) => t.role === 'history');
  const cellTracks = own.length ? own : shared;
  cellTracks.sort((p, q) =>
    CELL_ORDER[p.t.role] - CELL_ORDER[q.t.role] || (p.t.sample ?? 0) - (q.t.sample ?? 0) || p.i - q.i);
  const cells = cellTracks.length;
  const cols = chooseColumns(cells, spacing, rowSpacing, options.aspect ?? 1.6);
  const rows = Math.ceil(cells / cols);
  const heading = options.heading ?? 0;
  const c = Math.cos(heading);
  const s = Math.sin(heading);
  const at = (cell: number) => {
    // across the heading (u) and along it (v); row 0 is the farthest from a camera in front of the figures
    const u = ((cell % cols) - (cols - 1) / 2) * spacing;
    const v = (Math.floor(cell / cols) - (rows - 1) / 2) * rowSpacing;
    return { x: clean(c * u + s * v), z: clean(-s * u + c * v) };
  };
  const placements: Placement[] = cellTracks.map(({ i }, cell) => ({ track: i, cell, ...at(cell), shared: false }));
  if (own.length) {
    for (const { i } of shared) {
      for (let cell = 0; cell < cells; cell++) placements.push({ track: i, cell, ...at(cell), shared: true });
    }
  }
  return { placements, cells, cols, rows, spacing, rowSpacing };
}

/**
 * Compare mode: one row per method (its `group`; row 0 farthest from the camera), each laid out as
 * side by side lays out one prediction (truth first, then samples), its history copied into its own
 * row's cells only. Overlaid, each method is one cell, the methods side by side across the heading.
 */
function groupedLayout(tracks: readonly { role: TrackRole; sample?: number; group?: number }[], mode: LayoutMode,
  spacing: number, rowSpacing: number, heading: number): Layout {
  const groups = [...new Set(tracks.map((t) => t.group ?? 0))].sort((a, b) => a - b);
  const rowOf = new Map(groups.map((g, r) => [g, r]));
  const c = Math.cos(heading);
  const s = Math.sin(heading);
  const placements: Placement[] = [];
  if (mode === 'overlay') {
    const cols = groups.length;
    tracks.forEach((t, track) => {
      const col = rowOf.get(t.group ?? 0)!;
      const u = (col - (cols - 1) / 2) * spacing;
      placements.push({ track, cell: col, x: clean(c * u), z: clean(-s * u), shared: false });
    });
    return { placements, cells: cols, cols, rows: 1, spacing, rowSpacing };
  }
  const rows = groups.map((g) => {
    const all = tracks.map((t, i) => ({ t, i })).filter(({ t }) => (t.group ?? 0) === g);
    const own = all.filter(({ t }) => t.role !== 'history');
    own.sort((p, q) => CELL_ORDER[p.t.role] - CELL_ORDER[q.t.role] || (p.t.sample ?? 0) - (q.t.sample ?? 0) || p.i - q.i);
    return { own: own.length ? own : all, shared: own.length ? all.filter(({ t }) => t.role === 'history') : [] };
  });
  const cols = Math.max(1, ...rows.map((r) => r.own.length));
  const at = (row: number, col: number) => {
    const u = (col - (cols - 1) / 2) * spacing;
    const v = (row - (rows.length - 1) / 2) * rowSpacing;
    return { x: clean(c * u + s * v), z: clean(-s * u + c * v) };
  };
  rows.forEach((r, row) => {
    r.own.forEach(({ i }, col) => placements.push({ track: i, cell: row * cols + col, ...at(row, col), shared: false }));
    for (const { i } of r.shared) {
      r.own.forEach((_, col) => placements.push({ track: i, cell: row * cols + col, ...at(row, col), shared: true }));
    }
  });
  return { placements, cells: rows.length * cols, cols, rows: rows.length, spacing, rowSpacing };
}

/** -0 and rounding dust read as 0. */
function clean(v: number): number {
  return Math.abs(v) < 1e-12 ? 0 : v;
}
