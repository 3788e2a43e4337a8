// Issue 30 in TypeScript, twin of tests/export/test_odd_histories.py: the odd held-out walks of
// export/eval/odd_table.py (reflected, frozen, 0.5x/2x/3x speed, scaled 0.8/1.25, raised 0.5 m) through
// every served model as the site runs it (predictor/history.ts around factory.ts): each gives its
// warning, the scaled ones keep the first-frame jump within 1.5x the last step, a frozen one predicts
// anyway, and a refusal leads with its likely cause. ODD_MODELS_DIR checks another models directory
// (e.g. one about to be committed); the default is public/models.
import { readFileSync } from 'node:fs';
import { pathToFileURL } from 'node:url';
import * as ort from 'onnxruntime-web';
import { describe, expect, it } from 'vitest';
import type { ClipDoc, ClipIndex, Manifest } from '../../web/src/contract/types';
import { parseJson, validate } from '../../web/src/contract/validate';
import { createCheckedPredictor, refusalWithWarnings, warningsFor } from '../../web/src/predictor/history';
import type { Envelope } from '../../web/src/predictor/envelope';
import { OrtRunner, type OrtModule } from '../../web/src/predictor/ort-runner';
import { PredictError, type Prediction, type Predictor, type RangeWarning } from '../../web/src/predictor/types';

const modelsDir = process.env.ODD_MODELS_DIR ? pathToFileURL(`${process.env.ODD_MODELS_DIR.replace(/\/$/, '')}/`)
  : new URL('../../public/models/', import.meta.url);
ort.env.wasm.numThreads = 1;
ort.env.logLevel = 'error';
const manifest = validate(parseJson(readFileSync(new URL('manifest.json', modelsDir), 'utf8'), 'manifest.json'), 'manifest', 'manifest.json') as Manifest;
const J = manifest.skeleton.joints.length;
const S = J * 3;
const FRAMES = 40;
const read = (rel: string) => readFileSync(new URL(`../../public/clips/${rel}`, import.meta.url), 'utf8');
const index = JSON.parse(read('index.json')) as ClipIndex;
const walks = index.clips.filter((c) => c.role === 'test' && c.action === 'walk').slice(0, 3)
  .map((c) => Float64Array.from((JSON.parse(read(c.file)) as ClipDoc).positions.flat(2)));

const EXPECTED: Record<string, string> = {
  reflected: 'handedness', frozen: 'motion', 'speed 0.5x': 'tempo', 'speed 2x': 'tempo', 'speed 3x': 'tempo',
  'scale 0.8': 'body_scale', 'scale 1.25': 'body_scale', 'raised 0.5 m': 'root_height',
};

/** A motion played `factor` times as fast (Catmull-Rom between frames), twin of odd_table.retime. */
function retime(p: Float64Array, frames: number, factor: number): Float64Array {
  const out: number[] = [];
  const at = (f: number, i: number) => p[Math.min(Math.max(f, 0), frames - 1) * S + i];
  for (let t = 0; t < frames - 1 - 1e-9; t += factor) {
    const i = Math.floor(t);
    const u = t - i;
    for (let k = 0; k < S; k++) {
      const [p0, p1, p2, p3] = [at(i - 1, k), at(i, k), at(i + 1, k), at(i + 2, k)];
      out.push(0.5 * (2 * p1 + (p2 - p0) * u + (2 * p0 - 5 * p1 + 4 * p2 - p3) * u * u + (3 * p1 - p0 - 3 * p2 + p3) * u ** 3));
    }
  }
  return Float64Array.from(out);
}

/** FRAMES frames of a held-out walk changed as `kind` says, twin of odd_table.odd_history. */
function oddHistory(walk: Float64Array, kind: string): Float32Array {
  const base = walk.subarray(0, FRAMES * S);
  const out = new Float64Array(FRAMES * S);
  if (kind === 'reflected') base.forEach((v, i) => { out[i] = i % 3 === 0 ? -v : v; });
  else if (kind === 'frozen') for (let f = 0; f < FRAMES; f++) out.set(base.subarray((FRAMES - 1) * S, FRAMES * S), f * S);
  else if (kind.startsWith('speed')) {
    const factor = Number(kind.split(' ')[1].replace('x', ''));
    let played = retime(walk, walk.length / S, factor);
    if (played.length < FRAMES * S) played = Float64Array.from([...played, ...retime(walk, walk.length / S, factor)]);
    out.set(played.subarray(0, FRAMES * S));
  } else if (kind.startsWith('scale')) base.forEach((v, i) => { out[i] = v * Number(kind.split(' ')[1]); });
  else if (kind === 'raised 0.5 m') base.forEach((v, i) => { out[i] = i % 3 === 1 ? v + 0.5 : v; });
  else throw new Error(`unknown odd history ${kind}`);
  return Float32Array.from(out);
}

const predictors = new Map<string, Predictor>();
function predictorOf(id: string): Predictor {
  let p = predictors.get(id);
  if (!p) {
    const entry = manifest.models.find((m) => m.id === id)!;
    const load = async (file: string) => new Uint8Array(readFileSync(new URL(file, modelsDir)));
    p = createCheckedPredictor({ entry, skeleton: manifest.skeleton, actions: manifest.actions, fps: manifest.fps,
      runner: new OrtRunner(ort as unknown as OrtModule, entry, load), loadFile: load });
    predictors.set(id, p);
  }
  return p;
}

