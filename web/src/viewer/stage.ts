// The three.js stage: renderer, camera, orbit controls, grid, lights and the figures' HTML labels;
// renders only when something changed. The camera frames a plan (what must be in view at each
// timeline frame) and follows it as the figures travel.
import {
  Box3, Color, DirectionalLight, GridHelper, HemisphereLight, PerspectiveCamera, Scene, Vector3,
  WebGLRenderer,
} from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import { CSS2DRenderer } from 'three/examples/jsm/renderers/CSS2DRenderer.js';
import { requireWebGL2, WebGLUnavailableError } from './webgl';

interface Theme { background: Color; gridCentre: Color; grid: Color }

/**
 * What the camera keeps in view: for each timeline frame the box of the figures shown then and the
 * point the camera looks at then (a smoothed centre). One distance serves every frame, so the view
 * pans with travelling figures without zooming in and out.
 */
export interface FramePlan {
  direction: Vector3;
  boxes: Box3[];
  centres: Vector3[];
  /** Per frame, the corners (x, y, z triples) of every shown figure's own box: the fit frames these when
   *  given, which is tighter than the corners of the union's world-axis box once the grid is turned to
   *  the figures' heading (that box's empty corners cost a side-by-side grid a fifth of its size). */
  corners?: Float32Array[];
}

export class Stage {
  readonly scene = new Scene();
  readonly camera = new PerspectiveCamera(40, 1, 0.05, 200);
  readonly renderer: WebGLRenderer;
  readonly labels: CSS2DRenderer;
  readonly controls: OrbitControls;
  /** Drawn by the CPU: antialiasing is off (see the constructor). */
  readonly software: boolean;
  private grid: GridHelper | null = null;
  private gridSize = 0;
  private gridCentre = new Vector3();
  private pending = 0;
  private theme: Theme;
  private plan: FramePlan | null = null;
  private t = 0;
  private userMoved = false;
  private readonly resizeObserver: ResizeObserver;
  private readonly colourScheme = window.matchMedia('(prefers-color-scheme: dark)');
  private readonly onScheme = () => { this.applyTheme(); };
  /** Called on every render after the camera has moved and before the labels are drawn: labels that
   *  are placed on screen (viewer.ts) are placed from where the camera is then. */
  beforeLabels: (() => void) | null = null;
  private drawn = { width: 1, height: 1 };

  /** Throws WebGLUnavailableError when no usable WebGL 2 context can be made. */
  constructor(private readonly container: HTMLElement, private readonly onContextLost?: (lost: boolean) => void) {
    // Multisampling on a CPU renderer doubles every frame's cost: the 50 figures of K = 50 took 21 ms
    // a draw with it and 8-10 ms without (make bench probe), so software WebGL draws without it.
    this.software = requireWebGL2().software;
    try {
      this.renderer = new WebGLRenderer({ antialias: !this.software, powerPreference: 'high-performance' });
    } catch (err) {
      throw new WebGLUnavailableError(`The 3D viewer could not start WebGL: ${(err as Error).message}`);
    }
    this.renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
    container.dataset.renderer = this.software ? 'software' : 'gpu'; // for make bench's notes
    const canvas = this.renderer.domElement;
    canvas.classList.add('stage-canvas');
    canvas.setAttribute('role', 'img');
    canvas.setAttribute('aria-label', 'Skeleton figures in 3D; drag to orbit, scroll to zoom, click a figure to select it');
    container.append(canvas);
    this.labels = new CSS2DRenderer();
    this.labels.domElement.classList.add('stage-labels');
    this.labels.domElement.setAttribute('aria-hidden', 'true');
    container.append(this.labels.domElement);

    this.theme = this.readTheme();
    this.scene.background = this.theme.background;
    this.scene.add(new HemisphereLight(0xffffff, 0x667080, 2.0));
    const sun = new DirectionalLight(0xffffff, 1.6);
    sun.position.set(3, 6, 4);
    this.scene.add(sun);
    this.setGrid(6, new Vector3());

    this.controls = new OrbitControls(this.camera, canvas);
    this.controls.maxPolarAngle = Math.PI * 0.495; // stay above the floor
    this.controls.minDistance = 0.3;
    this.controls.maxDistance = 160;
    this.controls.addEventListener('change', () => this.invalidate());
    this.controls.addEventListener('start', () => { this.userMoved = true; });

    canvas.addEventListener('webglcontextlost', (e) => { e.preventDefault(); this.onContextLost?.(true); });
    canvas.addEventListener('webglcontextrestored', () => { this.onContextLost?.(false); this.invalidate(); });
    this.resizeObserver = new ResizeObserver(() => this.resize());
    this.resizeObserver.observe(container);
    this.colourScheme.addEventListener('change', this.onScheme);
    this.resize();
  }

  /** Schedule one render on the next animation frame (coalesced). */
  invalidate(): void {
    if (this.pending) return;
    this.pending = requestAnimationFrame(() => {
      this.pending = 0;
      this.render();
    });
  }

  /** Like invalidate(), a frame later: after heavy work (a new set of tracks) the first draw gets a
   *  frame of its own instead of landing in the frame that work delayed. Later invalidate() calls
   *  before it join it. */
  invalidateAfterNextFrame(): void {
    cancelAnimationFrame(this.pending);
    this.pending = requestAnimationFrame(() => {
      this.pending = requestAnimationFrame(() => {
        this.pending = 0;
        this.render();
      });
    });
  }

  /** Render now (the labels too). */
  render(): void {
    this.renderer.render(this.scene, this.camera);
    this.beforeLabels?.();
    this.labels.render(this.scene, this.camera);
  }

