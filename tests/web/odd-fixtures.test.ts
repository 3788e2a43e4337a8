// The committed odd histories of issue 19 (tests/fixtures/odd/: a held-out walk raised by 0.7 m, the
// same walk with one-frame spikes, a held-out jump_reach_grab take) through every served model in
// TypeScript: bounded futures, with the named warnings Python gives (tests/export/test_guards.py).
// (The unnamed SMPL-H npz is Python's alone: the browser reads no npz and says so.)
import { readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import type { ClipDoc } from '../../web/src/contract/types';
import { firstBadFrame } from '../../web/src/predictor/guard';
import { PredictError } from '../../web/src/predictor/types';
import { loadManifest, nodePredictor } from './helpers/models';

const manifest = loadManifest();
const J = manifest.skeleton.joints.length;
const S = J * 3;
const ODD: Record<string, string | null> = { walk_raised: 'root_height', walk_spikes: 'joint_speed', jump_reach_grab: null };

describe('committed odd histories give bounded futures and named warnings', () => {
  for (const [name, expected] of Object.entries(ODD)) {
    const doc = JSON.parse(readFileSync(new URL(`../fixtures/odd/${name}.json`, import.meta.url), 'utf8')) as ClipDoc;
    const frames = doc.positions.length;
    const positions = Float32Array.from(doc.positions.flat(2));
    for (const entry of manifest.models) {
      it(`${name} with ${entry.id}`, async () => {
        const ids = new Set(entry.controls.map((c) => c.id));
        let pred;
        try {
          pred = await nodePredictor(manifest, entry.id).predict({ positions, frames, joints: J }, {
            k: ids.has('k') ? 3 : 1, seed: 0, actions: ids.has('actions') ? ['walk'] : undefined,
            horizonFrames: ids.has('horizon') || ids.has('actions') ? 30 : undefined,
          });
        } catch (err) {
          // A named refusal (Keyposes: too few keyposes) is an answer too, and names the range it is out of.
          expect(err).toBeInstanceOf(PredictError);
          expect(entry.method).toBe('keyposes');
          expect((err as Error).message).toContain('keyposes');
          if (expected) expect((err as Error).message).toContain('outside the training range');
          return;
        }
        const n = entry.params.history_frames;
        const recent = positions.subarray((frames - n) * S);
        for (let i = 0; i < pred.k; i++) {
          const len = pred.lengths[i];
          const fut = pred.futures.subarray(i * pred.frames * S, (i * pred.frames + len) * S);
          expect(firstBadFrame(fut, len, recent, n, manifest.skeleton)).toBeNull();
        }
        const named = (pred.warnings ?? []).map((w) => w.quantity);
        if (expected) expect(named).toContain(expected);
      });
    }
  }
});