async function predict(id: string, h: Float32Array): Promise<{ pred?: Prediction; refusal?: string }> {
  const entry = manifest.models.find((m) => m.id === id)!;
  const ids = new Set(entry.controls.map((c) => c.id));
  try {
    return { pred: await predictorOf(id).predict({ positions: h, frames: FRAMES, joints: J }, {
      k: ids.has('k') ? 3 : 1, seed: 0, actions: ids.has('actions') ? ['walk'] : undefined,
      horizonFrames: ids.has('horizon') || ids.has('actions') ? 30 : undefined,
    }) };
  } catch (err) {
    expect(err).toBeInstanceOf(PredictError);
    return { refusal: (err as Error).message };
  }
}

function firstMessage(id: string, h: Float32Array, quantity: string): string {
  const entry = manifest.models.find((m) => m.id === id)!;
  const n = entry.params.history_frames;
  const ws = warningsFor(h.subarray((FRAMES - n) * S), n, manifest.fps, manifest.skeleton,
    (entry.params as { envelope?: Envelope }).envelope);
  return ws.find((w) => w.quantity === quantity)?.message ?? '<no such warning>';
}

/** null when the odd history gets its warning (a refusal leading with it counts), else what it got. */
async function gives(id: string, kind: string, walk: Float64Array): Promise<string | null> {
  const h = oddHistory(walk, kind);
  const { pred, refusal } = await predict(id, h);
  if (pred) {
    const got = (pred.warnings ?? []).map((w) => w.quantity);
    return got.includes(EXPECTED[kind]) ? null : `warned [${got.join(', ')}]`;
  }
  return refusal!.startsWith(firstMessage(id, h, EXPECTED[kind])) ? null : `refused: ${refusal}`;
}

function jumpAndStep(h: Float32Array, future: Float32Array): [number, number] {
  let jump = 0;
  let step = 0;
  for (let j = 0; j < J; j++) {
    const l = (FRAMES - 1) * S + j * 3;
    const p = (FRAMES - 2) * S + j * 3;
    jump += Math.hypot(future[j * 3] - h[l], future[j * 3 + 1] - h[l + 1], future[j * 3 + 2] - h[l + 2]);
    step += Math.hypot(h[l] - h[p], h[l + 1] - h[p + 1], h[l + 2] - h[p + 2]);
  }
  return [jump / J, step / J];
}

describe('the odd held-out walks of issue 30 give their warning with every served model', () => {
  for (const entry of manifest.models) {
    it(`${entry.id}`, async () => {
      const misses: string[] = [];
      for (const kind of Object.keys(EXPECTED).filter((k) => k !== 'speed 0.5x')) {
        for (const [i, w] of walks.entries()) {
          const got = await gives(entry.id, kind, w);
          if (got !== null) misses.push(`${kind} (walk ${i}): ${got}`);
        }
      }
      expect(misses).toEqual([]);
    }, 120_000);
  }
  // tempo sees about half of the held-out walk windows at 0.5x (export/ops/envelope.py): a known miss. Here it is
  // the first walk from frame 0, a person standing before the first step (tests/export/test_odd_histories.py)
  it.fails('a walk at half speed is warned, every time', async () => {
    for (const w of walks) expect(await gives(manifest.models[0].id, 'speed 0.5x', w)).toBeNull();
  });
});

describe('scaled histories are brought to the model size: the first frame continues the last step', () => {
  for (const entry of manifest.models) {
    it(`${entry.id}: 0.8 and 1.25`, async () => {
      for (const kind of ['scale 0.8', 'scale 1.25']) {
        for (const w of walks) {
          const h = oddHistory(w, kind);
          const { pred, refusal } = await predict(entry.id, h);
          expect(refusal).toBeUndefined();
          for (let i = 0; i < pred!.k; i++) {
            const [jump, step] = jumpAndStep(h, pred!.futures.subarray(i * pred!.frames * S));
            expect(jump).toBeLessThanOrEqual(1.5 * step);
          }
        }
      }
    }, 120_000);
  }
});

describe('a frozen history is said not to move, and predicted anyway', () => {
  for (const entry of manifest.models) {
    it(`${entry.id}`, async () => {
      const { pred, refusal } = await predict(entry.id, oddHistory(walks[0], 'frozen'));
      expect(refusal).toBeUndefined();
      const w = pred!.warnings!.find((x) => x.quantity === 'motion')!;
      expect(w.message).toMatch(/^The history does not move: its fastest joint moves at \d\.\d{3} m\/s/);
    });
  }
});

describe('a refusal leads with its likely cause', () => {
  const w = (quantity: string, value: number, min: number, max: number, message: string): RangeWarning => ({ quantity, value, min, max, message });
  it('the quantity farthest outside its range first, then the refusal, then the rest', () => {
    const msg = refusalWithWarnings('choose a history with more motion',
      [w('root_speed', 2.1, 0, 2, 'Speed is high.'), w('root_height', 1.6, 0.3, 1.1, 'Root is high.')]);
    expect(msg).toBe('Root is high. That is the most likely cause of this refusal, the quantity farthest outside the training range: '
      + 'choose a history with more motion. Also outside the training range: Speed is high.');
    expect(refusalWithWarnings('no', [w('root_height', 1.6, 0.3, 1.1, 'Root is high.'), w('motion', 0, 0.05, 10, 'Does not move.')]))
      .toMatch(/^Does not move\. That is the most likely cause of this refusal: no\./);
    expect(refusalWithWarnings('no', [])).toBe('no');
  });
});
