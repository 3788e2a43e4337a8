// Many skeletons in two draw calls: one InstancedMesh of bone cylinders, one of joint spheres.
// A crowd (more than CROWD figures, e.g. K = 50) is drawn coarser: software WebGL (SwiftShader, what
// a machine without a GPU uses) spends its frame on vertices, and 50 figures of 18 fine spheres
// took 200-280 ms a frame here (make bench); at that count each figure is small on screen, so bones
// with fewer sides and a sphere for the head only read the same.
import {
  Color, CylinderGeometry, Group, InstancedMesh, Matrix4, MeshLambertMaterial, Quaternion, SRGBColorSpace,
  SphereGeometry, Vector3,
} from 'three';
import type { Skeleton } from '../contract/types';
import { sideOf, tintColour, tintScale, type Side, type Tint } from './palette';

export interface FigureDraw {
  /** [joints * 3] metres. */
  pose: Float32Array;
  x: number;
  z: number;
  tint: Tint;
}

const BONE_RADIUS = 0.022;
const JOINT_RADIUS = 0.034;
// A head about 0.16 m wide on this 1.46 m figure; 0.1 read as oversized next to the thin bones.
const HEAD_RADIUS = 0.08;
const SIDES: Side[] = ['left', 'right', 'mid'];
/** Above this many figures the crowd detail is drawn. */
export const CROWD = 20;

/** Segments of a bone's cylinder and of a joint's sphere, and whether every joint gets a sphere. */
export interface Detail { boneSides: number; sphere: [number, number]; everyJoint: boolean }
export const FINE: Detail = { boneSides: 10, sphere: [14, 10], everyJoint: true };
export const COARSE: Detail = { boneSides: 6, sphere: [10, 7], everyJoint: false };

export function detailFor(figures: number): Detail {
  return figures > CROWD ? COARSE : FINE;
}
const UP = new Vector3(0, 1, 0);

export class SkeletonFigures {
  readonly group = new Group();
  private detail: Detail = FINE;
  private boneGeometry = new CylinderGeometry(1, 1, 1, FINE.boneSides, 1, true);
  private jointGeometry = new SphereGeometry(1, ...FINE.sphere);
  private readonly material = new MeshLambertMaterial({ color: 0xffffff });
  private bones: InstancedMesh | null = null;
  private joints: InstancedMesh | null = null;
  private capacity = 0;
  private bonePairs: [number, number][] = [];
  private boneSides: Side[] = [];
  private jointSides: Side[] = [];
  private jointRadii: number[] = [];
  /** The joint that shows a figure's identity colour (the head). */
  private identityJoint = 0;
  // Scratch objects: draw() runs every animation frame.
  private readonly m = new Matrix4();
  private readonly q = new Quaternion();
  private readonly a = new Vector3();
  private readonly b = new Vector3();
  private readonly d = new Vector3();
  private readonly s = new Vector3();
  private readonly c = new Color();
  private readonly colours: Record<Side, Color> = { left: new Color(), right: new Color(), mid: new Color() };

  setSkeleton(skeleton: Skeleton): void {
    this.bonePairs = [];
    this.boneSides = [];
    skeleton.parents.forEach((p, j) => {
      if (p < 0) return;
      this.bonePairs.push([p, j]);
      this.boneSides.push(sideOf(skeleton.joints[j]));
    });
    this.jointSides = skeleton.joints.map(sideOf);
    this.jointRadii = skeleton.joints.map((name) => (name === 'head' ? HEAD_RADIUS : JOINT_RADIUS));
    this.identityJoint = Math.max(0, skeleton.joints.indexOf('head'));
    this.capacity = 0; // joint count may differ: rebuild on next draw
  }

  /** The detail the last draw used. */
  get drawnDetail(): Detail {
    return this.detail;
  }

