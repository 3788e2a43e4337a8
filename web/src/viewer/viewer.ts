// The skeleton viewer: tracks on a shared timeline, laid out overlaid or side by side. Figures travel
// over the floor with their root paths drawn faintly; each figure (each cell, side by side) carries a
// label in its identity colour; the camera frames every figure after each change of tracks or layout
// and follows them as they travel. A camera preset (front, side, top, or following one figure) turns
// that framing; in a sequence each label names the figure's current action, and a badge says when its
// sample has stopped; a toggle marks the sample closest to the ground truth, another hides the truth.
import { Box3, Group, Vector3 } from 'three';
import { CSS2DObject } from 'three/examples/jsm/renderers/CSS2DRenderer.js';
import type { Skeleton } from '../contract/types';
import { facingAngle } from '../motion/facing';
import { SkeletonFigures, type FigureDraw } from './figures';
import { bestPerRow, type BestSample } from './best';
import { labelRect, placeLabel, type Rect } from './label-place';
import { layoutTracks, ROW_SPACING, type Layout, type LayoutMode } from './layout';
import { identityColour, identityCss } from './palette';
import { RootPaths } from './paths';
import { Stage, type FramePlan } from './stage';
import { figureStatus, poseInto, timelineLength, trackPose, type Track } from './tracks';

/** Where the camera looks from: 'auto' is the default framing (three-quarter front, raised side by
 *  side); 'follow' frames one figure (the selected sample, else the highlighted best, else #1) and
 *  travels with it. */
export type CameraPreset = 'auto' | 'front' | 'side' | 'top' | 'follow';
export const CAMERA_PRESETS: readonly CameraPreset[] = ['auto', 'front', 'side', 'top', 'follow'];

export interface SetTracksOptions {
  /** Keep the camera where it is (by default every new set of tracks is framed). */
  keepView?: boolean;
}

/** A figure as drawn now: what it is, its identity colour as the GPU holds it, and where it is on screen. */
export interface FigureInfo {
  /** The track's id (a shared history copy carries its cell's track id in `cell`). */
  track: string;
  role: Track['role'];
  sample?: number;
  /** The label shown over the figure (side by side: over its cell). */
  label: string;
  /** Cell of the layout (0 when overlaid). */
  cell: number;
  shared: boolean;
  /** '#rrggbb': the instance colour of the figure's head, as drawn. */
  colour: string | null;
  /** Projected bounding box of the figure's joints, CSS pixels from the canvas's top-left. */
  box: { left: number; top: number; right: number; bottom: number };
  /** The action its label names now (a sequence only), and whether it shows the "stopped" badge. */
  action: string | null;
  stopped: boolean;
  /** It is the highlighted sample closest to the ground truth. */
  best: boolean;
  /** Compare mode: the method's row (track.group). */
  group?: number;
}

/** What the page talks to; the UI never needs to know whether WebGL is there. */
export interface SkeletonView {
  readonly layout: LayoutMode;
  setTracks(tracks: readonly Track[], skeleton: Skeleton, options?: SetTracksOptions): void;
  /** Remove every figure. */
  clear(): void;
  setLayout(mode: LayoutMode): void;
  /** Fractional position on the shared timeline, in frames. */
  setFrame(t: number): void;
  /** Highlight one prediction sample, or none. */
  setSelected(sample: number | null): void;
  /** Called with the sample a click on a figure or its label picks (null: a click on nothing). */
  onPick(handler: (sample: number | null) => void): void;
  /** The figures drawn now (empty without WebGL). */
  figures(): FigureInfo[];
  resetView(): void;
  /** Turn the camera to a preset (kept across new tracks until changed). */
  setCamera(preset: CameraPreset): void;
  readonly camera: CameraPreset;
  /** The unit vector from the point looked at to the camera, in the world frame (null without WebGL). */
  viewDirection(): [number, number, number] | null;
  /** Highlight the sample closest to the ground truth (kept across new tracks). */
  setBestShown(on: boolean): void;
  /** Show or hide the ground truth's figure, label and path (kept across new tracks). */
  setTruthShown(on: boolean): void;
  /** The sample closest to the ground truth among the tracks given, or null (no truth, no samples);
   *  in compare mode, in the page's own model's row (group 0). */
  best(): BestSample | null;
  /** Compare mode: the closest sample of each method's row, in row order (one model: its one row). */
  bestRows(): readonly BestSample[];
  /** What is on stage: each track drawn, in order (a hidden ground truth is not). */
  shownTracks(): readonly Pick<Track, 'role' | 'sample' | 'group'>[];
  /** Called after every setTracks() and clear(), and when the ground truth is shown or hidden. */
  onTracks(handler: () => void): void;
  dispose(): void;
}

