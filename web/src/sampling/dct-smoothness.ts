// WAT's smoothness prior (Eq. 4), twin of export/ops/dct_smoothness.py: the last L history poses
// and the first L predicted ones, Z [2L, K], against their first M orthonormal DCT-II bases,
// L_smooth = 1/(2L) sum_i ||z_i - (D D^T Z)_i||^2 in square metres. Float64 throughout.

/** D [frames, bases] row-major: column m is the m-th orthonormal DCT-II basis vector (scipy's norm='ortho'). */
export function dctBasis(frames: number, bases: number): Float64Array {
  if (!(bases > 0 && bases <= frames)) throw new RangeError(`need 0 < bases <= frames, got ${bases} bases for ${frames} frames`);
  const d = new Float64Array(frames * bases);
  for (let n = 0; n < frames; n++) {
    for (let m = 0; m < bases; m++) {
      const norm = m === 0 ? Math.sqrt(1 / frames) : Math.sqrt(2 / frames);
      d[n * bases + m] = norm * Math.cos((Math.PI * m * (2 * n + 1)) / (2 * frames));
    }
  }
  return d;
}

const projectors = new Map<string, Float64Array>();

/** P = D D^T [frames, frames], cached per (frames, bases). */
function projector(frames: number, bases: number): Float64Array {
  const key = `${frames}:${bases}`;
  let p = projectors.get(key);
  if (!p) {
    const d = dctBasis(frames, bases);
    p = new Float64Array(frames * frames);
    for (let a = 0; a < frames; a++) {
      for (let b = 0; b < frames; b++) {
        let s = 0;
        for (let m = 0; m < bases; m++) s += d[a * bases + m] * d[b * bases + m];
        p[a * frames + b] = s;
      }
    }
    projectors.set(key, p);
  }
  return p;
}

/** tail and head: [l, coords] flat (coords = joints * 3), metres -> Eq. 4 in square metres. */
export function smoothness(tail: ArrayLike<number>, head: ArrayLike<number>, l: number, coords: number, bases: number): number {
  if (tail.length !== l * coords || head.length !== l * coords) {
    throw new RangeError(`smoothness: tail ${tail.length} and head ${head.length} values, expected ${l * coords} each`);
  }
  const frames = 2 * l;
  const z = new Float64Array(frames * coords);
  for (let i = 0; i < l * coords; i++) {
    z[i] = tail[i];
    z[l * coords + i] = head[i];
  }
  const p = projector(frames, bases);
  let total = 0;
  for (let a = 0; a < frames; a++) {
    let sq = 0;
    for (let c = 0; c < coords; c++) {
      let approx = 0;
      for (let b = 0; b < frames; b++) approx += p[a * frames + b] * z[b * coords + c];
      const r = z[a * coords + c] - approx;
      sq += r * r;
    }
    total += sq;
  }
  return total / frames;
}
