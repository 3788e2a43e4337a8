// Exports of compare mode (issue 29 items 2 and 4): every compared model's futures, named after their
// model, on one timeline after the longest history, the ground truth once, and each model's run
// (its own history, seed, controls, foot planting) recorded so it can be made again.
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { GLTFLoader, type GLTF } from 'three/examples/jsm/loaders/GLTFLoader.js';
import { parseJson, validate } from '../../web/src/contract/validate';
import { motionFromDoc } from '../../web/src/motion/clip';
import { clipJson } from '../../web/src/export/clip-json';
import { csvText } from '../../web/src/export/csv';
import { glbBytes } from '../../web/src/export/glb';
import { shownFromRuns, type RunPrediction } from '../../web/src/export/shown';
import type { Prediction } from '../../web/src/predictor/types';
import { exportBaseName, exportDescription } from '../../web/src/ui/export-panel';
import { droppedWalk, predictFromDropped } from './helpers/dropped';

// GLTFExporter assembles the GLB with FileReader, which Node lacks (as in export-glb.test.ts).
class NodeFileReader {
  result: ArrayBuffer | null = null;
  onloadend: (() => void) | null = null;
  readAsArrayBuffer(blob: Blob): void { void blob.arrayBuffer().then((b) => { this.result = b; this.onloadend?.(); }); }
}
const g = globalThis as { FileReader?: unknown };
const hadFileReader = 'FileReader' in g;
beforeAll(() => { if (!hadFileReader) g.FileReader = NodeFileReader; });
afterAll(() => { if (!hadFileReader) delete g.FileReader; });

const END = 22;   // both histories end at this frame of the walk

/** The regression GRU's future from frames [12, 22), and a second "model" with a 19-frame history
 *  ending at the same frame: K bent copies of that future, with lengths of their own. */
async function twoRuns(k = 3): Promise<RunPrediction[]> {
  const m = droppedWalk();
  const { prediction: p, n } = await predictFromDropped(m, END - 10);
  expect(n).toBe(10);
  const stride = p.joints * 3;
  const frames = p.frames + 6;
  const futures = new Float32Array(k * frames * stride);
  for (let i = 0; i < k; i++) {
    for (let f = 0; f < frames; f++) {
      for (let v = 0; v < stride; v++) futures[(i * frames + f) * stride + v] = p.futures[Math.min(f, p.frames - 1) * stride + v] + (v % 3 === 0 ? 0.1 * (i + 1) : 0);
    }
  }
  const lengths = Int32Array.from({ length: k }, (_, i) => frames - 4 * i);
  const other: Prediction = { ...p, k, frames, futures, lengths, samples: Array.from({ length: k }, (_, i) => ({ length: lengths[i], stopped: true, segments: [] })) };
  return [
    { model: 'regression-gru', hash: 'sha256:aa', label: 'Regression GRU', start: END - 10, historyFrames: 10, seed: 4, controls: { horizon: 2 }, plantFeet: true, prediction: p },
    { model: 'lcp-vae', hash: 'sha256:bb', label: 'LCP-VAE', start: END - 19, historyFrames: 19, seed: 4, controls: { k, horizon: 2, sigma_scale: 2 }, plantFeet: false, prediction: other },
  ];
}

const slice = (a: Float32Array, stride: number, from: number, frames: number) => a.slice(from * stride, (from + frames) * stride);

