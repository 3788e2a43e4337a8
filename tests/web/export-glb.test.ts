// GLB export of what is shown: re-imported with three.js's GLTFLoader in Node, the animated joint
// nodes are where the history, each future and the ground truth put them, frame by frame.
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { AnimationMixer, LoopOnce, Vector3, type Object3D } from 'three';
import { GLTFLoader, type GLTF } from 'three/examples/jsm/loaders/GLTFLoader.js';
import { glbBytes, jointNodeName } from '../../web/src/export/glb';
import { figureName, type Shown } from '../../web/src/export/shown';
import { shownWithSamples } from './helpers/dropped';

// GLTFExporter assembles the GLB with FileReader, which Node lacks: the one polyfill needed.
class NodeFileReader {
  result: ArrayBuffer | string | null = null;
  onloadend: (() => void) | null = null;
  readAsArrayBuffer(blob: Blob): void {
    void blob.arrayBuffer().then((b) => { this.result = b; this.onloadend?.(); });
  }
}
const g = globalThis as { FileReader?: unknown };
const hadFileReader = 'FileReader' in g;
beforeAll(() => { if (!hadFileReader) g.FileReader = NodeFileReader; });
afterAll(() => { if (!hadFileReader) delete g.FileReader; });

function load(bytes: ArrayBuffer): Promise<GLTF> {
  return new Promise((resolve, reject) => new GLTFLoader().parse(bytes, '', resolve, reject));
}

/** World position of every joint node of every figure at time t, through the animation. */
function posesAt(gltf: GLTF, mixer: AnimationMixer, t: number, s: Shown, figure: string): { p: number[][]; visible: boolean } {
  mixer.existingAction(gltf.animations[0])!.reset().play(); // a finished, clamped action stays paused otherwise
  mixer.setTime(t);
  gltf.scene.updateMatrixWorld(true);
  const group = gltf.scene.getObjectByName(figure)!;
  const v = new Vector3();
  const p = s.skeleton.joints.map((j) => (gltf.scene.getObjectByName(jointNodeName(figure, j)) as Object3D).getWorldPosition(v).toArray());
  return { p, visible: group.scale.x > 0 };
}

async function roundTrip(s: Shown) {
  const bytes = await glbBytes(s);
  expect(new TextDecoder().decode(new Uint8Array(bytes, 0, 4))).toBe('glTF');
  const gltf = await load(bytes);
  const mixer = new AnimationMixer(gltf.scene);
  expect(gltf.animations).toHaveLength(1);
  // play once and hold the end, as a timeline does (the mixer's default would loop back to 0)
  const action = mixer.clipAction(gltf.animations[0]);
  action.setLoop(LoopOnce, 1);
  action.clampWhenFinished = true;
  action.play();
  return { bytes, gltf, mixer };
}

function worst(got: number[][], want: Float32Array, frame: number, joints: number): number {
  let w = 0;
  got.forEach((xyz, j) => xyz.forEach((v, c) => { w = Math.max(w, Math.abs(v - want[(frame * joints + j) * 3 + c])); }));
  return w;
}

describe('GLB export', () => {
  it('all K futures with the history: every joint of every figure at every frame, to 1e-5 m', async () => {
    const s = await shownWithSamples(3);
    const { bytes, gltf, mixer } = await roundTrip(s);
    const H = s.history.frames;
    const names = gltf.scene.getObjectByName('motion-futures')!.children.map((c) => c.name);
    expect(names).toEqual(['history', 'sample_1', 'sample_2', 'sample_3', 'ground_truth']);
    expect(gltf.animations[0].duration).toBeCloseTo((H + s.futures[0].frames - 1) / s.fps, 5);
    let err = 0;
    for (let f = 0; f < H; f++) {
      const { p, visible } = posesAt(gltf, mixer, f / s.fps, s, 'history');
      expect(visible).toBe(true);
      err = Math.max(err, worst(p, s.history.positions, f, s.joints));
      for (const fut of s.futures) expect(posesAt(gltf, mixer, f / s.fps, s, figureName(fut.sample)).visible).toBe(false);
      expect(posesAt(gltf, mixer, f / s.fps, s, 'ground_truth').visible).toBe(false);
    }
    // the ground truth plays after the history like a future, every frame where the clip put it
    const truth = s.truth!;
    expect(truth.frames).toBeGreaterThan(0);
    for (let f = 0; f < truth.frames; f++) {
      const { p, visible } = posesAt(gltf, mixer, (H + f) / s.fps, s, 'ground_truth');
      expect(visible, `ground_truth frame ${f}`).toBe(true);
      err = Math.max(err, worst(p, truth.positions, f, s.joints));
    }
    for (const fut of s.futures) {
      for (let f = 0; f < fut.frames; f++) {
        const { p, visible } = posesAt(gltf, mixer, (H + f) / s.fps, s, figureName(fut.sample));
        expect(visible, `${figureName(fut.sample)} frame ${f}`).toBe(true);
        err = Math.max(err, worst(p, fut.positions, f, s.joints));
      }
      // after its end a future holds its last pose, as on the page
      const { p } = posesAt(gltf, mixer, (H + fut.frames + 5) / s.fps, s, figureName(fut.sample));
      err = Math.max(err, worst(p, fut.positions, fut.frames - 1, s.joints));
    }
    // and the history holds its last pose while the futures play
    err = Math.max(err, worst(posesAt(gltf, mixer, (H + 3) / s.fps, s, 'history').p, s.history.positions, H - 1, s.joints));
    console.info(`GLB round trip: ${(bytes.byteLength / 1024).toFixed(0)} KiB, max joint error ${err.toExponential(2)} m`);
    expect(err).toBeLessThan(1e-5);
  });

  it('the selected future only', async () => {
    const s = await shownWithSamples(3, 1);
    const { gltf, mixer } = await roundTrip(s);
    expect(gltf.scene.getObjectByName('motion-futures')!.children.map((c) => c.name)).toEqual(['history', 'sample_2', 'ground_truth']);
    const fut = s.futures[0];
    const { p } = posesAt(gltf, mixer, (s.history.frames + 4) / s.fps, s, 'sample_2');
    expect(worst(p, fut.positions, 4, s.joints)).toBeLessThan(1e-5);
  });

  it('an empty export is refused with a message', async () => {
    const s = await shownWithSamples(1);
    await expect(glbBytes({ ...s, futures: [] })).rejects.toThrow('there is no future to export; predict first');
  });
});