  draw(figures: readonly FigureDraw[]): void {
    this.ensureCapacity(figures.length, detailFor(figures.length));
    const sphereJoints = this.sphereJoints();
    const bones = this.bones!;
    const joints = this.joints!;
    let bi = 0;
    let ji = 0;
    for (const f of figures) {
      const scale = tintScale(f.tint);
      for (const side of SIDES) {
        const [r, g, b] = tintColour(side, f.tint);
        this.colours[side].setRGB(r, g, b, SRGBColorSpace);
      }
      const p = f.pose;
      for (let k = 0; k < this.bonePairs.length; k++) {
        const [pa, ch] = this.bonePairs[k];
        this.a.set(p[pa * 3] + f.x, p[pa * 3 + 1], p[pa * 3 + 2] + f.z);
        this.b.set(p[ch * 3] + f.x, p[ch * 3 + 1], p[ch * 3 + 2] + f.z);
        this.d.subVectors(this.b, this.a);
        const len = this.d.length();
        if (len > 1e-9) this.q.setFromUnitVectors(UP, this.d.divideScalar(len));
        else this.q.identity();
        this.a.add(this.b).multiplyScalar(0.5);
        this.s.set(BONE_RADIUS * scale, len, BONE_RADIUS * scale);
        bones.setMatrixAt(bi, this.m.compose(this.a, this.q, this.s));
        bones.setColorAt(bi++, this.colours[this.boneSides[k]]);
      }
      this.q.identity();
      for (const j of sphereJoints) {
        this.a.set(p[j * 3] + f.x, p[j * 3 + 1], p[j * 3 + 2] + f.z);
        const r = this.jointRadii[j] * scale;
        this.s.set(r, r, r);
        joints.setMatrixAt(ji, this.m.compose(this.a, this.q, this.s));
        joints.setColorAt(ji++, this.colours[this.jointSides[j]]);
      }
    }
    bones.count = bi;
    joints.count = ji;
    bones.instanceMatrix.needsUpdate = true;
    joints.instanceMatrix.needsUpdate = true;
    if (bones.instanceColor) bones.instanceColor.needsUpdate = true;
    if (joints.instanceColor) joints.instanceColor.needsUpdate = true;
  }

  /** The colour the head of drawn figure `i` (in the last draw's order) has in the GPU's instance
   *  colours, as '#rrggbb' sRGB: what the screen shows, for the legend and the tests. */
  identityHex(i: number): string | null {
    const colours = this.joints?.instanceColor;
    const per = this.sphereJoints();
    const index = i * per.length + per.indexOf(this.identityJoint);
    if (!colours || !this.joints || index >= this.joints.count) return null;
    return this.c.fromArray(colours.array, index * 3).getHexString(SRGBColorSpace).replace(/^/, '#');
  }

  dispose(): void {
    this.bones?.dispose();
    this.joints?.dispose();
    this.boneGeometry.dispose();
    this.jointGeometry.dispose();
    this.material.dispose();
  }

  /** The joints drawn as spheres at the current detail: all, or the head only. */
  private sphereJoints(): number[] {
    return this.detail.everyJoint ? this.jointSides.map((_, j) => j) : [this.identityJoint];
  }

  private ensureCapacity(figures: number, detail: Detail): void {
    if (detail !== this.detail) {
      this.detail = detail;
      this.boneGeometry.dispose();
      this.jointGeometry.dispose();
      this.boneGeometry = new CylinderGeometry(1, 1, 1, detail.boneSides, 1, true);
      this.jointGeometry = new SphereGeometry(1, ...detail.sphere);
      this.capacity = 0;
    }
    if (figures <= this.capacity && this.bones) return;
    // Grow geometrically so adding samples one by one does not rebuild every time.
    const capacity = Math.max(8, figures, this.capacity * 2);
    for (const mesh of [this.bones, this.joints]) {
      if (mesh) { this.group.remove(mesh); mesh.dispose(); }
    }
    this.bones = this.makeMesh(this.boneGeometry, capacity * Math.max(1, this.bonePairs.length));
    this.joints = this.makeMesh(this.jointGeometry, capacity * Math.max(1, this.jointSides.length));
    this.capacity = capacity;
  }

  private makeMesh(geometry: CylinderGeometry | SphereGeometry, count: number): InstancedMesh {
    const mesh = new InstancedMesh(geometry, this.material, count);
    mesh.count = 0;
    // Instances move every frame; a stale bounding sphere would cull visible figures.
    mesh.frustumCulled = false;
    mesh.setColorAt(0, this.c.set(0xffffff)); // allocates instanceColor
    this.group.add(mesh);
    return mesh;
  }
}
