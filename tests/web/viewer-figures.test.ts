// The instanced figures: fine detail for a few figures, the crowd detail past CROWD, and in both the
// head's instance colour is the figure's identity colour (what the legend and the browser tests read).
import { describe, expect, it } from 'vitest';
import { InstancedMesh } from 'three';
import { COARSE, CROWD, FINE, SkeletonFigures, type FigureDraw } from '../../web/src/viewer/figures';
import { identityHex } from '../../web/src/viewer/palette';
import { skeleton } from './helpers/dropped';

function figures(n: number): FigureDraw[] {
  const pose = new Float32Array(skeleton.joints.length * 3).map((_, i) => (i % 3 === 1 ? 0.05 * (i / 3) : 0.01 * i));
  return Array.from({ length: n }, (_, s) => ({ pose, x: s, z: 0, tint: { role: 'prediction' as const, sample: s } }));
}

function meshes(f: SkeletonFigures): InstancedMesh[] {
  return f.group.children as InstancedMesh[];
}

describe('SkeletonFigures', () => {
  const bones = skeleton.parents.filter((p) => p >= 0).length;

  it('draws every joint as a sphere up to CROWD figures', () => {
    const f = new SkeletonFigures();
    f.setSkeleton(skeleton);
    f.draw(figures(CROWD));
    const [boneMesh, jointMesh] = meshes(f);
    expect(f.drawnDetail).toBe(FINE);
    expect(boneMesh.count).toBe(CROWD * bones);
    expect(jointMesh.count).toBe(CROWD * skeleton.joints.length);
  });

  it('draws a crowd with coarser bones and the head only, with fewer vertices per figure', () => {
    const f = new SkeletonFigures();
    f.setSkeleton(skeleton);
    f.draw(figures(CROWD));
    const [fineBones, fineJoints] = meshes(f);
    const fineVertices = fineBones.geometry.attributes.position.count * bones
      + fineJoints.geometry.attributes.position.count * skeleton.joints.length;
    f.draw(figures(50));
    const [boneMesh, jointMesh] = meshes(f);
    expect(f.drawnDetail).toBe(COARSE);
    expect(boneMesh.count).toBe(50 * bones);
    expect(jointMesh.count).toBe(50);
    const coarseVertices = boneMesh.geometry.attributes.position.count * bones + jointMesh.geometry.attributes.position.count;
    expect(coarseVertices * 4).toBeLessThan(fineVertices);
    // and back: fewer figures are fine again
    f.draw(figures(3));
    expect(f.drawnDetail).toBe(FINE);
    expect(meshes(f)[1].count).toBe(3 * skeleton.joints.length);
  });

  it.each([5, 50])('gives figure i its identity colour on the head (%i figures)', (n) => {
    const f = new SkeletonFigures();
    f.setSkeleton(skeleton);
    f.draw(figures(n));
    for (const i of [0, 1, n - 1]) expect(f.identityHex(i)).toBe(identityHex('prediction', i));
    expect(f.identityHex(n)).toBeNull();
  });
});