// Camera directions: a three-quarter front view of one figure; a raised front view of a grid. Both
// are turned to the figures' heading.
const OVERLAY_VIEW = new Vector3(0.65, 0.35, 1);
const SIDE_VIEW = new Vector3(0.25, 0.95, 1);
/** The presets' directions in the figures' frame (+z their heading, +x their left): front and side a
 *  little raised so the floor and the paths read; top from just behind, so the heading points up. */
const PRESET_VIEWS: Record<Exclude<CameraPreset, 'auto' | 'follow'>, Vector3> = {
  front: new Vector3(0, 0.2, 1),
  side: new Vector3(1, 0.2, 0),
  top: new Vector3(0, 1, -0.03),
};
/** Following one figure, the camera's path is smoothed less: it keeps up with that figure. */
const FOLLOW_ONE_SMOOTHING = 5;
const UP = new Vector3(0, 1, 0);
/** Room between cells beyond what the figures need (metres), and the smallest cells. */
const CELL_GAP = 0.35;
const MIN_CELL_WIDTH = 1.0;
/** Rows closer than this hide each other from the raised front view (layout.ts ROW_SPACING). */
const MIN_CELL_DEPTH = ROW_SPACING;
/** The largest cells: one sample that walks 4 m while the others stand would otherwise make every
 *  cell 4 m wide and every figure a few dozen pixels tall; past this a far walker may cross into a
 *  neighbour's cell (its colour and label still say whose it is). Readable figures over no overlap. */
const MAX_CELL_WIDTH = 1.8;
const MAX_CELL_DEPTH = 2.0;
/** Frames the camera's path is averaged over on each side: it glides instead of jittering with every step. */
const FOLLOW_SMOOTHING = 12;
const LABEL_LIFT = 0.3;
const LABEL_STEP = 0.17;
const PATH_HEIGHT = 0.004;

interface LabelSlot {
  object: CSS2DObject;
  element: HTMLElement;
  /** Placements (indices) whose figure the label sits over, the first visible one wins. */
  placements: number[];
  sample?: number;
  /** The track the label names (its cell's own track side by side). */
  track: number;
  /** The parts after the name: current action, "stopped", "closest to truth" (text as shown). */
  action: HTMLElement;
  stopped: HTMLElement;
  best: HTMLElement;
  /** Height above the head (metres): overlaid figures share a place, so their labels stack. */
  lift: number;
  /** Where the label sits in the world (over its figure's head): the ground truth's may be moved on screen. */
  home: Vector3;
  /** Its size in CSS px as last laid out (labelSizes): reading it in the render would force a layout
   *  each frame, 3-6 ms at K = 50 in software rendering. */
  size: { width: number; height: number };
}

export class Viewer implements SkeletonView {
  private readonly stage: Stage;
  private readonly figuresMesh = new SkeletonFigures();
  private readonly paths = new RootPaths(PATH_HEIGHT);
  private readonly labelGroup = new Group();
  private tracks: readonly Track[] = [];
  /** The tracks as given (the ground truth included when hidden), and their pose boxes. */
  private given: readonly Track[] = [];
  private givenBoxes: Box3[][] = [];
  private preset: CameraPreset = 'auto';
  private bestShown = false;
  private truthShown = true;
  /** The closest sample of each row (one model: one row); highlighted while bestShown. */
  private bests: readonly BestSample[] = [];
  private trackListeners: (() => void)[] = [];
  private skeleton: Skeleton | null = null;
  /** Per track, per stored frame: the box of its pose. */
  private frameBoxes: Box3[][] = [];
  private arrangement: Layout = layoutTracks([], 'overlay');
  private mode: LayoutMode = 'overlay';
  private selected: number | null = null;
  private t = 0;
  private draws: FigureDraw[] = [];
  /** Placement index of each figure in the last draw, in draw order. */
  private drawn: number[] = [];
  private labels: LabelSlot[] = [];
  private readonly scratch = new Vector3();
  /** Reports each label's size after layout; a change draws again, so a label placed by a stale size is placed anew. */
  private readonly labelSizes = new ResizeObserver((entries) => {
    let changed = false;
    for (const e of entries) {
      const slot = this.labels.find((l) => l.element === e.target);
      const box = e.borderBoxSize[0];
      if (!slot || !box || (slot.size.width === box.inlineSize && slot.size.height === box.blockSize)) continue;
      slot.size = { width: box.inlineSize, height: box.blockSize };
      changed = true;
    }
    if (changed && this.labels.some((l) => l.object.visible && this.tracks[l.track]?.role === 'truth')) this.stage.invalidate();
  });
  /** Per root path (placement order): whose it is, for its opacity under a selection. */
  private pathOwners: { sample?: number; role: Track['role'] }[] = [];
  private pick: ((sample: number | null) => void) | null = null;
  private headJoint = 0;
  /** Some track is not a history: an ended history gives way to it. */
  private followed = false;

