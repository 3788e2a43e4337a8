// The figures in one buffer: fine detail for a few figures, the crowd detail past CROWD; every bone's
// cylinder lies on its bone and every sphere on its joint, where the pose and the figure's offset put
// them; the head's vertex colour is the figure's identity colour (what the legend and the browser
// tests read).
import { describe, expect, it } from 'vitest';
import { BufferGeometry, Mesh, MeshLambertMaterial } from 'three';
import {
  BONE_RADIUS, COARSE, CROWD, FINE, HEAD_RADIUS, JOINT_RADIUS, SkeletonFigures, type FigureDraw,
} from '../../web/src/viewer/figures';
import { identityHex, tintScale } from '../../web/src/viewer/palette';
import { skeleton } from './helpers/dropped';

const J = skeleton.joints.length;
const bonePairs = skeleton.parents.flatMap((p, j) => (p >= 0 ? [[p, j] as [number, number]] : []));

function pose(seed: number): Float32Array {
  // a skewed, non-degenerate pose: every bone has its own direction and length
  return new Float32Array(J * 3).map((_, i) => Math.sin(1.7 * i + seed) * 0.4 + (i % 3 === 1 ? 1 : 0));
}

function figures(n: number): FigureDraw[] {
  return Array.from({ length: n }, (_, s) => ({ pose: pose(s), x: 1.5 * s, z: -0.5 * s, tint: { role: 'prediction' as const, sample: s } }));
}

// Positions are float32 at up to 75 m from the origin (figure 49 is offset 73.5 m): a float32 step
// there is 7.6e-6 m, so distances are compared to 1e-4 m and positions along a bone to 1e-3.
const METRES = 4;
const ALONG = 1e-3;

function mesh(f: SkeletonFigures): Mesh<BufferGeometry, MeshLambertMaterial> {
  return f.group.children[0] as Mesh<BufferGeometry, MeshLambertMaterial>;
}

/** Distance of point q from the segment a-b and where along it q projects (0 at a, 1 at b). */
function fromSegment(q: number[], a: number[], b: number[]): { distance: number; along: number } {
  const d = b.map((x, i) => x - a[i]);
  const len2 = d.reduce((s, x) => s + x * x, 0);
  const along = d.reduce((s, x, i) => s + x * (q[i] - a[i]), 0) / len2;
  const foot = a.map((x, i) => x + along * d[i]);
  return { distance: Math.hypot(...q.map((x, i) => x - foot[i])), along };
}

describe('SkeletonFigures', () => {
  it('draws every figure in one draw call, every joint as a sphere up to CROWD figures', () => {
    const f = new SkeletonFigures();
    f.setSkeleton(skeleton);
    f.draw(figures(CROWD));
    expect(f.group.children).toHaveLength(1);
    expect(f.drawnDetail).toBe(FINE);
    expect(f.drawn).toMatchObject({ figures: CROWD, bones: CROWD * bonePairs.length, spheres: CROWD * J });
    const g = mesh(f).geometry;
    // the draw range covers exactly the drawn figures' triangles
    expect(g.drawRange.count % 3).toBe(0);
    expect(Array.from(g.index!.array).slice(0, g.drawRange.count).reduce((a, b) => Math.max(a, b), 0)).toBe(f.drawn.vertices - 1);
  });

  it('draws a crowd with coarser bones and the head only, with fewer vertices per figure', () => {
    const f = new SkeletonFigures();
    f.setSkeleton(skeleton);
    f.draw(figures(CROWD));
    const fine = f.drawn.vertices / CROWD;
    f.draw(figures(50));
    expect(f.drawnDetail).toBe(COARSE);
    expect(f.drawn).toMatchObject({ figures: 50, bones: 50 * bonePairs.length, spheres: 50 });
    expect((f.drawn.vertices / 50) * 4).toBeLessThan(fine);
    // and back: fewer figures are fine again
    f.draw(figures(3));
    expect(f.drawnDetail).toBe(FINE);
    expect(f.drawn.spheres).toBe(3 * J);
  });

  it.each([3, 50])('puts each bone on its bone and each sphere on its joint (%i figures)', (n) => {
    const f = new SkeletonFigures();
    f.setSkeleton(skeleton);
    const draws = figures(n);
    f.draw(draws);
    for (const i of [0, n - 1]) {
      const { pose: p, x, z } = draws[i];
      const at = (j: number) => [p[j * 3] + x, p[j * 3 + 1], p[j * 3 + 2] + z];
      const scale = tintScale(draws[i].tint);
      bonePairs.forEach(([pa, ch], k) => {
        const v = f.partVertices(i, { bone: k })!;
        const alongs: number[] = [];
        for (let q = 0; q < v.length; q += 3) {
          const { distance, along } = fromSegment([v[q], v[q + 1], v[q + 2]], at(pa), at(ch));
          expect(distance).toBeCloseTo(BONE_RADIUS * scale, METRES);
          alongs.push(along);
        }
        // the cylinder runs from the parent joint to the child joint
        expect(Math.abs(Math.min(...alongs))).toBeLessThan(ALONG);
        expect(Math.abs(Math.max(...alongs) - 1)).toBeLessThan(ALONG);
      });
      skeleton.joints.forEach((name, j) => {
        const v = f.partVertices(i, { joint: j });
        if (n > CROWD && name !== 'head') { expect(v).toBeNull(); return; }
        const radius = (name === 'head' ? HEAD_RADIUS : JOINT_RADIUS) * scale;
        const c = at(j);
        for (let q = 0; q < v!.length; q += 3) expect(Math.hypot(v![q] - c[0], v![q + 1] - c[1], v![q + 2] - c[2])).toBeCloseTo(radius, METRES);
      });
    }
  });

  it.each([5, 50])('gives figure i its identity colour on the head (%i figures)', (n) => {
    const f = new SkeletonFigures();
    f.setSkeleton(skeleton);
    f.draw(figures(n));
    for (const i of [0, 1, n - 1]) expect(f.identityHex(i)).toBe(identityHex('prediction', i));
    expect(f.identityHex(n)).toBeNull();
  });

  it('keeps its buffers when the figure count shrinks, and grows them for more', () => {
    const f = new SkeletonFigures();
    f.setSkeleton(skeleton);
    f.draw(figures(10));
    const g = mesh(f).geometry;
    f.draw(figures(4));
    expect(mesh(f).geometry).toBe(g);
    f.draw(figures(18));
    expect(mesh(f).geometry).not.toBe(g);
    expect(f.identityHex(17)).toBe(identityHex('prediction', 17));
  });
});
