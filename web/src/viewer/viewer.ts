// The skeleton viewer: tracks on a shared timeline, laid out overlaid or side by side.
import { Box3, Vector3 } from 'three';
import type { Skeleton } from '../contract/types';
import { facingAngle } from '../motion/facing';
import { SkeletonFigures, type FigureDraw } from './figures';
import { layoutTracks, type Layout, type LayoutMode } from './layout';
import { Stage } from './stage';
import { poseInto, trackPose, type Track } from './tracks';

export interface SetTracksOptions {
  /** Keep the camera where it is (e.g. new samples for the same window). */
  keepView?: boolean;
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
  resetView(): void;
  dispose(): void;
}

// Camera directions: a three-quarter front view of one figure; a raised front view of a grid.
const OVERLAY_VIEW = new Vector3(0.65, 0.35, 1);
const SIDE_VIEW = new Vector3(0.25, 0.95, 1);
const UP = new Vector3(0, 1, 0);

export class Viewer implements SkeletonView {
  private readonly stage: Stage;
  private readonly figures = new SkeletonFigures();
  private tracks: readonly Track[] = [];
  private skeleton: Skeleton | null = null;
  private bounds: Box3[] = [];
  private arrangement: Layout = layoutTracks([], 'overlay');
  private mode: LayoutMode = 'overlay';
  private selected: number | null = null;
  private t = 0;
  private draws: FigureDraw[] = [];

  /** Throws WebGLUnavailableError when WebGL 2 is missing. */
  constructor(container: HTMLElement, onContextLost?: (lost: boolean) => void) {
    this.stage = new Stage(container, onContextLost);
    this.stage.scene.add(this.figures.group);
  }

  get layout(): LayoutMode { return this.mode; }

  setTracks(tracks: readonly Track[], skeleton: Skeleton, options: SetTracksOptions = {}): void {
    for (const tr of tracks) {
      if (tr.joints !== skeleton.joints.length || tr.positions.length < tr.frames * tr.joints * 3) {
        throw new Error(`track ${tr.id}: ${tr.frames} frames x ${tr.joints} joints do not fit ${tr.positions.length} values / ${skeleton.joints.length} joints`);
      }
    }
    this.tracks = tracks;
    if (this.skeleton !== skeleton) { this.skeleton = skeleton; this.figures.setSkeleton(skeleton); }
    this.bounds = tracks.map(trackBounds);
    this.arrange(!options.keepView);
  }

  clear(): void {
    this.tracks = [];
    this.bounds = [];
    this.arrange(false);
  }

  setLayout(mode: LayoutMode): void {
    if (mode === this.mode) return;
    this.mode = mode;
    this.arrange(true);
  }

  setFrame(t: number): void {
    this.t = t;
    this.redraw();
  }

  setSelected(sample: number | null): void {
    this.selected = sample;
    this.redraw();
  }

  resetView(): void { this.stage.resetView(); }

  dispose(): void {
    this.figures.dispose();
    this.stage.dispose();
  }

  private arrange(reframe: boolean): void {
    this.arrangement = layoutTracks(this.tracks, this.mode);
    this.draws = this.arrangement.placements.map((p) => ({
      pose: new Float32Array(this.tracks[p.track].joints * 3), x: p.x, z: p.z, tint: { role: this.tracks[p.track].role },
    }));
    const box = new Box3();
    for (const p of this.arrangement.placements) {
      const b = this.bounds[p.track];
      if (!b.isEmpty()) box.union(b.clone().translate(new Vector3(p.x, 0, p.z)));
    }
    if (box.isEmpty()) box.set(new Vector3(-0.5, 0, -0.5), new Vector3(0.5, 1.8, 0.5));
    box.expandByPoint(new Vector3(box.min.x, 0, box.min.z)); // keep the floor in view
    const reach = Math.max(-box.min.x, box.max.x, -box.min.z, box.max.z);
    this.stage.setGridSize(Math.max(6, 2 * reach + 2)); // the grid is centred on the origin
    if (reframe) this.stage.fit(box, this.viewDirection());
    this.redraw();
  }

  /** Overlaid: face the figure (its facing at its first frame); side by side: face the grid. */
  private viewDirection(): Vector3 {
    if (this.mode === 'side' && this.arrangement.cells > 1) return SIDE_VIEW.clone();
    const ref = this.tracks.find((tr) => tr.role !== 'prediction') ?? this.tracks[0];
    if (!ref || !this.skeleton) return OVERLAY_VIEW.clone();
    return OVERLAY_VIEW.clone().applyAxisAngle(UP, facingAngle(ref.positions, 0, this.skeleton));
  }

  private redraw(): void {
    const visible: FigureDraw[] = [];
    this.arrangement.placements.forEach((p, i) => {
      const track = this.tracks[p.track];
      const pose = trackPose(track, this.t);
      if (pose.state === 'pending') return;
      // A shared history copy gives way to its cell's own track once it ends.
      if (p.shared && pose.state === 'ended') return;
      const draw = this.draws[i];
      poseInto(track, pose, draw.pose);
      const isPrediction = track.role === 'prediction';
      const selected = isPrediction && this.selected !== null && track.sample === this.selected;
      draw.tint = {
        role: track.role, sample: track.sample, selected,
        muted: isPrediction && this.selected !== null && !selected, ended: pose.state === 'ended',
      };
      visible.push(draw);
    });
    this.figures.draw(visible);
    this.stage.invalidate();
  }
}

function trackBounds(track: Track): Box3 {
  const box = new Box3();
  const p = track.positions;
  const v = new Vector3();
  for (let i = 0; i < track.frames * track.joints * 3; i += 3) box.expandByPoint(v.set(p[i], p[i + 1], p[i + 2]));
  return box;
}
