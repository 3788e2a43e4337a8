// The figures' root paths, drawn faintly on the floor: every path in one LineSegments (one draw call),
// with each path's colour and opacity in its vertex colours. Software WebGL pays per draw call and
// per material: 52 separate transparent lines (K = 50) took about 30 ms a frame, the first frame after
// a new result about 190 ms (probe of make bench's K = 50 page). A selection rewrites the alphas.
import { BufferAttribute, BufferGeometry, Color, LineBasicMaterial, LineSegments, SRGBColorSpace } from 'three';
import type { Rgb } from './palette';

export interface RootPath {
  /** [frames * 3] world positions of the root, drawn at `height` above the floor. */
  points: Float32Array;
  /** sRGB in [0, 1]. */
  colour: Rgb;
}

export class RootPaths {
  readonly object: LineSegments;
  private readonly material = new LineBasicMaterial({ vertexColors: true, transparent: true, depthWrite: false });
  private geometry = new BufferGeometry();
  /** Per path, its first vertex and vertex count. */
  private spans: { start: number; count: number }[] = [];
  private colours = new Float32Array(0);

  constructor(private readonly height: number) {
    this.object = new LineSegments(this.geometry, this.material);
    this.object.frustumCulled = false; // rebuilt with every set of tracks
  }

  /** Replace every path; all start at opacity 0.5. */
  set(paths: readonly RootPath[]): void {
    const vertices = paths.reduce((n, p) => n + p.points.length / 3, 0);
    const positions = new Float32Array(vertices * 3);
    this.colours = new Float32Array(vertices * 4);
    const segments: number[] = [];
    const c = new Color();
    this.spans = [];
    let v = 0;
    for (const path of paths) {
      const n = path.points.length / 3;
      this.spans.push({ start: v, count: n });
      c.setRGB(path.colour[0], path.colour[1], path.colour[2], SRGBColorSpace);
      for (let f = 0; f < n; f++) {
        positions[(v + f) * 3] = path.points[f * 3];
        positions[(v + f) * 3 + 1] = this.height;
        positions[(v + f) * 3 + 2] = path.points[f * 3 + 2];
        const at = (v + f) * 4;
        this.colours[at] = c.r; this.colours[at + 1] = c.g; this.colours[at + 2] = c.b; this.colours[at + 3] = 0.5;
        if (f > 0) segments.push(v + f - 1, v + f);
      }
      v += n;
    }
    const geometry = new BufferGeometry();
    geometry.setAttribute('position', new BufferAttribute(positions, 3));
    geometry.setAttribute('color', new BufferAttribute(this.colours, 4)); // the 4th channel is the opacity
    geometry.setIndex(vertices > 65535 ? new BufferAttribute(new Uint32Array(segments), 1) : new BufferAttribute(new Uint16Array(segments), 1));
    this.geometry.dispose();
    this.geometry = geometry;
    this.object.geometry = geometry;
  }

  /** Set path i's opacity (paths in the order given to `set`). */
  setOpacity(opacity: (i: number) => number): void {
    let changed = false;
    this.spans.forEach(({ start, count }, i) => {
      const a = opacity(i);
      if (this.colours[start * 4 + 3] === Math.fround(a)) return; // stored as float32
      for (let f = 0; f < count; f++) this.colours[(start + f) * 4 + 3] = a;
      changed = true;
    });
    if (changed) (this.geometry.getAttribute('color') as BufferAttribute).needsUpdate = true;
  }

  /** Opacity of path i now (for tests). */
  opacity(i: number): number | null {
    const s = this.spans[i];
    return s ? this.colours[s.start * 4 + 3] : null;
  }

  /** Number of paths. */
  get count(): number {
    return this.spans.length;
  }

  dispose(): void {
    this.geometry.dispose();
    this.material.dispose();
  }
}
