// A clip in memory: flat float32 positions [frame, joint, 3] plus what the contract says of it.
import type { ClipDoc, ClipIndexEntry, Range, Role, Skeleton } from '../contract/types';
import { fetchContract } from '../contract/validate';

export interface Motion {
  name: string;
  action: string;
  fps: number;
  skeleton: Skeleton;
  frames: number;
  joints: number;
  /** [frames * joints * 3] metres, y-up. */
  positions: Float32Array;
  loops: boolean;
  cycleFrames?: number;
  role: Role;
  train: Range[];
  test: Range[];
  license?: string;
  /** Set for motion that came from a user's file rather than the site's data (see motion/bvh.ts). */
  origin?: { kind: 'dropped-file'; file: string };
}

export function motionFromDoc(doc: ClipDoc): Motion {
  const frames = doc.positions.length;
  const joints = doc.skeleton.joints.length;
  const positions = new Float32Array(frames * joints * 3);
  let i = 0;
  for (const frame of doc.positions) for (const p of frame) { positions[i++] = p[0]; positions[i++] = p[1]; positions[i++] = p[2]; }
  return {
    name: doc.name, action: doc.action, fps: doc.fps, skeleton: doc.skeleton, frames, joints, positions,
    loops: doc.loops, cycleFrames: doc.cycle_frames, role: doc.split.role, train: doc.split.train,
    test: doc.split.test, license: doc.source?.license,
  };
}

export async function loadClip(baseUrl: string, entry: ClipIndexEntry, fetcher?: typeof fetch): Promise<Motion> {
  return motionFromDoc(await fetchContract(`${baseUrl}clips/${entry.file}`, 'clip', fetcher));
}

/** Frames [start, start + count) of a motion as a new flat array. */
export function window(m: Motion, start: number, count: number): Float32Array {
  const stride = m.joints * 3;
  return m.positions.slice(start * stride, (start + count) * stride);
}