describe('compare-mode exports', () => {
  it('the Shown: the longest history, every run\'s futures in row order, the truth as far as the longest of all', async () => {
    const runs = await twoRuns();
    const m = droppedWalk();
    const s = shownFromRuns(m, runs);
    const stride = m.joints * 3;
    expect([s.start, s.history.frames]).toEqual([END - 19, 19]);
    expect(s.history.positions).toEqual(slice(m.positions, stride, END - 19, 19));
    expect(s.futures.map((f) => [f.run, f.sample])).toEqual([[0, 0], [1, 0], [1, 1], [1, 2]]);
    const longest = Math.max(...runs.flatMap((r) => [...r.prediction.lengths]));
    expect(longest).toBeGreaterThan(runs[0].prediction.lengths[0]);
    expect(s.truth!.frames).toBe(Math.min(m.frames - END, longest));
    expect(s.truth!.positions).toEqual(slice(m.positions, stride, END, s.truth!.frames));
    expect(s.runs.map((r) => r.model)).toEqual(['regression-gru', 'lcp-vae']);
    expect(s.runs[1]).not.toHaveProperty('prediction');
    expect(exportBaseName(s)).toBe('walk.regression-gru+lcp-vae.4-futures');
    expect(exportDescription(s)).toBe('The history of walk with the futures of Regression GRU (1) and LCP-VAE (3) and the ground truth, '
      + 'each named after its model (select one to save only it).');
  });

  it('CSV: each future\'s figure starts with its model, the truth once, all after the shared history', async () => {
    const runs = await twoRuns();
    const s = shownFromRuns(droppedWalk(), runs);
    const back: Record<string, { first: number; xyz: number[] }> = {};
    for (const row of csvText(s).trimEnd().split('\n').slice(1)) {
      const [figure, frame, , , x, y, z] = row.split(',');
      (back[figure] ??= { first: Number(frame), xyz: [] }).xyz.push(Number(x), Number(y), Number(z));
    }
    expect(Object.keys(back)).toEqual(['history', 'regression-gru_sample_1', 'lcp-vae_sample_1', 'lcp-vae_sample_2', 'lcp-vae_sample_3', 'ground_truth']);
    expect(back['lcp-vae_sample_2'].first).toBe(19);
    expect(back['regression-gru_sample_1'].first).toBe(19);
    expect(Float32Array.from(back['lcp-vae_sample_3'].xyz)).toEqual(s.futures[3].positions);
    expect(Float32Array.from(back['regression-gru_sample_1'].xyz)).toEqual(s.futures[0].positions);
    expect(Float32Array.from(back.ground_truth.xyz)).toEqual(s.truth!.positions);
  });

  it('JSON: one clip per future named after its model, each source recording its run with plant_feet, the truth once', async () => {
    const runs = await twoRuns();
    const s = shownFromRuns(droppedWalk(), runs);
    const docs = (parseJson(clipJson(s), 'compare.json') as unknown[]).map((d, i) => validate(d, 'clip', `compare.json[${i}]`));
    expect(docs.map((d) => d.name)).toEqual(['walk.regression-gru_sample_1', 'walk.lcp-vae_sample_1', 'walk.lcp-vae_sample_2',
      'walk.lcp-vae_sample_3', 'walk.ground_truth']);
    const source = (i: number) => docs[i].source as Record<string, unknown>;
    expect(source(0)).toMatchObject({ model: 'regression-gru', sample: 1, start: END - 19, history_frames: 19 });
    expect(source(0).run).toEqual({ model: 'regression-gru', model_hash: 'sha256:aa', model_label: 'Regression GRU', history_start: END - 10,
      history_frames: 10, seed: 4, controls: { horizon: 2 }, plant_feet: true });
    expect(source(2).run).toMatchObject({ model: 'lcp-vae', history_start: END - 19, history_frames: 19, controls: { k: 3, horizon: 2, sigma_scale: 2 }, plant_feet: false });
    expect(source(4)).not.toHaveProperty('run');
    expect(docs.filter((d) => d.action === 'ground truth')).toHaveLength(1);
    // each clip: the shared history, then its future
    const clip = motionFromDoc(docs[2]).positions;
    expect(clip.slice(0, s.history.positions.length)).toEqual(s.history.positions);
    expect(clip.slice(s.history.positions.length)).toEqual(s.futures[2].positions);
  });

  it('GLB: a group per future named after its model, and every run in the scene\'s extras', async () => {
    const runs = await twoRuns(2);
    const s = shownFromRuns(droppedWalk(), runs);
    const gltf = await new Promise<GLTF>((resolve, reject) => { void glbBytes(s).then((b) => new GLTFLoader().parse(b, '', resolve, reject), reject); });
    const root = gltf.scene.getObjectByName('motion-futures')!;
    expect(root.children.map((c) => c.name)).toEqual(['history', 'regression-gru_sample_1', 'lcp-vae_sample_1', 'lcp-vae_sample_2', 'ground_truth']);
    expect(root.children[3].userData).toMatchObject({ model: 'lcp-vae', sample: 2 });
    expect((root.userData.runs as { model: string; plant_feet: boolean }[]).map((r) => [r.model, r.plant_feet])).toEqual([['regression-gru', true], ['lcp-vae', false]]);
    expect(gltf.animations[0].name).toBe('walk (regression-gru+lcp-vae)');
  });

  it('a selected sample: that future of each model that has it', async () => {
    const runs = await twoRuns();
    const m = droppedWalk();
    const first = shownFromRuns(m, runs, { selected: 0 });
    expect(first.futures.map((f) => [f.run, f.sample])).toEqual([[0, 0], [1, 0]]);
    expect(exportDescription(first)).toBe('The history of walk with future #1 of Regression GRU and LCP-VAE and the ground truth.');
    const third = shownFromRuns(m, runs, { selected: 2 });   // the deterministic model has one future only
    expect(third.futures.map((f) => [f.run, f.sample])).toEqual([[1, 2]]);
    expect(exportDescription(third)).toBe('The history of walk with future #3 of LCP-VAE and the ground truth.');
    expect(csvText(third).split('\n').some((r) => r.startsWith('lcp-vae_sample_3,'))).toBe(true);
  });

  it('one model is the single view: plain figure names, its own history', async () => {
    const [one] = await twoRuns();
    const s = shownFromRuns(droppedWalk(), [one]);
    expect([s.start, s.history.frames]).toEqual([END - 10, 10]);
    expect(csvText(s).split('\n').slice(1).map((r) => r.split(',')[0]).filter((v, i, a) => v && a.indexOf(v) === i)).toEqual(['history', 'sample_1', 'ground_truth']);
    expect(exportBaseName(s)).toBe('walk.regression-gru.sample_1');
  });

  it('runs whose histories end at different frames, or share an id, are refused with a message', async () => {
    const runs = await twoRuns();
    const m = droppedWalk();
    expect(() => shownFromRuns(m, [runs[0], { ...runs[1], start: runs[1].start + 1 }])).toThrow("export: lcp-vae's history ends at frame 23, not 22 like the others'");
    expect(() => shownFromRuns(m, [runs[0], { ...runs[1], model: 'regression-gru' }])).toThrow('export: each compared model needs its own id');
    expect(() => shownFromRuns(m, [])).toThrow('export: there is no prediction to export; predict first');
  });
});
