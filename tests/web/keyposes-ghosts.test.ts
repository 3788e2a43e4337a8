// Keyposes' ghosts stand where the drawn figure stands (twin of tests/export/test_keyposes_ghosts.py):
// with planted feet (the default) each ghost moves by the root shift planting gave its future at the
// ghost's frame; with plantFeet off it stays at the method's own root.
import { describe, expect, it } from 'vitest';
import { followRoots } from '../../web/src/predictor/ghosts';
import type { Prediction } from '../../web/src/predictor/types';
import { loadManifest, nodePredictor } from './helpers/models';
import { readVector } from './helpers/vectors';

const manifest = loadManifest();
const entry = manifest.models.find((m) => m.method === 'keyposes');
const J = manifest.skeleton.joints.length;
const s = J * 3;
interface Case { model: string; clip: string; start: number; history: number[][][];
  request: { horizon_frames?: number; controls: Record<string, number | boolean> } }
const cases = readVector<{ cases: Case[] }>('e2e').cases.filter((c) => c.model === entry?.id);

/** Future q's root x, z at its ghost i's frame. */
function rootAt(p: Prediction, q: number, i: number): [number, number] {
  const at = (q * p.frames + p.ghosts!.frames[q][i]) * s;
  return [p.futures[at], p.futures[at + 2]];
}

describe.runIf(entry)('Keyposes ghosts follow planted feet', () => {
  it('has the end-to-end cases to run on', () => {
    expect(cases.length).toBeGreaterThanOrEqual(2);
  });

  for (const c of cases) {
    it(`${c.clip}@${c.start}: each ghost on its future's root at its frame, planted or not, moved by planting's shift`, async () => {
      const p = nodePredictor(manifest, entry!.id);
      const history = { positions: Float32Array.from(c.history.flat(2)), frames: c.history.length, joints: J };
      const req = { k: 4, seed: 5, horizonFrames: c.request.horizon_frames, controls: c.request.controls };
      const on = await p.predict(history, req);
      const off = await p.predict(history, { ...req, plantFeet: false });
      let moved = 0;
      for (let q = 0; q < 4; q++) {
        const gOn = on.ghosts!.poses[q];
        const gOff = off.ghosts!.poses[q];
        expect(gOn.length).toBe(on.ghosts!.frames[q].length * s);
        on.ghosts!.frames[q].forEach((_, i) => {
          const [x, z] = rootAt(on, q, i);
          expect(Math.abs(gOn[i * s] - x)).toBeLessThan(1e-5);
          expect(Math.abs(gOn[i * s + 2] - z)).toBeLessThan(1e-5);
        });
        off.ghosts!.frames[q].forEach((_, i) => {
          const [x, z] = rootAt(off, q, i);
          expect(Math.abs(gOff[i * s] - x)).toBeLessThan(1e-5);
          expect(Math.abs(gOff[i * s + 2] - z)).toBeLessThan(1e-5);
        });
        // the whole pose moves by planting's shift at that frame, horizontally only (ghosts past a cut are gone)
        const keep = Math.min(on.ghosts!.frames[q].length, off.ghosts!.frames[q].length);
        expect(on.ghosts!.frames[q].slice(0, keep)).toEqual(off.ghosts!.frames[q].slice(0, keep));
        for (let i = 0; i < keep; i++) {
          const [xOn, zOn] = rootAt(on, q, i);
          const [xOff, zOff] = rootAt(off, q, i);
          for (let j = 0; j < J; j++) {
            const o = i * s + j * 3;
            expect(Math.abs(gOn[o] - gOff[o] - (xOn - xOff))).toBeLessThan(1e-5);
            expect(gOn[o + 1]).toBe(gOff[o + 1]);
            expect(Math.abs(gOn[o + 2] - gOff[o + 2] - (zOn - zOff))).toBeLessThan(1e-5);
          }
          moved = Math.max(moved, Math.abs(xOn - xOff), Math.abs(zOn - zOff));
        }
      }
      expect(moved).toBeGreaterThan(0.01); // planting moved these futures, so a stale ghost would fail
    });
  }

  it('a ghost outside its future is refused by name', () => {
    const futures = new Float32Array(5 * s);
    const ghosts = { frames: [[2, 5]], poses: [new Float32Array(2 * s)] };
    expect(() => followRoots(ghosts, futures, futures.map((v) => v + 1), 5, J)).toThrow(/future 0 has a ghost outside its 5 frames: 2, 5/);
  });
});
