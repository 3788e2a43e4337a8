// The three.js stage: renderer, camera, orbit controls, grid and lights; renders only when something changed.
import {
  Box3, Color, DirectionalLight, GridHelper, HemisphereLight, PerspectiveCamera, Scene, Vector3,
  WebGLRenderer,
} from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import { requireWebGL2, WebGLUnavailableError } from './webgl';

interface Theme { background: Color; gridCentre: Color; grid: Color }

export class Stage {
  readonly scene = new Scene();
  readonly camera = new PerspectiveCamera(40, 1, 0.05, 200);
  readonly renderer: WebGLRenderer;
  readonly controls: OrbitControls;
  private grid: GridHelper | null = null;
  private gridSize = 0;
  private pending = 0;
  private theme: Theme;
  private lastFit: { box: Box3; direction: Vector3 } | null = null;
  private userMoved = false;
  private readonly resizeObserver: ResizeObserver;
  private readonly colourScheme = window.matchMedia('(prefers-color-scheme: dark)');
  private readonly onScheme = () => { this.applyTheme(); };

  /** Throws WebGLUnavailableError when no usable WebGL 2 context can be made. */
  constructor(private readonly container: HTMLElement, private readonly onContextLost?: (lost: boolean) => void) {
    requireWebGL2();
    try {
      this.renderer = new WebGLRenderer({ antialias: true, powerPreference: 'high-performance' });
    } catch (err) {
      throw new WebGLUnavailableError(`The 3D viewer could not start WebGL: ${(err as Error).message}`);
    }
    this.renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
    const canvas = this.renderer.domElement;
    canvas.classList.add('stage-canvas');
    canvas.setAttribute('role', 'img');
    canvas.setAttribute('aria-label', 'Skeleton figures in 3D; drag to orbit, scroll to zoom');
    container.append(canvas);

    this.theme = this.readTheme();
    this.scene.background = this.theme.background;
    this.scene.add(new HemisphereLight(0xffffff, 0x667080, 2.0));
    const sun = new DirectionalLight(0xffffff, 1.6);
    sun.position.set(3, 6, 4);
    this.scene.add(sun);
    this.setGridSize(6);

    this.controls = new OrbitControls(this.camera, canvas);
    this.controls.maxPolarAngle = Math.PI * 0.495; // stay above the floor
    this.controls.minDistance = 0.3;
    this.controls.maxDistance = 120;
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
      this.renderer.render(this.scene, this.camera);
    });
  }

  setGridSize(size: number): void {
    const s = Math.max(2, Math.ceil(size / 2) * 2);
    if (s === this.gridSize && this.grid) return;
    this.gridSize = s;
    if (this.grid) { this.scene.remove(this.grid); this.grid.dispose(); }
    this.grid = new GridHelper(s, s * 2, this.theme.gridCentre, this.theme.grid); // 0.5 m squares
    this.scene.add(this.grid);
    this.invalidate();
  }

  /** Aim at `box` from `direction`, close enough that it fills the view. */
  fit(box: Box3, direction: Vector3): void {
    this.lastFit = { box: box.clone(), direction: direction.clone().normalize() };
    this.userMoved = false;
    this.applyFit();
  }

  /** Return to the last framing. */
  resetView(): void {
    if (this.lastFit) { this.userMoved = false; this.applyFit(); }
  }

  dispose(): void {
    cancelAnimationFrame(this.pending);
    this.resizeObserver.disconnect();
    this.colourScheme.removeEventListener('change', this.onScheme);
    this.controls.dispose();
    this.grid?.dispose();
    this.renderer.dispose();
    this.renderer.domElement.remove();
  }

  private applyFit(): void {
    if (!this.lastFit) return;
    const { box, direction } = this.lastFit;
    const centre = box.getCenter(new Vector3());
    // Camera basis looking along -direction; move back until every box corner is inside the frustum.
    const right = new Vector3().crossVectors(new Vector3(0, 1, 0), direction).normalize();
    if (right.lengthSq() < 1e-9) right.set(1, 0, 0);
    const up = new Vector3().crossVectors(direction, right).normalize();
    const tanV = Math.tan((this.camera.fov * Math.PI) / 360);
    const tanH = tanV * this.camera.aspect;
    let distance = 1;
    const corner = new Vector3();
    for (let i = 0; i < 8; i++) {
      corner.set(i & 1 ? box.max.x : box.min.x, i & 2 ? box.max.y : box.min.y, i & 4 ? box.max.z : box.min.z).sub(centre);
      const toward = corner.dot(direction);
      distance = Math.max(distance, toward + Math.abs(corner.dot(right)) / tanH, toward + Math.abs(corner.dot(up)) / tanV);
    }
    distance *= 1.08; // a little air around the figures
    this.controls.target.copy(centre);
    this.camera.position.copy(centre).addScaledVector(direction, distance);
    this.camera.near = Math.max(0.01, distance / 100);
    this.camera.far = distance * 10 + 50;
    this.camera.updateProjectionMatrix();
    this.controls.update();
    this.invalidate();
  }

  private resize(): void {
    const w = Math.max(1, this.container.clientWidth);
    const h = Math.max(1, this.container.clientHeight);
    this.renderer.setSize(w, h, false);
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
    this.setGridSize(size);
  }
}