  /** Throws WebGLUnavailableError when WebGL 2 is missing. */
  constructor(container: HTMLElement, onContextLost?: (lost: boolean) => void) {
    this.stage = new Stage(container, onContextLost);
    this.stage.scene.add(this.paths.object, this.figuresMesh.group, this.labelGroup);
    this.stage.beforeLabels = () => this.placeTruthLabels();
    this.listenForPicks();
  }

  get layout(): LayoutMode { return this.mode; }

  setTracks(tracks: readonly Track[], skeleton: Skeleton, options: SetTracksOptions = {}): void {
    for (const tr of tracks) {
      if (tr.joints !== skeleton.joints.length || tr.positions.length < tr.frames * tr.joints * 3) {
        throw new Error(`track ${tr.id}: ${tr.frames} frames x ${tr.joints} joints do not fit ${tr.positions.length} values / ${skeleton.joints.length} joints`);
      }
    }
    // K = 50 makes this a heavy call: its first draw waits a frame (make bench's frame gaps)
    this.stage.invalidateAfterNextFrame();
    this.given = tracks;
    if (this.skeleton !== skeleton) {
      this.skeleton = skeleton;
      this.figuresMesh.setSkeleton(skeleton);
      this.headJoint = Math.max(0, skeleton.joints.indexOf('head'));
    }
    this.givenBoxes = tracks.map(poseBoxes);
    // compare mode: each method's row against its own truth, so the toggle marks one sample per row
    this.bests = bestPerRow(tracks);
    this.keepShown();
    if (this.selected !== null && !tracks.some((tr) => tr.sample === this.selected)) this.selected = null;
    this.arrange(!options.keepView);
    for (const l of this.trackListeners) l();
  }

  clear(): void {
    this.given = [];
    this.givenBoxes = [];
    this.bests = [];
    this.keepShown();
    this.arrange(false);
    for (const l of this.trackListeners) l();
  }

  get camera(): CameraPreset { return this.preset; }

  setCamera(preset: CameraPreset): void {
    if (!CAMERA_PRESETS.includes(preset)) throw new Error(`unknown camera preset '${preset}' (${CAMERA_PRESETS.join(', ')})`);
    this.preset = preset;
    this.refit();
  }

  setBestShown(on: boolean): void {
    if (on === this.bestShown) return;
    this.bestShown = on;
    if (this.preset === 'follow') this.refit();
    this.redraw();
  }

  setTruthShown(on: boolean): void {
    if (on === this.truthShown) return;
    this.truthShown = on;
    this.keepShown();
    // side by side the truth has a cell of its own: the grid changes, so it is framed again
    this.arrange(this.mode === 'side' || this.preset === 'follow');
    for (const l of this.trackListeners) l();
  }

  best(): BestSample | null { return this.bests.find((b) => b.group === 0) ?? null; }

  bestRows(): readonly BestSample[] { return this.bests; }

  /** The track is a highlighted closest sample of its row. */
  private isBest(track: Track | undefined): boolean {
    return this.bestShown && track?.role === 'prediction' && this.bests.some((b) => b.group === (track.group ?? 0) && b.sample === track.sample);
  }

  /** The eye is led to the track: it is the selected sample, or else a highlighted closest one. */
  private focused(track: Track | undefined): boolean {
    if (this.selected !== null) return track?.role === 'prediction' && track.sample === this.selected;
    return this.isBest(track);
  }

  /** Some figure is focused (a selection, or the highlight with a closest sample): the others are muted. */
  private anyFocus(): boolean {
    return this.selected !== null || (this.bestShown && this.bests.length > 0);
  }

  viewDirection(): [number, number, number] | null {
    const d = this.stage.camera.position.clone().sub(this.stage.controls.target).normalize();
    return [d.x, d.y, d.z];
  }

