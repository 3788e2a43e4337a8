// WAT's variance stopping (Eq. 8), twin of export/ops/variance_stop.py.
// v_i = 1/Q sum_{j=i}^{i+Q-1} ||y_j - mean(y_i..y_{i+Q-1})||_2 over whole poses; a sample stops at
// the first frame i >= T_min with v_i < delta and keeps frames 1..i, else it keeps T_max frames.

/** frames [count, coords] flat -> v [count - q + 1]; v[f] is the window starting at 0-based frame f. */
export function varianceCurve(frames: ArrayLike<number>, count: number, coords: number, q: number): Float64Array {
  if (frames.length !== count * coords) throw new RangeError(`varianceCurve: ${frames.length} values for ${count} x ${coords}`);
  if (q < 1 || count < q) throw new RangeError(`need at least q=${q} frames for a variance window, got ${count}`);
  const out = new Float64Array(count - q + 1);
  const mean = new Float64Array(coords);
  for (let f = 0; f < out.length; f++) {
    mean.fill(0);
    for (let j = f; j < f + q; j++) for (let c = 0; c < coords; c++) mean[c] += frames[j * coords + c];
    for (let c = 0; c < coords; c++) mean[c] /= q;
    let total = 0;
    for (let j = f; j < f + q; j++) {
      let sq = 0;
      for (let c = 0; c < coords; c++) {
        const d = frames[j * coords + c] - mean[c];
        sq += d * d;
      }
      total += Math.sqrt(sq);
    }
    out[f] = total / q;
  }
  return out;
}

export interface Stop {
  /** Frames kept (1-based index of the stop frame), or maxFrames. */
  length: number;
  /** False when no tested window fell below delta: the sample keeps maxFrames. */
  stopped: boolean;
  /** Smallest |v_i - delta| over the windows tested (i = T_min .. length). */
  margin: number;
}

export function firstStop(curve: ArrayLike<number>, delta: number, minFrames: number, maxFrames: number): Stop {
  let margin = Infinity;
  for (let f = minFrames - 1; f < curve.length; f++) {
    margin = Math.min(margin, Math.abs(curve[f] - delta));
    if (curve[f] < delta) return { length: f + 1, stopped: true, margin };
  }
  return { length: maxFrames, stopped: false, margin };
}
