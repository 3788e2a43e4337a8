// Guards that hold whatever a model does, twin of export/sample/guard.py: every future frame is
// checked against the history it continues (finite values, bones within BONE_RATIO of their length in
// the history, joints within reach of the root, a root that neither flies off nor leaves the floor far
// behind); a sample breaking a bound is cut at its last good frame with the reason "cut: out of bounds",
// separate from Eq. 8's "stopped".
import type { Skeleton } from '../contract/types';
import { boneLengths, meanLengths } from '../motion/bones';
import type { Prediction } from './types';

export const BONE_RATIO = 1.5;
export const REACH_RATIO = 1.5;
export const MIN_REACH = 1.5;
export const MAX_ROOT_STEP = 0.5;
export const MAX_ROOT_HEIGHT = 3.0;
export const CUT_REASON = 'cut: out of bounds';

/** The first future frame [frames, J, 3] (world) that breaks a bound, and which; null when none does. */
export function firstBadFrame(future: ArrayLike<number>, frames: number, history: ArrayLike<number>, historyFrames: number,
  skeleton: Skeleton): { frame: number; detail: string } | null {
  const J = skeleton.joints.length;
  const s = J * 3;
  const rest = meanLengths(history, historyFrames, skeleton);
  let reach = 0;
  for (let f = 0; f < historyFrames; f++) {
    for (let j = 0; j < J; j++) {
      reach = Math.max(reach, Math.hypot(history[f * s + j * 3] - history[f * s], history[f * s + j * 3 + 1] - history[f * s + 1],
        history[f * s + j * 3 + 2] - history[f * s + 2]));
    }
  }
  reach = Math.max(REACH_RATIO * reach, MIN_REACH);
  const lens = boneLengths(future, frames, skeleton);
  const nb = rest.length;
  let prevX = history[(historyFrames - 1) * s];
  let prevZ = history[(historyFrames - 1) * s + 2];
  for (let f = 0; f < frames; f++) {
    const o = f * s;
    for (let i = 0; i < s; i++) if (!Number.isFinite(future[o + i])) return { frame: f, detail: 'a value is not finite' };
    for (let b = 0; b < nb; b++) {
      const r = lens[f * nb + b] / rest[b];
      if (!(r <= BONE_RATIO && r >= 1 / BONE_RATIO)) return { frame: f, detail: `a bone is more than ${BONE_RATIO}x off its length in the history` };
    }
    for (let j = 0; j < J; j++) {
      const d = Math.hypot(future[o + j * 3] - future[o], future[o + j * 3 + 1] - future[o + 1], future[o + j * 3 + 2] - future[o + 2]);
      if (!(d <= reach)) return { frame: f, detail: `a joint is more than ${reach.toFixed(2)} m from the root` };
    }
    if (!(Math.hypot(future[o] - prevX, future[o + 2] - prevZ) <= MAX_ROOT_STEP)) {
      return { frame: f, detail: `the root moves more than ${MAX_ROOT_STEP} m in one frame` };
    }
    if (!(Math.abs(future[o + 1]) <= MAX_ROOT_HEIGHT)) return { frame: f, detail: `the root is more than ${MAX_ROOT_HEIGHT} m from the floor` };
    prevX = future[o];
    prevZ = future[o + 2];
  }
  return null;
}

/** Cut, in place, every sample of a prediction at its first bad frame (within its length). */
export function cutOutOfBounds(pred: Prediction, history: ArrayLike<number>, historyFrames: number, skeleton: Skeleton): void {
  const s = pred.joints * 3;
  for (let i = 0; i < pred.k; i++) {
    const base = i * pred.frames * s;
    const len = pred.lengths[i];
    const bad = firstBadFrame(pred.futures.subarray(base, base + len * s), len, history, historyFrames, skeleton);
    if (!bad) continue;
    const { frame, detail } = bad;
    const last = frame > 0 ? pred.futures.slice(base + (frame - 1) * s, base + frame * s)
      : Float32Array.from(Array.prototype.slice.call(history, (historyFrames - 1) * s, historyFrames * s) as number[]);
    for (let f = frame; f < pred.frames; f++) pred.futures.set(last, base + f * s);
    pred.lengths[i] = frame;
    const sample = pred.samples[i];
    sample.length = frame;
    sample.cut = { frame, reason: CUT_REASON, detail };
    sample.segments = sample.segments.filter((g) => g.start < frame).map((g) => ({ ...g, length: Math.min(g.length, frame - g.start) }));
    if (sample.marks) sample.marks = sample.marks.filter((m) => m < frame);
    if (sample.labels) sample.labels = sample.labels.slice(0, (sample.marks ?? sample.labels).length);
    if (pred.ghosts) {
      const keep = (sample.marks ?? pred.ghosts.frames[i]).length;
      pred.ghosts.frames[i] = pred.ghosts.frames[i].slice(0, keep);
      pred.ghosts.poses[i] = pred.ghosts.poses[i].slice(0, keep * s);
    }
  }
}