  onTracks(handler: () => void): void { this.trackListeners.push(handler); }

  shownTracks(): readonly Pick<Track, 'role' | 'sample' | 'group'>[] { return this.tracks; }

  /** The tracks drawn: those given, less the ground truth when it is hidden. */
  private keepShown(): void {
    const keep = this.given.map((tr) => this.truthShown || tr.role !== 'truth');
    this.tracks = this.given.filter((_, i) => keep[i]);
    this.frameBoxes = this.givenBoxes.filter((_, i) => keep[i]);
    this.followed = this.tracks.some((tr) => tr.role !== 'history');
  }

  /** The sample the eye is led to: the selected one, else the highlighted best. */
  private focus(): number | null {
    if (this.selected !== null) return this.selected;
    return this.bestShown ? this.best()?.sample ?? null : null;
  }

  /** Frame the figures again from the current preset (after a preset or a followed figure changes). */
  private refit(): void {
    this.stage.fit(this.plan(this.heading()), this.t);
  }

  setLayout(mode: LayoutMode): void {
    if (mode === this.mode) return;
    this.mode = mode;
    this.arrange(true);
  }

  setFrame(t: number): void {
    this.t = t;
    this.stage.follow(t);
    this.redraw();
  }

  setSelected(sample: number | null): void {
    this.selected = sample;
    if (this.preset === 'follow') this.refit();
    this.redraw();
  }

  onPick(handler: (sample: number | null) => void): void { this.pick = handler; }

  resetView(): void { this.stage.resetView(); }

  dispose(): void {
    this.clearLabels();
    this.paths.dispose();
    this.figuresMesh.dispose();
    this.stage.dispose();
  }

  figures(): FigureInfo[] {
    const camera = this.stage.camera;
    camera.updateMatrixWorld();
    const size = this.stage.size;
    return this.drawn.map((pi, i) => {
      const p = this.arrangement.placements[pi];
      const track = this.tracks[p.track];
      const box = this.screenBox(pi, size);
      const slot = this.labels.find((l) => l.placements.includes(pi));
      const status = figureStatus(this.tracks[slot?.track ?? p.track], this.t);
      return {
        track: track.id, role: track.role, sample: track.sample, cell: p.cell, shared: p.shared,
        label: slot?.element.textContent ?? '', colour: this.figuresMesh.identityHex(i), box,
        action: status.action, stopped: status.stopped,
        best: this.isBest(track),
        group: track.group,
      };
    });
  }

  /** The projected box of placement `pi`'s joints as last drawn, CSS px from the canvas's top-left
   *  (the camera's matrices must be current). */
  private screenBox(pi: number, { width, height }: { width: number; height: number }): Rect {
    const p = this.arrangement.placements[pi];
    const joints = this.tracks[p.track].joints;
    const pose = this.draws[pi].pose;
    const v = this.scratch;
    const box = { left: Infinity, top: Infinity, right: -Infinity, bottom: -Infinity };
    for (let j = 0; j < joints; j++) {
      v.set(pose[j * 3] + p.x, pose[j * 3 + 1], pose[j * 3 + 2] + p.z).project(this.stage.camera);
      const x = ((v.x + 1) / 2) * width;
      const y = ((1 - v.y) / 2) * height;
      box.left = Math.min(box.left, x); box.right = Math.max(box.right, x);
      box.top = Math.min(box.top, y); box.bottom = Math.max(box.bottom, y);
    }
    return box;
  }

  /**
   * The ground truth's label covers no other figure and no other label (label-place.ts): where its own
   * spot over the head is taken, it moves on screen to the nearest free spot. Run on every render,
   * from where the camera is then; the other labels stay over their heads.
   */
  private placeTruthLabels(): void {
    const truths = this.labels.filter((l) => l.object.visible && this.tracks[l.track]?.role === 'truth');
    if (!truths.length) return;
    const camera = this.stage.camera;
    camera.updateMatrixWorld();
    const { width, height } = this.stage.drawnSize;
    const v = this.scratch;
    const onScreen = (at: Vector3) => {
      v.copy(at).project(camera);
      return { x: ((v.x + 1) / 2) * width, y: ((1 - v.y) / 2) * height, z: v.z, shown: v.z >= -1 && v.z <= 1 };
    };
    const obstacles: Rect[] = this.drawn.map((pi) => this.screenBox(pi, { width, height }));
    for (const l of this.labels) {
      if (!l.object.visible || truths.includes(l)) continue;
      const s = onScreen(l.home);
      if (s.shown) obstacles.push(labelRect(s, l.size));
    }
    const bounds = { left: 0, top: 0, right: width, bottom: height };
    for (const l of truths) {
      l.object.position.copy(l.home);
      const s = onScreen(l.home);
      if (!s.shown) continue; // behind the camera: CSS2DRenderer hides it
      const size = l.size;
      const at = placeLabel(s, size, obstacles, bounds);
      // back into the world at the head's depth, where CSS2DRenderer projects it to that spot
      if (at.x !== s.x || at.y !== s.y) l.object.position.set((at.x / width) * 2 - 1, 1 - (at.y / height) * 2, s.z).unproject(camera);
      obstacles.push(labelRect(at, size));
    }
  }

