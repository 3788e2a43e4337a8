// The measured diversity of K futures, twin of diversity() in export/sample/lcp_vae.py:
// WAT Eq. 10, the average over all pairs of the per-frame L2 norm of the whole-pose difference, on
// root-relative poses (each frame's root x and z subtracted, as DLow's APD): where the root stands is
// not pose diversity, and the planted feet (predictor/foot-plant.ts) move only the root path.

/** futures [k, frames, perFrame] flat (perFrame = joints * 3) -> metres; 0 for k < 2. */
export function diversity(futures: Float32Array, k: number, frames: number, perFrame: number): number {
  if (futures.length !== k * frames * perFrame) {
    throw new RangeError(`diversity: expected ${k * frames * perFrame} values, got ${futures.length}`);
  }
  if (k < 2 || frames < 1) return 0;
  const sample = frames * perFrame;
  let total = 0;
  for (let i = 0; i < k; i++) {
    for (let j = i + 1; j < k; j++) {
      let pair = 0;
      for (let f = 0; f < frames; f++) {
        let sq = 0;
        const a = i * sample + f * perFrame;
        const b = j * sample + f * perFrame;
        for (let c = 0; c < perFrame; c++) {
          const axis = c % 3;   // x and z relative to the frame's root; heights kept
          const d = futures[a + c] - futures[b + c] - (axis === 1 ? 0 : futures[a + axis] - futures[b + axis]);
          sq += d * d;
        }
        pair += Math.sqrt(sq);
      }
      total += pair / frames;
    }
  }
  return (2 * total) / (k * (k - 1));
}
