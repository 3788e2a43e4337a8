// Tracks on the shared timeline: which pose of a track shows at a timeline position.

export type TrackRole = 'clip' | 'history' | 'prediction' | 'truth';

export interface Track {
  id: string;
  role: TrackRole;
  /** [frames * joints * 3] metres, y-up. */
  positions: Float32Array;
  frames: number;
  joints: number;
  /** Timeline frame at which this track's frame 0 shows. */
  startFrame: number;
  /** Sample index of a prediction (0-based); drives its tint. */
  sample?: number;
  label?: string;
  /** A sample cut at its last good frame (Prediction.samples[].cut): its label says so. */
  cut?: boolean;
  /** A prediction's actions in order (track frames), when it runs a sequence: its label names the current one. */
  segments?: TrackSegment[];
  /** The sample stopped by its own rule (its last action's stop, Eq. 8) at its last frame: a badge says so. */
  stopped?: boolean;
  /** Compare mode (ui/compare.ts): the method's row on stage (0 first), and the method's name its labels lead with. */
  group?: number;
  groupLabel?: string;
}

export interface TrackSegment { start: number; length: number; action?: string; stopped?: boolean }

/** What a prediction sample's info gives its track: its segments and whether its last one stopped.
 *  A cut sample did not stop, it was cut (its label says that). */
export function sampleTrackInfo(s: { stopped: boolean; segments: readonly TrackSegment[]; cut?: unknown; length?: number } | undefined): Pick<Track, 'segments' | 'stopped'> {
  if (!s) return {};
  const last = s.segments[s.segments.length - 1];
  return {
    segments: s.segments.map((g) => ({ start: g.start, length: g.length, action: g.action, stopped: g.stopped })),
    stopped: !s.cut && (last?.stopped ?? s.stopped),
  };
}

/** What a figure's label adds at timeline position `t`: the action it is doing in a sequence of two or
 *  more (null otherwise, and before it starts), and "stopped" once its last frame is reached. */
export function figureStatus(track: Pick<Track, 'startFrame' | 'frames' | 'segments' | 'stopped'>, t: number): { action: string | null; stopped: boolean } {
  const local = Math.floor(t - track.startFrame + 1e-9);
  const stopped = Boolean(track.stopped) && track.frames > 0 && local >= track.frames - 1;
  const segs = track.segments;
  if (local < 0 || !segs || segs.length < 2) return { action: null, stopped };
  // no arrays made here: every label asks every frame (K = 50)
  let named = 0;
  let action: string | null = null;
  for (const g of segs) {
    if (!g.action) continue;
    named += 1;
    if (g.start <= local) action = g.action; // the last one begun
  }
  return { action: named >= 2 ? action : null, stopped };
}

/** pending: before the track starts (hidden); playing; ended: holds its last pose. */
export type TrackState = 'pending' | 'playing' | 'ended';

export interface TrackPose {
  state: TrackState;
  /** The two stored frames to blend and the weight of the second. */
  a: number;
  b: number;
  w: number;
}

/** Frames the shared timeline needs so that every track plays to its end. */
export function timelineLength(tracks: readonly Pick<Track, 'frames' | 'startFrame'>[]): number {
  let n = 0;
  for (const t of tracks) n = Math.max(n, t.startFrame + t.frames);
  return n;
}

/** Pose of `track` at fractional timeline position `t`; blends neighbouring frames so slow playback stays smooth. */
export function trackPose(track: Pick<Track, 'frames' | 'startFrame'>, t: number): TrackPose {
  const local = t - track.startFrame;
  const last = track.frames - 1;
  if (local < 0 || track.frames <= 0) return { state: 'pending', a: 0, b: 0, w: 0 };
  if (local >= last) {
    // The final frame is a pose too, shown for its full frame interval before the track counts as ended.
    return { state: local < track.frames ? 'playing' : 'ended', a: last, b: last, w: 0 };
  }
  const a = Math.floor(local);
  return { state: 'playing', a, b: a + 1, w: local - a };
}

/** Write the blended pose into `out` ([joints * 3]). */
export function poseInto(track: Pick<Track, 'positions' | 'joints'>, pose: TrackPose, out: Float32Array): Float32Array {
  const n = track.joints * 3;
  const pa = pose.a * n;
  const pb = pose.b * n;
  const p = track.positions;
  if (pose.w === 0) {
    for (let i = 0; i < n; i++) out[i] = p[pa + i];
  } else {
    const w = pose.w;
    for (let i = 0; i < n; i++) out[i] = p[pa + i] + (p[pb + i] - p[pa + i]) * w;
  }
  return out;
}
