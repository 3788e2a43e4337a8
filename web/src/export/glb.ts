// Export what is shown as a binary glTF (GLB) with one animation, via three.js's GLTFExporter.
// Layout (Blender imports it as animated empties/meshes in a hierarchy):
//   motion-futures
//     history              <- a figure: a group per figure
//       history_root       <- a node per joint, nested like the skeleton, a small sphere each;
//         history_chest       its translation track is the offset from its parent joint
//         ...
//     sample_1 ...         <- each future ("<model>_sample_1" when several models are shown); hidden
//                             (scale 0, STEP) until half a frame before its first
//     ground_truth         <- what the clip really does next, the same way (when the clip has it)
// Time: frame f of the history at f / fps; future frame i at (history frames + i) / fps. Like the
// page, the history holds its last pose while the futures play, and each future holds its last pose.
// The scene's extras ("runs") record each model's run (model, its own history, seed, controls,
// plant_feet), and each future's group its model and sample.
import {
  AnimationClip, Group, IcosahedronGeometry, InterpolateDiscrete, Mesh, MeshStandardMaterial, Object3D, VectorKeyframeTrack,
  type KeyframeTrack,
} from 'three';
import { GLTFExporter } from 'three/examples/jsm/exporters/GLTFExporter.js';
import { sideOf, tintColour, type Side } from '../viewer/palette';
import { checkShown, figureName, futureName, modelsText, runRecord, TRUTH_FIGURE, type Shown } from './shown';

export const JOINT_RADIUS = 0.02;

/** Node name of a joint of a figure, e.g. "sample_2_left_knee" (safe for three's track bindings). */
export function jointNodeName(figure: string, joint: string): string {
  return `${figure}_${joint}`;
}

interface Figure { name: string; sample: number | null; run?: number; truth?: boolean; positions: Float32Array; frames: number; first: number }

/** The scene and animation of a Shown (exported by glbBytes; also useful for tests and previews). */
export function shownScene(s: Shown): { scene: Group; clip: AnimationClip } {
  checkShown(s);
  const J = s.joints;
  const parents = s.skeleton.parents;
  const scene = new Group();
  scene.name = 'motion-futures';
  scene.userData = { runs: s.runs.map(runRecord) };
  const geometry = new IcosahedronGeometry(JOINT_RADIUS, 1);
  const tracks: KeyframeTrack[] = [];
  const figures: Figure[] = [
    { name: figureName(null), sample: null, positions: s.history.positions, frames: s.history.frames, first: 0 },
    ...s.futures.map((f) => ({ name: futureName(s, f), sample: f.sample, run: f.run, positions: f.positions, frames: f.frames, first: s.history.frames })),
    ...(s.truth ? [{ name: TRUTH_FIGURE, sample: null, truth: true, positions: s.truth.positions, frames: s.truth.frames, first: s.history.frames }] : []),
  ];
  for (const fig of figures) {
    const group = new Group();
    group.name = fig.name;
    if (fig.run !== undefined) group.userData = { ...(s.runs[fig.run].model ? { model: s.runs[fig.run].model } : {}), sample: fig.sample! + 1 };
    scene.add(group);
    const tint = fig.truth ? { role: 'truth' as const } : fig.sample === null ? { role: 'history' as const } : { role: 'prediction' as const, sample: fig.sample };
    const materials = new Map<Side, MeshStandardMaterial>();
    const material = (side: Side) => {
      if (!materials.has(side)) {
        const [r, g, b] = tintColour(side, tint);
        const m = new MeshStandardMaterial({ color: 0xffffff, roughness: 0.6 });
        m.color.setRGB(r, g, b);
        m.name = `${fig.name}_${side}`;
        materials.set(side, m);
      }
      return materials.get(side)!;
    };
    const times = Float32Array.from({ length: fig.frames }, (_, f) => (fig.first + f) / s.fps);
    const nodes: Object3D[] = [];
    for (let j = 0; j < J; j++) {
      const joint = s.skeleton.joints[j];
      const node = new Mesh(geometry, material(sideOf(joint)));
      node.name = jointNodeName(fig.name, joint);
      const p = parents[j];
      (p < 0 ? group : nodes[p]).add(node);
      nodes.push(node);
      // translation relative to the parent joint (parents have no rotation, so this is exact)
      const values = new Float32Array(fig.frames * 3);
      for (let f = 0; f < fig.frames; f++) {
        for (let c = 0; c < 3; c++) {
          const here = fig.positions[(f * J + j) * 3 + c];
          values[f * 3 + c] = p < 0 ? here : here - fig.positions[(f * J + p) * 3 + c];
        }
      }
      node.position.fromArray(values, 0);
      tracks.push(new VectorKeyframeTrack(`${node.name}.position`, times, values));
    }
    if (fig.first > 0) {
      // hidden until the future starts, as on the page; the step sits half a frame early because
      // keyframe times are float32 and (first / fps) may round up past a player's frame time
      group.scale.setScalar(0);
      tracks.push(new VectorKeyframeTrack(`${fig.name}.scale`, [0, (fig.first - 0.5) / s.fps], [0, 0, 0, 1, 1, 1], InterpolateDiscrete));
    }
  }
  const clip = new AnimationClip(modelsText(s) ? `${s.name} (${modelsText(s)})` : s.name, -1, tracks);
  return { scene, clip };
}

/** The GLB file's bytes. */
export async function glbBytes(s: Shown): Promise<ArrayBuffer> {
  const { scene, clip } = shownScene(s);
  const out = await new GLTFExporter().parseAsync(scene, { binary: true, animations: [clip], trs: true, onlyVisible: false });
  if (!(out instanceof ArrayBuffer)) throw new Error('export: GLTFExporter did not return binary glTF');
  return out;
}
