// Where each track's figure stands: all at the origin, or one cell per figure in a grid.
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

export const CELL_SPACING = 1.6;
/** Rows sit further apart than columns: seen from the front and above, a figure hides the row behind it. */
export const ROW_SPACING = 2.0;

const CELL_ORDER: Record<TrackRole, number> = { truth: 0, clip: 1, prediction: 2, history: 3 };

/**
 * Side by side: ground truth first, then clips, then predictions by sample, row-major from the back-left.
 * History is the shared past of every cell, so it is drawn in each cell rather than given its own
 * (unless nothing else is on stage).
 */
export function layoutTracks(
  tracks: readonly { role: TrackRole; sample?: number }[],
  mode: LayoutMode,
  spacing = CELL_SPACING,
  rowSpacing = ROW_SPACING,
): Layout {
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
  // Wider than deep: the camera looks along -z, so rows recede.
  const cols = Math.min(cells, Math.max(1, Math.ceil(Math.sqrt(cells * 1.5))));
  const rows = Math.ceil(cells / cols);
  const at = (cell: number) => ({
    x: ((cell % cols) - (cols - 1) / 2) * spacing,
    z: (Math.floor(cell / cols) - (rows - 1) / 2) * rowSpacing,
  });
  const placements: Placement[] = cellTracks.map(({ i }, cell) => ({ track: i, cell, ...at(cell), shared: false }));
  if (own.length) {
    for (const { i } of shared) {
      for (let cell = 0; cell < cells; cell++) placements.push({ track: i, cell, ...at(cell), shared: true });
    }
  }
  return { placements, cells, cols, rows, spacing, rowSpacing };
}