  /** A grid of 0.5 m squares, `size` metres wide, centred near `centre` (snapped to whole metres). */
  setGrid(size: number, centre: Vector3): void {
    const s = Math.max(2, Math.ceil(size / 2) * 2);
    const c = new Vector3(Math.round(centre.x), 0, Math.round(centre.z));
    if (s === this.gridSize && c.equals(this.gridCentre) && this.grid) return;
    this.gridSize = s;
    this.gridCentre = c;
    if (this.grid) { this.scene.remove(this.grid); this.grid.dispose(); }
    this.grid = new GridHelper(s, s * 2, this.theme.gridCentre, this.theme.grid);
    this.grid.position.copy(c);
    this.scene.add(this.grid);
    this.invalidate();
  }

  /** Frame a plan (every figure at every frame) and look at its frame `t`. */
  fit(plan: FramePlan, t = this.t): void {
    this.plan = { direction: plan.direction.clone().normalize(), boxes: plan.boxes, centres: plan.centres, corners: plan.corners };
    this.t = t;
    this.userMoved = false;
    this.applyFit();
  }

  /** Keep looking at the plan's frame `t` (fractional): the camera and its target move together, so an
   *  orbit or zoom the user made is kept while the figures travel. */
  follow(t: number): void {
    this.t = t;
    if (!this.plan) return;
    const want = this.centreAt(t);
    const delta = want.sub(this.controls.target);
    if (delta.lengthSq() < 1e-12) return;
    this.controls.target.add(delta);
    this.camera.position.add(delta);
    this.controls.update();
  }

  /** Return to the plan's framing. */
  resetView(): void {
    if (this.plan) { this.userMoved = false; this.applyFit(); }
  }

  dispose(): void {
    cancelAnimationFrame(this.pending);
    this.resizeObserver.disconnect();
    this.colourScheme.removeEventListener('change', this.onScheme);
    this.controls.dispose();
    this.grid?.dispose();
    this.renderer.dispose();
    this.renderer.domElement.remove();
    this.labels.domElement.remove();
  }

  private centreAt(t: number): Vector3 {
    const cs = this.plan!.centres;
    if (!cs.length) return new Vector3();
    const a = Math.max(0, Math.min(cs.length - 1, Math.floor(t)));
    const b = Math.min(cs.length - 1, a + 1);
    return cs[a].clone().lerp(cs[b], Math.max(0, Math.min(1, t - a)));
  }

  /** The one distance at which every frame's box, seen from its centre along the direction, fits the view. */
  private distance(): number {
    const { boxes, centres, direction } = this.plan!;
    const right = new Vector3().crossVectors(new Vector3(0, 1, 0), direction).normalize();
    if (right.lengthSq() < 1e-9) right.set(1, 0, 0);
    const up = new Vector3().crossVectors(direction, right).normalize();
    const tanV = Math.tan((this.camera.fov * Math.PI) / 360);
    const tanH = tanV * this.camera.aspect;
    let distance = 1;
    const corner = new Vector3();
    const reach = () => {
      const toward = corner.dot(direction);
      distance = Math.max(distance, toward + Math.abs(corner.dot(right)) / tanH, toward + Math.abs(corner.dot(up)) / tanV);
    };
    const { corners } = this.plan!;
    boxes.forEach((box, f) => {
      if (box.isEmpty()) return;
      const points = corners?.[f];
      if (points && points.length) {
        for (let i = 0; i < points.length; i += 3) { corner.set(points[i], points[i + 1], points[i + 2]).sub(centres[f]); reach(); }
        return;
      }
      for (let i = 0; i < 8; i++) {
        corner.set(i & 1 ? box.max.x : box.min.x, i & 2 ? box.max.y : box.min.y, i & 4 ? box.max.z : box.min.z).sub(centres[f]);
        reach();
      }
    });
    return distance * 1.06; // a little air around the figures
  }

  private applyFit(): void {
    if (!this.plan) return;
    const distance = this.distance();
    const centre = this.centreAt(this.t);
    this.controls.target.copy(centre);
    this.camera.position.copy(centre).addScaledVector(this.plan.direction, distance);
    this.camera.near = Math.max(0.01, distance / 100);
    this.camera.far = distance * 10 + 80;
    this.camera.updateProjectionMatrix();
    this.controls.update();
    this.invalidate();
  }

  private resize(): void {
    const w = Math.max(1, this.container.clientWidth);
    const h = Math.max(1, this.container.clientHeight);
    this.renderer.setSize(w, h, false);
    this.labels.setSize(w, h);
    this.drawn = { width: w, height: h };
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    if (!this.userMoved) this.applyFit();
    this.invalidate();
  }

  private readTheme(): Theme {
    const css = getComputedStyle(this.container);
    const colour = (name: string, fallback: string) => new Color(css.getPropertyValue(name).trim() || fallback);
    return {
      background: colour('--stage-bg', '#eef0f3'),
      gridCentre: colour('--stage-grid-centre', '#9aa3ad'),
      grid: colour('--stage-grid', '#c9ced4'),
    };
  }

  private applyTheme(): void {
    this.theme = this.readTheme();
    this.scene.background = this.theme.background;
    const size = this.gridSize;
    this.gridSize = 0;
    this.setGrid(size, this.gridCentre);
  }

  /** The size drawn at, as of the last resize: read in the render without forcing a layout. */
  get drawnSize(): { width: number; height: number } { return this.drawn; }

  /** Width and height of the drawing area in CSS pixels. */
  get size(): { width: number; height: number } {
    return { width: Math.max(1, this.container.clientWidth), height: Math.max(1, this.container.clientHeight) };
  }
}