  /** Whether placement `p` shows a figure at timeline position `t`. */
  private visible(pi: number, t: number): boolean {
    const p = this.arrangement.placements[pi];
    const track = this.tracks[p.track];
    const state = trackPose(track, t).state;
    if (state === 'pending') return false;
    // A history gives way to what follows it (its cell's own track, or the futures overlaid) once it ends.
    if (track.role === 'history' && state === 'ended' && this.followed) return false;
    return true;
  }

  /** The figures' heading: the history's (or else the first track's) facing where the futures start. */
  private heading(): number {
    const ref = this.tracks.find((tr) => tr.role === 'history') ?? this.tracks.find((tr) => tr.role !== 'prediction') ?? this.tracks[0];
    if (!ref || !this.skeleton) return 0;
    return facingAngle(ref.positions, ref.role === 'history' ? ref.frames - 1 : 0, this.skeleton);
  }

  /** The room the figures need at one moment, across and along the heading (side by side's cell size). */
  private spread(heading: number): { width: number; depth: number } {
    const c = Math.cos(heading);
    const s = Math.sin(heading);
    const length = timelineLength(this.tracks);
    const others = this.tracks.some((tr) => tr.role !== 'history');
    let width = 0;
    let depth = 0;
    for (let f = 0; f < length; f++) {
      let u0 = Infinity; let u1 = -Infinity; let v0 = Infinity; let v1 = -Infinity;
      this.tracks.forEach((track, i) => {
        const pose = trackPose(track, f);
        if (pose.state === 'pending') return;
        if (track.role === 'history' && pose.state === 'ended' && others) return;
        const b = this.frameBoxes[i][pose.a];
        for (const x of [b.min.x, b.max.x]) {
          for (const z of [b.min.z, b.max.z]) {
            const u = c * x - s * z;
            const w = s * x + c * z;
            u0 = Math.min(u0, u); u1 = Math.max(u1, u); v0 = Math.min(v0, w); v1 = Math.max(v1, w);
          }
        }
      });
      if (u1 >= u0) { width = Math.max(width, u1 - u0); depth = Math.max(depth, v1 - v0); }
    }
    return {
      width: Math.min(MAX_CELL_WIDTH, Math.max(MIN_CELL_WIDTH, width + CELL_GAP)),
      depth: Math.min(MAX_CELL_DEPTH, Math.max(MIN_CELL_DEPTH, depth + CELL_GAP)),
    };
  }

  private arrange(reframe: boolean): void {
    const heading = this.heading();
    const { width, height } = this.stage.size;
    // compare mode overlaid puts each method in a cell of its own, as wide as its futures need
    const grouped = this.tracks.some((tr) => tr.group !== undefined);
    const cell = this.mode === 'side' || grouped ? this.spread(heading) : null;
    this.arrangement = layoutTracks(this.tracks, this.mode, {
      heading, spacing: MIN_CELL_WIDTH, rowSpacing: MIN_CELL_DEPTH,
      cellWidth: cell?.width, cellDepth: cell?.depth, aspect: width / height,
    });
    this.draws = this.arrangement.placements.map((p) => ({
      pose: new Float32Array(this.tracks[p.track].joints * 3), x: p.x, z: p.z, tint: { role: this.tracks[p.track].role },
    }));
    this.decorate();
    const plan = this.plan(heading);
    const all = new Box3();
    for (const b of plan.boxes) all.union(b);
    if (all.isEmpty()) all.set(new Vector3(-0.5, 0, -0.5), new Vector3(0.5, 1.8, 0.5));
    const centre = all.getCenter(new Vector3());
    this.stage.setGrid(Math.max(6, 2 * Math.max(all.max.x - centre.x, all.max.z - centre.z) + 3), centre);
    if (reframe) this.stage.fit(plan, this.t);
    else this.stage.follow(this.t);
    this.redraw();
  }

