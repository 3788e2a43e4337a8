// Issue 28, target 8: Keyposes predicts from every served clip's default history (the window the page
// opens a picked clip on, web/src/ui/history-picker.ts defaultStart), on the committed model.
import { describe, expect, it } from 'vitest';
import { readFileSync } from 'node:fs';
import * as ort from 'onnxruntime-web';
import type { ClipIndex, Manifest } from '../../web/src/contract/types';
import type { Motion } from '../../web/src/motion/clip';
import { KeyposesPredictor } from '../../web/src/predictor/keyposes';
import { OrtRunner, type OrtModule } from '../../web/src/predictor/ort-runner';
import { defaultStart } from '../../web/src/ui/history-picker';
import { loadManifest } from './helpers/models';

const modelsDir = new URL('../../public/models/', import.meta.url);
const manifest: Manifest = loadManifest();
const entry = manifest.models.find((m) => m.method === 'keyposes');
const index: ClipIndex = JSON.parse(readFileSync(new URL('../../public/clips/index.json', import.meta.url), 'utf8'));
const readModelFile = async (file: string) => new Uint8Array(readFileSync(new URL(file, modelsDir)));

describe.runIf(entry)('Keyposes accepts every served clip at its default history', () => {
  const runner = new OrtRunner(ort as unknown as OrtModule, entry!, readModelFile);
  const p = new KeyposesPredictor({ entry: entry!, skeleton: manifest.skeleton, actions: manifest.actions, fps: manifest.fps,
    runner, loadFile: readModelFile });
  const n = entry!.params.history_frames as number;

  it('predicts from each clip without a refusal', async () => {
    const refused: string[] = [];
    const long = index.clips.filter((c) => c.frames >= n);   // a shorter clip holds no history at all
    expect(long.length).toBeGreaterThan(20);
    for (const c of long) {
      const doc = JSON.parse(readFileSync(new URL(`../../public/clips/${c.file}`, import.meta.url), 'utf8')) as { positions: number[][][] };
      const positions = Float32Array.from(doc.positions.flat(2));
      const joints = doc.positions[0].length;
      const motion = { name: c.name, frames: doc.positions.length, joints, fps: index.fps, positions, test: c.test, train: c.train } as unknown as Motion;
      const start = defaultStart(motion, n);
      const history = { positions: positions.slice(start * joints * 3, (start + n) * joints * 3), frames: n, joints };
      try {
        const pred = await p.predict(history, { k: 2, seed: 0, horizonFrames: 30 });
        expect(pred.futures.length).toBeGreaterThan(0);
      } catch (e) {
        refused.push(`${c.name}@${start}: ${(e as Error).message}`);
      }
    }
    expect(refused).toEqual([]);
  }, 120_000);
});
