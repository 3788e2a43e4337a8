// Where a take's motion is under way. Many captures begin with the person standing still for a
// second or so; a history cut there shows no motion to continue (and Keyposes finds too few
// keyposes in it). The stage opens a clip's default history at the first frame from which one
// second of the take moves at least half as fast as the take's median: a rule on the motion
// alone, the same for every method.

/** Fraction of the take's median mean-joint speed that one second from the start must reach. */
export const MOVING_FRACTION = 0.5;

/** The first start >= `from` (in steps of `step` frames) from which one second moves at least
 *  MOVING_FRACTION x the take's median speed; `from` itself when the take never does or is too short. */
export function movingStart(positions: ArrayLike<number>, frames: number, joints: number, fps: number,
  from = 0, step = 3): number {
  const w = Math.max(1, Math.round(fps));
  if (frames < w + 2) return from;
  const speed = new Float64Array(frames - 1);     // mean joint displacement between frames f and f + 1
  for (let f = 0; f + 1 < frames; f++) {
    let sum = 0;
    for (let j = 0; j < joints; j++) {
      const a = (f * joints + j) * 3;
      const b = a + joints * 3;
      sum += Math.hypot(positions[b] - positions[a], positions[b + 1] - positions[a + 1], positions[b + 2] - positions[a + 2]);
    }
    speed[f] = sum / joints;
  }
  const sorted = Float64Array.from(speed).sort();
  const median = sorted.length % 2 ? sorted[(sorted.length - 1) / 2] : (sorted[sorted.length / 2 - 1] + sorted[sorted.length / 2]) / 2;
  for (let s = from; s + w <= speed.length; s += step) {
    let sum = 0;
    for (let f = s; f < s + w; f++) sum += speed[f];
    if (sum / w >= MOVING_FRACTION * median) return s;
  }
  return from;
}