  /** Per timeline frame: the box of every figure shown then, and a smoothed point to look at. */
  private plan(heading: number): FramePlan {
    const length = Math.max(1, timelineLength(this.tracks));
    const labelRoom = Math.max(0, ...this.labels.map((l) => l.lift)) + 0.12;
    const boxes: Box3[] = [];
    const corners: Float32Array[] = [];
    const placements = this.arrangement.placements;
    const only = this.preset === 'follow' ? this.followedPlacements() : null;
    for (let f = 0; f < length; f++) {
      // plain numbers, not a Box3 per figure and frame: K = 50 runs this for 52 figures x 150 frames
      let x0 = Infinity; let y0 = Infinity; let z0 = Infinity; let x1 = -Infinity; let y1 = -Infinity; let z1 = -Infinity;
      const shown: number[] = [];
      for (let pi = 0; pi < placements.length; pi++) {
        if (!this.visible(pi, f) || (only && !only.has(pi))) continue;
        const p = placements[pi];
        const b = this.frameBoxes[p.track][trackPose(this.tracks[p.track], f).a];
        x0 = Math.min(x0, b.min.x + p.x); y0 = Math.min(y0, b.min.y); z0 = Math.min(z0, b.min.z + p.z);
        x1 = Math.max(x1, b.max.x + p.x); y1 = Math.max(y1, b.max.y); z1 = Math.max(z1, b.max.z + p.z);
        shown.push(pi);
      }
      // each figure's own box (floor to label), for a fit as tight as the figures (stage.ts FramePlan)
      const pts = new Float32Array(shown.length * 24);
      shown.forEach((pi, n) => {
        const p = placements[pi];
        const b = this.frameBoxes[p.track][trackPose(this.tracks[p.track], f).a];
        const lo = Math.min(b.min.y, 0);
        const hi = Math.max(b.max.y, 0) + labelRoom;
        for (let i = 0; i < 8; i++) {
          pts[n * 24 + i * 3] = (i & 1 ? b.max.x : b.min.x) + p.x;
          pts[n * 24 + i * 3 + 1] = i & 2 ? hi : lo;
          pts[n * 24 + i * 3 + 2] = (i & 4 ? b.max.z : b.min.z) + p.z;
        }
      });
      corners.push(pts);
      const box = new Box3();
      if (x0 <= x1) {
        // keep the floor in view, and the labels over the heads
        box.min.set(x0, Math.min(y0, 0), z0);
        box.max.set(x1, Math.max(y1, 0) + labelRoom, z1);
      }
      boxes.push(box);
    }
    if (boxes.every((b) => b.isEmpty())) boxes[0] = new Box3(new Vector3(-0.5, 0, -0.5), new Vector3(0.5, 1.8, 0.5));
    const raw = boxes.map((b) => (b.isEmpty() ? null : b.getCenter(new Vector3())));
    const smoothing = only ? FOLLOW_ONE_SMOOTHING : FOLLOW_SMOOTHING;
    const centres = raw.map((_, f) => {
      const sum = new Vector3();
      let n = 0;
      for (let g = Math.max(0, f - smoothing); g <= Math.min(raw.length - 1, f + smoothing); g++) {
        if (raw[g]) { sum.add(raw[g]!); n++; }
      }
      return n ? sum.divideScalar(n) : new Vector3(0, 0.9, 0);
    });
    const view = this.preset === 'auto' ? (this.mode === 'side' && this.arrangement.cells > 1 && !only ? SIDE_VIEW : OVERLAY_VIEW)
      : this.preset === 'follow' ? OVERLAY_VIEW : PRESET_VIEWS[this.preset];
    const direction = view.clone().applyAxisAngle(UP, heading);
    return { direction, boxes, centres, corners };
  }

