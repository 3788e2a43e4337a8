// Many skeletons in one draw call: every frame the bones' cylinders and the joints' spheres are placed
// on the CPU into one vertex buffer. Software WebGL (SwiftShader, what a machine without a GPU uses)
// pays for every instance of an instanced draw: the 867 bones of 50 figures took 25-35 ms a draw as an
// InstancedMesh and 8-10 ms as this one buffer (same triangles, probe of make bench's K = 50 page).
// A crowd (more than CROWD figures) is also drawn coarser: at that count each figure is small on
// screen, so bones with fewer sides and a sphere for the head only read the same.
import {
  BufferAttribute, BufferGeometry, Color, CylinderGeometry, DynamicDrawUsage, Group, Mesh,
  MeshLambertMaterial, Quaternion, SRGBColorSpace, SphereGeometry, Vector3,
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

export const BONE_RADIUS = 0.022;
export const JOINT_RADIUS = 0.034;
// A head about 0.16 m wide on this 1.46 m figure; 0.1 read as oversized next to the thin bones.
export const HEAD_RADIUS = 0.08;
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

/** A unit shape's vertices: the cylinder spans y in [-0.5, 0.5] with radius 1, the sphere radius 1. */
interface Shape { position: Float32Array; normal: Float32Array; index: number[]; vertices: number }

function shape(g: BufferGeometry): Shape {
  const out = {
    position: Float32Array.from(g.attributes.position.array),
    normal: Float32Array.from(g.attributes.normal.array),
    index: Array.from(g.index!.array),
    vertices: g.attributes.position.count,
  };
  g.dispose();
  return out;
}

/** What the last draw put in the buffer. */
export interface Drawn { figures: number; bones: number; spheres: number; vertices: number }

export class SkeletonFigures {
  readonly group = new Group();
  private detail: Detail = FINE;
  private bone = shape(new CylinderGeometry(1, 1, 1, FINE.boneSides, 1, true));
  private sphere = shape(new SphereGeometry(1, ...FINE.sphere));
  private readonly material = new MeshLambertMaterial({ color: 0xffffff, vertexColors: true });
  private geometry = new BufferGeometry();
  private readonly mesh = new Mesh(this.geometry, this.material);
  private positions = new Float32Array(0);
  private normals = new Float32Array(0);
  private colours = new Float32Array(0);
  /** Figures the buffers hold; 0 forces a rebuild (new skeleton or detail). */
  private capacity = 0;
  private bonePairs: [number, number][] = [];
  private boneSides: Side[] = [];
  private jointSides: Side[] = [];
  private jointRadii: number[] = [];
  /** The joints drawn as spheres at the current detail: all, or the head only. */
  private sphereJoints: number[] = [];
  /** The joint that shows a figure's identity colour (the head). */
  private identityJoint = 0;
  private last: Drawn = { figures: 0, bones: 0, spheres: 0, vertices: 0 };
  // Scratch objects: draw() runs every animation frame.
  private readonly q = new Quaternion();
  private readonly d = new Vector3();
  private readonly c = new Color();
  private readonly sideColours: Record<Side, Color> = { left: new Color(), right: new Color(), mid: new Color() };

  constructor() {
    // Vertices move every frame; a stale bounding sphere would cull visible figures.
    this.mesh.frustumCulled = false;
    this.group.add(this.mesh);
  }

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

  /** Counts of the last draw. */
  get drawn(): Drawn {
    return { ...this.last };
  }

  draw(figures: readonly FigureDraw[]): void {
    this.ensureCapacity(figures.length, detailFor(figures.length));
    const perFigure = this.verticesPerFigure();
    let v = 0;
    for (const f of figures) {
      const scale = tintScale(f.tint);
      for (const side of SIDES) {
        const [r, g, b] = tintColour(side, f.tint);
        this.sideColours[side].setRGB(r, g, b, SRGBColorSpace);
      }
      const p = f.pose;
      for (let k = 0; k < this.bonePairs.length; k++) {
        const [pa, ch] = this.bonePairs[k];
        v = this.placeBone(v, p, pa, ch, f.x, f.z, BONE_RADIUS * scale, this.sideColours[this.boneSides[k]]);
      }
      for (const j of this.sphereJoints) {
        v = this.placeSphere(v, p[j * 3] + f.x, p[j * 3 + 1], p[j * 3 + 2] + f.z, this.jointRadii[j] * scale,
          this.sideColours[this.jointSides[j]]);
      }
    }
    const used = figures.length * perFigure;
    for (const name of ['position', 'normal', 'color']) {
      const attribute = this.geometry.getAttribute(name) as BufferAttribute;
      attribute.clearUpdateRanges();
      attribute.addUpdateRange(0, used * 3); // upload only the figures drawn
      attribute.needsUpdate = true;
    }
    this.geometry.setDrawRange(0, figures.length * this.indicesPerFigure());
    this.last = {
      figures: figures.length, bones: figures.length * this.bonePairs.length,
      spheres: figures.length * this.sphereJoints.length, vertices: used,
    };
  }

  /** The colour the head of drawn figure `i` (in the last draw's order) has in the vertex colours, as
   *  '#rrggbb' sRGB: what the screen shows, for the legend and the tests. */
  identityHex(i: number): string | null {
    const at = this.sphereJoints.indexOf(this.identityJoint);
    if (i < 0 || i >= this.last.figures || at < 0) return null;
    const vertex = i * this.verticesPerFigure() + this.bonePairs.length * this.bone.vertices + at * this.sphere.vertices;
    return this.c.fromArray(this.colours, vertex * 3).getHexString(SRGBColorSpace).replace(/^/, '#');
  }

  /** World positions [n * 3] of one bone (index into the skeleton's bones, parent order) or one joint's
   *  sphere of drawn figure `i`; null when that part is not drawn. */
  partVertices(i: number, part: { bone: number } | { joint: number }): Float32Array | null {
    if (i < 0 || i >= this.last.figures) return null;
    let start = i * this.verticesPerFigure();
    let count: number;
    if ('bone' in part) {
      if (part.bone < 0 || part.bone >= this.bonePairs.length) return null;
      start += part.bone * this.bone.vertices;
      count = this.bone.vertices;
    } else {
      const at = this.sphereJoints.indexOf(part.joint);
      if (at < 0) return null;
      start += this.bonePairs.length * this.bone.vertices + at * this.sphere.vertices;
      count = this.sphere.vertices;
    }
    return this.positions.slice(start * 3, (start + count) * 3);
  }

  dispose(): void {
    this.geometry.dispose();
    this.material.dispose();
  }

  private verticesPerFigure(): number {
    return this.bonePairs.length * this.bone.vertices + this.sphereJoints.length * this.sphere.vertices;
  }

  private indicesPerFigure(): number {
    return this.bonePairs.length * this.bone.index.length + this.sphereJoints.length * this.sphere.index.length;
  }

  /** The unit cylinder stretched from joint `pa` to joint `ch`, turned from +y onto the bone. */
  private placeBone(v: number, p: Float32Array, pa: number, ch: number, x: number, z: number, radius: number, colour: Color): number {
    const ax = p[pa * 3] + x; const ay = p[pa * 3 + 1]; const az = p[pa * 3 + 2] + z;
    const bx = p[ch * 3] + x; const by = p[ch * 3 + 1]; const bz = p[ch * 3 + 2] + z;
    this.d.set(bx - ax, by - ay, bz - az);
    const len = this.d.length();
    if (len > 1e-9) this.q.setFromUnitVectors(UP, this.d.divideScalar(len));
    else this.q.identity();
    // The rotation's matrix, written out: it is applied to every vertex.
    const { x: qx, y: qy, z: qz, w: qw } = this.q;
    const r00 = 1 - 2 * (qy * qy + qz * qz); const r01 = 2 * (qx * qy - qz * qw); const r02 = 2 * (qx * qz + qy * qw);
    const r10 = 2 * (qx * qy + qz * qw); const r11 = 1 - 2 * (qx * qx + qz * qz); const r12 = 2 * (qy * qz - qx * qw);
    const r20 = 2 * (qx * qz - qy * qw); const r21 = 2 * (qy * qz + qx * qw); const r22 = 1 - 2 * (qx * qx + qy * qy);
    const mx = (ax + bx) / 2; const my = (ay + by) / 2; const mz = (az + bz) / 2;
    const { position, normal, vertices } = this.bone;
    const P = this.positions; const N = this.normals; const C = this.colours;
    for (let k = 0; k < vertices; k++, v++) {
      const lx = position[k * 3] * radius; const ly = position[k * 3 + 1] * len; const lz = position[k * 3 + 2] * radius;
      P[v * 3] = mx + r00 * lx + r01 * ly + r02 * lz;
      P[v * 3 + 1] = my + r10 * lx + r11 * ly + r12 * lz;
      P[v * 3 + 2] = mz + r20 * lx + r21 * ly + r22 * lz;
      // A side's normal has no y part, so stretching along y leaves it as it is: only turn it.
      const nx = normal[k * 3]; const ny = normal[k * 3 + 1]; const nz = normal[k * 3 + 2];
      N[v * 3] = r00 * nx + r01 * ny + r02 * nz;
      N[v * 3 + 1] = r10 * nx + r11 * ny + r12 * nz;
      N[v * 3 + 2] = r20 * nx + r21 * ny + r22 * nz;
      C[v * 3] = colour.r; C[v * 3 + 1] = colour.g; C[v * 3 + 2] = colour.b;
    }
    return v;
  }

  private placeSphere(v: number, cx: number, cy: number, cz: number, radius: number, colour: Color): number {
    const { position, normal, vertices } = this.sphere;
    const P = this.positions; const N = this.normals; const C = this.colours;
    for (let k = 0; k < vertices; k++, v++) {
      P[v * 3] = cx + position[k * 3] * radius;
      P[v * 3 + 1] = cy + position[k * 3 + 1] * radius;
      P[v * 3 + 2] = cz + position[k * 3 + 2] * radius;
      N[v * 3] = normal[k * 3]; N[v * 3 + 1] = normal[k * 3 + 1]; N[v * 3 + 2] = normal[k * 3 + 2];
      C[v * 3] = colour.r; C[v * 3 + 1] = colour.g; C[v * 3 + 2] = colour.b;
    }
    return v;
  }

  private ensureCapacity(figures: number, detail: Detail): void {
    if (detail !== this.detail) {
      this.detail = detail;
      this.bone = shape(new CylinderGeometry(1, 1, 1, detail.boneSides, 1, true));
      this.sphere = shape(new SphereGeometry(1, ...detail.sphere));
      this.capacity = 0;
    }
    if (figures <= this.capacity && this.capacity > 0) return;
    // a new skeleton or detail zeroes the capacity, so the spheres' joints are set whenever they change
    this.sphereJoints = detail.everyJoint ? this.jointSides.map((_, j) => j) : [this.identityJoint];
    // Grow geometrically so adding samples one by one does not rebuild every time.
    const capacity = Math.max(8, figures, this.capacity * 2);
    const perFigure = this.verticesPerFigure();
    const vertices = capacity * perFigure;
    this.positions = new Float32Array(vertices * 3);
    this.normals = new Float32Array(vertices * 3);
    this.colours = new Float32Array(vertices * 3);
    // The triangles never change: figure after figure, its bones then its spheres.
    const index = vertices > 65535 ? new Uint32Array(capacity * this.indicesPerFigure()) : new Uint16Array(capacity * this.indicesPerFigure());
    let i = 0;
    let base = 0;
    for (let f = 0; f < capacity; f++) {
      for (let k = 0; k < this.bonePairs.length; k++, base += this.bone.vertices) {
        for (const t of this.bone.index) index[i++] = base + t;
      }
      for (let s = 0; s < this.sphereJoints.length; s++, base += this.sphere.vertices) {
        for (const t of this.sphere.index) index[i++] = base + t;
      }
    }
    const geometry = new BufferGeometry();
    for (const [name, array] of [['position', this.positions], ['normal', this.normals], ['color', this.colours]] as const) {
      geometry.setAttribute(name, new BufferAttribute(array, 3).setUsage(DynamicDrawUsage));
    }
    geometry.setIndex(new BufferAttribute(index, 1));
    geometry.setDrawRange(0, 0);
    this.geometry.dispose();
    this.geometry = geometry;
    this.mesh.geometry = geometry;
    this.capacity = capacity;
  }
}
