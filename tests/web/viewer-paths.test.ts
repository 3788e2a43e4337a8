// The root paths in one LineSegments: each path's points become consecutive segments (none joins two
// paths), at the given height, in its identity colour; a selection changes only the alphas.
import { describe, expect, it } from 'vitest';
import { Color, SRGBColorSpace, type BufferAttribute } from 'three';
import { RootPaths } from '../../web/src/viewer/paths';

const path = (n: number, x0: number) => new Float32Array(n * 3).map((_, i) => (i % 3 === 0 ? x0 + Math.floor(i / 3) : i % 3 === 2 ? 0.1 * Math.floor(i / 3) : 9));

describe('RootPaths', () => {
  it('draws n - 1 segments per path, never one between two paths', () => {
    const p = new RootPaths(0.004);
    p.set([{ points: path(4, 0), colour: [1, 0, 0] }, { points: path(3, 10), colour: [0, 0, 1] }]);
    const g = p.object.geometry;
    const index = Array.from(g.index!.array);
    expect(index).toEqual([0, 1, 1, 2, 2, 3, 4, 5, 5, 6]);
    const pos = g.getAttribute('position');
    expect(pos.count).toBe(7);
    for (let v = 0; v < 7; v++) expect(pos.getY(v)).toBe(Math.fround(0.004)); // on the floor, not at the root's height
    expect(pos.getX(4)).toBe(10);
    expect(pos.getZ(2)).toBeCloseTo(0.2, 6);
  });

  it('colours each path in its colour (linear, as three.js draws) at opacity 0.5', () => {
    const p = new RootPaths(0);
    p.set([{ points: path(2, 0), colour: [0.8, 0.2, 0.1] }]);
    const c = p.object.geometry.getAttribute('color');
    const want = new Color().setRGB(0.8, 0.2, 0.1, SRGBColorSpace);
    expect(c.itemSize).toBe(4);
    expect([c.getX(1), c.getY(1), c.getZ(1)].map((x) => x.toFixed(6))).toEqual([want.r, want.g, want.b].map((x) => x.toFixed(6)));
    expect(p.opacity(0)).toBe(0.5);
    expect((p.object.material as { vertexColors: boolean; transparent: boolean }).vertexColors).toBe(true);
  });

  it('sets each path\'s opacity on every one of its vertices', () => {
    const p = new RootPaths(0);
    p.set([{ points: path(3, 0), colour: [1, 0, 0] }, { points: path(2, 5), colour: [0, 1, 0] }]);
    const c = p.object.geometry.getAttribute('color') as BufferAttribute;
    const before = c.version;
    p.setOpacity((i) => (i === 1 ? 0.9 : 0.15));
    expect([0, 1, 2].map((v) => c.getW(v))).toEqual([0.15, 0.15, 0.15].map(Math.fround));
    expect([3, 4].map((v) => c.getW(v))).toEqual([0.9, 0.9].map(Math.fround));
    expect(c.version).toBeGreaterThan(before);
    const after = c.version;
    p.setOpacity((i) => (i === 1 ? 0.9 : 0.15)); // nothing changed: nothing to upload
    expect(c.version).toBe(after);
    expect(p.count).toBe(2);
    p.set([]);
    expect(p.count).toBe(0);
    expect(p.object.geometry.getAttribute('position').count).toBe(0);
  });
});