  /** The placements the 'follow' preset frames: the followed sample's figure (the selected one, else
   *  the highlighted best, else the first), with the history it continues in its cell; null (frame
   *  every figure) when there is no sample. */
  private followedPlacements(): Set<number> | null {
    const samples = this.tracks.filter((tr) => tr.role === 'prediction' && tr.sample !== undefined).map((tr) => tr.sample!);
    if (!samples.length) return null;
    const want = this.focus();
    const sample = want !== null && samples.includes(want) ? want : Math.min(...samples);
    const placements = this.arrangement.placements;
    const own = placements.findIndex((p) => !p.shared && this.tracks[p.track].sample === sample && this.tracks[p.track].role === 'prediction');
    if (own < 0) return null;
    const cell = placements[own].cell;
    const out = new Set([own]);
    placements.forEach((p, pi) => {
      if (this.tracks[p.track].role === 'history' && p.cell === cell) out.add(pi);
    });
    return out;
  }

  private clearLabels(): void {
    this.labelSizes.disconnect();
    for (const l of this.labels) l.element.remove();
    this.labelGroup.clear();
    this.labels = [];
  }

  /** Root paths (one per figure placed, history copies included) and labels (one per figure, or per cell). */
  private decorate(): void {
    this.clearLabels();
    this.pathOwners = [];
    this.paths.set(this.arrangement.placements.map((p) => {
      const track = this.tracks[p.track];
      const points = new Float32Array(track.frames * 3);
      for (let f = 0; f < track.frames; f++) {
        const at = f * track.joints * 3;
        points[f * 3] = track.positions[at] + p.x;
        points[f * 3 + 2] = track.positions[at + 2] + p.z;
      }
      this.pathOwners.push({ sample: track.sample, role: track.role });
      return { points, colour: identityColour(track.role, track.sample ?? 0) };
    }));
    // Side by side: one label per cell, over whichever figure the cell shows (its history copy first,
    // then its own track). Overlaid: one label per track.
    const groups = new Map<number, number[]>();
    this.arrangement.placements.forEach((p, pi) => {
      const key = this.mode === 'side' && this.arrangement.cells > 1 ? p.cell : p.track;
      groups.set(key, [...(groups.get(key) ?? []), pi]);
    });
    const ranks = new Map<number, number>(); // overlaid labels stack per place (per method in compare mode)
    for (const placements of groups.values()) {
      const owner = this.arrangement.placements[placements.find((pi) => !this.arrangement.placements[pi].shared) ?? placements[0]];
      const track = this.tracks[owner.track];
      const rank = ranks.get(owner.cell) ?? 0;
      const element = document.createElement('div');
      element.className = `figure-label figure-label-${track.role}`;
      // the name, then what changes with time (each part starts " · " so the text reads as one line)
      const part = (cls: string) => { const e = document.createElement('span'); e.className = cls; e.hidden = true; return e; };
      const action = part('figure-action');
      const stopped = part('figure-badge figure-stopped');
      const best = part('figure-badge figure-best');
      element.append(labelText(track), action, stopped, best);
      element.style.setProperty('--figure-colour', identityCss(track.role, track.sample ?? 0));
      if (track.sample !== undefined) {
        element.dataset.sample = String(track.sample);
        element.addEventListener('click', (e) => { e.stopPropagation(); this.pick?.(track.sample ?? null); });
      }
      element.dataset.role = track.role;
      element.style.display = 'none'; // until the stage's next draw places it
      const object = new CSS2DObject(element);
      object.center.set(0.5, 1);
      this.labelGroup.add(object);
      // Overlaid, labels stack above the shared place (the history, whose figure gives way to the
      // futures, shares the first step with the ground truth).
      const lift = LABEL_LIFT + (this.mode === 'overlay' || this.arrangement.cells <= 1 ? LABEL_STEP * rank : 0);
      if (track.role !== 'history') ranks.set(owner.cell, rank + 1);
      this.labels.push({ object, element, placements, sample: track.sample, lift, track: owner.track, action, stopped, best, home: new Vector3(), size: { width: 0, height: 0 } });
      this.labelSizes.observe(element);
    }
  }

