// Where a label goes on screen: its own spot (centred over its figure's head) when nothing is there,
// else the nearest spot around it that covers no figure and no other label. A pure function of what
// is on screen, so the same frame seen from the same camera always puts the label in the same place.

/** A rectangle in CSS pixels from the stage's top-left. */
export interface Rect { left: number; top: number; right: number; bottom: number }

/** Where a label sits: the middle of its bottom edge (CSS2DObject center (0.5, 1)), CSS pixels. */
export interface Spot { x: number; y: number }

export interface PlaceOptions {
  /** Grid step of the spots tried (px). */
  step?: number;
  /** How far from its own spot a label may go (px). */
  reach?: number;
  /** Room kept between the label and what it avoids (px): bones and heads are drawn thicker than their joints. */
  gap?: number;
}

export interface Placed extends Spot {
  /** Nothing is covered at this spot (false: no free spot within reach; the least covered one). */
  clear: boolean;
}

/** The label's rectangle at a spot. */
export function labelRect(at: Spot, size: { width: number; height: number }): Rect {
  return { left: at.x - size.width / 2, right: at.x + size.width / 2, top: at.y - size.height, bottom: at.y };
}

/** Offsets of a step grid within reach, nearest first: straight up before down, right before left
 *  at the same distance, so the order (and the choice) never depends on sort stability. */
const grids = new Map<string, Int16Array>();
function offsets(step: number, reach: number): Int16Array {
  const key = `${step}/${reach}`;
  let found = grids.get(key);
  if (!found) {
    const n = Math.floor(reach / step);
    const all: [number, number][] = [];
    for (let i = -n; i <= n; i++) for (let j = -n; j <= n; j++) if (i * i + j * j <= n * n) all.push([i * step, j * step]);
    all.sort((a, b) => (a[0] * a[0] + a[1] * a[1]) - (b[0] * b[0] + b[1] * b[1]) || a[1] - b[1] || b[0] - a[0]);
    found = Int16Array.from(all.flat());
    grids.set(key, found);
  }
  return found;
}

function overlap(a: Rect, b: Rect, gap: number): number {
  const w = Math.min(a.right, b.right + gap) - Math.max(a.left, b.left - gap);
  const h = Math.min(a.bottom, b.bottom + gap) - Math.max(a.top, b.top - gap);
  return w > 0 && h > 0 ? w * h : 0;
}

/**
 * The spot for a label of `size` whose own spot is `home`: home itself if the label there covers none
 * of `obstacles`, else the nearest free spot on a grid around it with the label inside `bounds`.
 * With no free spot within reach, the spot that covers the least.
 */
export function placeLabel(home: Spot, size: { width: number; height: number }, obstacles: readonly Rect[],
  bounds: Rect, options: PlaceOptions = {}): Placed {
  const step = options.step ?? 6;
  const reach = options.reach ?? 240;
  const gap = options.gap ?? 3;
  if (!(step > 0) || !(reach >= 0) || !(size.width >= 0) || !(size.height >= 0)) {
    throw new Error(`placeLabel: step ${step} must be > 0, reach ${reach} and size ${size.width} x ${size.height} >= 0`);
  }
  const grid = offsets(step, reach);
  const inside = (r: Rect) => r.left >= bounds.left && r.right <= bounds.right && r.top >= bounds.top && r.bottom <= bounds.bottom;
  // only what a spot within reach can touch
  const w = size.width / 2 + reach + gap;
  const near = obstacles.filter((o) => o.right > home.x - w && o.left < home.x + w
    && o.bottom > home.y - size.height - reach - gap && o.top < home.y + reach + gap);
  // home is kept when free even if the camera has put it past the stage's edge (as every other label is)
  let blocker = near.findIndex((o) => overlap(labelRect(home, size), o, gap) > 0);
  if (blocker < 0) return { ...home, clear: true };
  // neighbouring spots are mostly blocked by the same obstacle: it is tried first
  const free = (r: Rect) => {
    if (overlap(r, near[blocker], gap) > 0) return false;
    for (let k = 0; k < near.length; k++) if (overlap(r, near[k], gap) > 0) { blocker = k; return false; }
    return true;
  };
  for (let i = 2; i < grid.length; i += 2) {
    const at = { x: home.x + grid[i], y: home.y + grid[i + 1] };
    const r = labelRect(at, size);
    if (inside(r) && free(r)) return { ...at, clear: true };
  }
  // nothing free within reach: the spot that covers the least
  const covered = (r: Rect) => near.reduce((sum, o) => sum + overlap(r, o, gap), 0);
  let best: Placed = { ...home, clear: false };
  let least = covered(labelRect(home, size));
  for (let i = 2; i < grid.length; i += 2) {
    const at = { x: home.x + grid[i], y: home.y + grid[i + 1] };
    const r = labelRect(at, size);
    if (!inside(r)) continue;
    const c = covered(r);
    if (c < least) { least = c; best = { ...at, clear: false }; }
  }
  return best;
}
