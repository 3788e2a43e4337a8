// The seam between a history and its future, twin of export/ops/seam.py: the first predicted frames
// continue the history's last velocity and hand over to the prediction within SEAM_FRAMES frames,
//   y'_t = c_t + w_t (y_t - c_t),  c_t = x_N + (t + 1)(x_N - x_{N-1}),  w_t = min(t / SEAM_FRAMES, 1).
// The graphs apply it themselves; Keyposes, whose future is interpolated outside a graph, calls this.
export const SEAM_FRAMES = 5;

/** In place on k futures [k, frames, stride] (canonical), from the history's last two frames [2, stride]. */
export function continueHistory(futures: Float64Array, k: number, frames: number, stride: number, lastTwo: ArrayLike<number>): Float64Array {
  for (let q = 0; q < k; q++) {
    for (let t = 0; t < Math.min(frames, SEAM_FRAMES); t++) {
      const w = t / SEAM_FRAMES;
      const o = (q * frames + t) * stride;
      for (let i = 0; i < stride; i++) {
        const x1 = lastTwo[stride + i];
        const c = x1 + (t + 1) * (x1 - lastTwo[i]);
        futures[o + i] = c + w * (futures[o + i] - c);
      }
    }
  }
  return futures;
}
