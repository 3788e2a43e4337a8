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