  private redraw(): void {
    const visible: FigureDraw[] = [];
    this.drawn = [];
    const shown = new Set<number>();
    this.arrangement.placements.forEach((p, i) => {
      if (!this.visible(i, this.t)) return;
      const track = this.tracks[p.track];
      const pose = trackPose(track, this.t);
      const draw = this.draws[i];
      poseInto(track, pose, draw.pose);
      const isPrediction = track.role === 'prediction';
      const selected = this.focused(track);
      draw.tint = {
        role: track.role, sample: track.sample, selected,
        muted: isPrediction && this.anyFocus() && !selected, ended: pose.state === 'ended',
      };
      visible.push(draw);
      this.drawn.push(i);
      shown.add(i);
    });
    this.figuresMesh.draw(visible);
    const anyFocus = this.anyFocus();
    for (const l of this.labels) {
      const pi = l.placements.find((i) => shown.has(i));
      l.object.visible = pi !== undefined;
      l.element.classList.toggle('figure-label-selected', this.selected !== null && l.sample === this.selected);
      l.element.classList.toggle('figure-label-muted', anyFocus && l.sample !== undefined && !this.focused(this.tracks[l.track]));
      l.element.classList.toggle('figure-label-best', this.isBest(this.tracks[l.track]));
      if (pi === undefined) continue;
      this.labelStatus(l);
      const p = this.arrangement.placements[pi];
      const pose = this.draws[pi].pose;
      const j = this.headJoint * 3;
      l.home.set(pose[j] + p.x, pose[j + 1] + l.lift, pose[j + 2] + p.z);
      l.object.position.copy(l.home);
    }
    this.paths.setOpacity((i) => {
      const { sample, role } = this.pathOwners[i];
      return this.selected === null || role !== 'prediction' ? 0.5 : sample === this.selected ? 0.9 : 0.15;
    });
    this.stage.invalidate();
  }

  /** A label's action and badges at the current frame; the DOM is touched only when they change
   *  (labels are redrawn every frame). */
  private labelStatus(l: LabelSlot): void {
    const track = this.tracks[l.track];
    if (!track || track.role !== 'prediction') return;
    const { action, stopped } = figureStatus(track, this.t);
    const isBest = this.isBest(track);
    // a hidden part has no text either: the label's text is what it shows (FigureInfo.label); a badge
    // is a pill after its " · "
    const set = (e: HTMLElement, text: string, pill: boolean) => {
      if (e.textContent === (text ? ` · ${text}` : '')) return;
      if (!text) e.replaceChildren();
      else if (pill) { const b = document.createElement('b'); b.textContent = text; e.replaceChildren(' · ', b); }
      else e.textContent = ` · ${text}`;
      e.hidden = text === '';
    };
    set(l.action, action ? action.replace(/_/g, ' ') : '', false);
    set(l.stopped, stopped ? 'stopped' : '', true);
    set(l.best, isBest ? 'closest to truth' : '', true);
    if ((l.element.dataset.action ?? null) !== action) {
      if (action) l.element.dataset.action = action; else delete l.element.dataset.action;
    }
  }

  /** A click (not a drag) on the canvas picks the figure under it: the smallest box that holds the point. */
  private listenForPicks(): void {
    const canvas = this.stage.renderer.domElement;
    let down: { x: number; y: number; at: number } | null = null;
    canvas.addEventListener('pointerdown', (e) => { down = { x: e.clientX, y: e.clientY, at: performance.now() }; });
    canvas.addEventListener('pointerup', (e) => {
      if (!down || !this.pick) return;
      const moved = Math.hypot(e.clientX - down.x, e.clientY - down.y);
      const quick = performance.now() - down.at < 600;
      down = null;
      if (moved > 5 || !quick) return;
      const r = canvas.getBoundingClientRect();
      const x = e.clientX - r.left;
      const y = e.clientY - r.top;
      const pad = 8;
      let best: FigureInfo | null = null;
      let bestArea = Infinity;
      for (const f of this.figures()) {
        const { left, top, right, bottom } = f.box;
        if (x < left - pad || x > right + pad || y < top - pad || y > bottom + pad) continue;
        const area = (right - left) * (bottom - top);
        if (area < bestArea) { best = f; bestArea = area; }
      }
      this.pick(best?.role === 'prediction' ? best.sample ?? null : null);
    });
  }
}

function labelText(track: Track): string {
  const own = track.role === 'prediction' ? `#${(track.sample ?? 0) + 1}${track.cut ? ' · cut' : ''}`
    : track.role === 'truth' ? 'ground truth' : track.role === 'history' ? 'history' : track.label ?? 'clip';
  return track.groupLabel ? `${track.groupLabel} ${own}` : own;
}

/** Each stored frame's box of joint positions. */
function poseBoxes(track: Track): Box3[] {
  const p = track.positions;
  const out: Box3[] = [];
  const v = new Vector3();
  const stride = track.joints * 3;
  for (let f = 0; f < track.frames; f++) {
    const box = new Box3();
    for (let i = f * stride; i < (f + 1) * stride; i += 3) box.expandByPoint(v.set(p[i], p[i + 1], p[i + 2]));
    out.push(box);
  }
  return out;
}
