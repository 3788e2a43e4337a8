// The ground truth's label on screen (web/src/viewer/label-place.ts): kept over its head when free,
// moved to the nearest free spot when another figure or label is there, the same way every time.
import { describe, expect, it } from 'vitest';
import { labelRect, placeLabel, type Rect } from '../../web/src/viewer/label-place';

const STAGE: Rect = { left: 0, top: 0, right: 800, bottom: 500 };
const SIZE = { width: 84, height: 16 };
const GAP = 3;

const intersects = (a: Rect, b: Rect) => a.left < b.right && b.left < a.right && a.top < b.bottom && b.top < a.bottom;
const within = (a: Rect, b: Rect) => a.left >= b.left && a.right <= b.right && a.top >= b.top && a.bottom <= b.bottom;
const grow = (r: Rect, by: number): Rect => ({ left: r.left - by, top: r.top - by, right: r.right + by, bottom: r.bottom + by });
/** A standing figure's projected box: `h` px tall, head at `top`, centred on x. */
const figure = (x: number, top: number, h = 150): Rect => ({ left: x - h / 6, right: x + h / 6, top, bottom: top + h });

describe('placeLabel', () => {
  it('keeps the label over its head when nothing is there', () => {
    const home = { x: 400, y: 180 };
    const placed = placeLabel(home, SIZE, [figure(400, 200), figure(200, 200)], STAGE);
    expect(placed).toEqual({ ...home, clear: true });
  });

  it('moves it to the nearest free spot when a figure stands over it', () => {
    // A figure 40 px wide from y = 60 down covers the label's home (bottom-centre 100, 100). Free spots:
    // above the figure (label bottom <= 57, 43 px up: 48 on the 6 px grid), or beside it (54 px
    // sideways); up is nearer.
    const body: Rect = { left: 80, right: 120, top: 60, bottom: 200 };
    const placed = placeLabel({ x: 100, y: 100 }, { width: 60, height: 16 }, [body], STAGE, { step: 6, gap: GAP });
    expect(placed).toEqual({ x: 100, y: 52, clear: true });
  });

  it('among overlapping figures and their stacked labels, covers none of them and stays on the stage', () => {
    // Overlaid futures fan out from the truth's place; one sample mid-jump, head where the truth's label goes.
    const bodies = [figure(400, 200), figure(380, 196), figure(425, 205), figure(402, 140), figure(360, 210)];
    const labels = [1, 2, 3, 4].map((k) => labelRect({ x: 400, y: 180 - 18 * k }, { width: 40, height: 16 }));
    const obstacles = [...bodies, ...labels];
    const home = { x: 400, y: 180 };
    expect(obstacles.some((o) => intersects(labelRect(home, SIZE), o)), 'the home spot is taken').toBe(true);
    const placed = placeLabel(home, SIZE, obstacles, STAGE, { gap: GAP });
    expect(placed.clear).toBe(true);
    const rect = labelRect(placed, SIZE);
    for (const o of obstacles) expect(intersects(rect, grow(o, GAP)), JSON.stringify(o)).toBe(false);
    expect(within(rect, STAGE)).toBe(true);
    // it stays by its figure, not anywhere free on the stage
    expect(Math.hypot(placed.x - home.x, placed.y - home.y)).toBeLessThan(150);
    // deterministic: the same scene in any order gives the same spot
    expect(placeLabel(home, SIZE, [...obstacles].reverse(), STAGE, { gap: GAP })).toEqual(placed);
  });

  it('does not leave the stage: at the top edge it goes sideways', () => {
    const home = { x: 300, y: 20 };
    const body: Rect = { left: 270, right: 330, top: 10, bottom: 160 };
    const placed = placeLabel(home, SIZE, [body], STAGE, { gap: GAP });
    const rect = labelRect(placed, SIZE);
    expect(placed.clear).toBe(true);
    expect(within(rect, STAGE)).toBe(true);
    expect(intersects(rect, grow(body, GAP))).toBe(false);
    expect(rect.left >= body.right + GAP || rect.right <= body.left - GAP).toBe(true);
  });

  it('with no free spot within reach, takes the least covered one', () => {
    const wall: Rect = { left: 0, top: 0, right: 800, bottom: 300 };
    const post: Rect = { left: 380, top: 150, right: 420, bottom: 200 };
    const home = { x: 400, y: 190 };
    const placed = placeLabel(home, SIZE, [wall, post], STAGE, { reach: 60, gap: 0 });
    expect(placed.clear).toBe(false);
    const cover = (r: Rect) => [wall, post].reduce((sum, o) => sum + Math.max(0, Math.min(r.right, o.right) - Math.max(r.left, o.left)) * Math.max(0, Math.min(r.bottom, o.bottom) - Math.max(r.top, o.top)), 0);
    expect(cover(labelRect(placed, SIZE))).toBeLessThan(cover(labelRect(home, SIZE)));
  });

  it('refuses a step of zero or a negative size', () => {
    expect(() => placeLabel({ x: 0, y: 0 }, SIZE, [], STAGE, { step: 0 })).toThrow(/step 0 must be > 0/);
    expect(() => placeLabel({ x: 0, y: 0 }, { width: -1, height: 5 }, [], STAGE)).toThrow(/size -1 x 5/);
  });
});
