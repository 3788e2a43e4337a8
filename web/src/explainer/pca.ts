// A 2-D view of latent samples: principal component analysis by power iteration on the d x d
// covariance (d is the latent size, 16 here, so a library would be heavier than the job), and
// how far apart two clouds of samples are relative to their spread.

export interface Projection {
  mean: Float64Array;
  /** Two orthonormal directions of largest variance. */
  axes: [Float64Array, Float64Array];
  /** Fraction of the total variance along each axis. */
  explained: [number, number];
  project(points: ArrayLike<number>, count: number): Float64Array;
}

/** points [count, d] row-major. */
export function pca2(points: ArrayLike<number>, count: number, d: number): Projection {
  if (count < 2 || points.length !== count * d) throw new RangeError(`pca2: ${points.length} values for ${count} x ${d}`);
  const mean = new Float64Array(d);
  for (let n = 0; n < count; n++) for (let j = 0; j < d; j++) mean[j] += points[n * d + j] / count;
  const cov = new Float64Array(d * d);
  for (let n = 0; n < count; n++) {
    for (let a = 0; a < d; a++) {
      const xa = points[n * d + a] - mean[a];
      for (let b = 0; b < d; b++) cov[a * d + b] += (xa * (points[n * d + b] - mean[b])) / (count - 1);
    }
  }
  let total = 0;
  for (let a = 0; a < d; a++) total += cov[a * d + a];
  const axes: Float64Array[] = [];
  const values: number[] = [];
  const work = Float64Array.from(cov);
  for (let k = 0; k < 2; k++) {
    // Deterministic start, not parallel to an axis found before (deflation removes it).
    let v = Float64Array.from({ length: d }, (_, j) => 1 + j / d);
    let lambda = 0;
    for (let it = 0; it < 1000; it++) {
      const w = new Float64Array(d);
      for (let a = 0; a < d; a++) for (let b = 0; b < d; b++) w[a] += work[a * d + b] * v[b];
      const norm = Math.hypot(...w);
      if (norm < 1e-300) break;
      for (let a = 0; a < d; a++) w[a] /= norm;
      const change = Math.hypot(...w.map((x, a) => x - v[a]));
      v = w;
      lambda = norm;
      if (change < 1e-12) break;
    }
    axes.push(v);
    values.push(lambda);
    for (let a = 0; a < d; a++) for (let b = 0; b < d; b++) work[a * d + b] -= lambda * v[a] * v[b];
  }
  const pair = axes as [Float64Array, Float64Array];
  return {
    mean, axes: pair, explained: [values[0] / (total || 1), values[1] / (total || 1)],
    project(p, n) {
      const out = new Float64Array(n * 2);
      for (let i = 0; i < n; i++) {
        for (let j = 0; j < d; j++) {
          const x = p[i * d + j] - mean[j];
          out[i * 2] += x * pair[0][j];
          out[i * 2 + 1] += x * pair[1][j];
        }
      }
      return out;
    },
  };
}

/**
 * Distance between the means of two clouds [count, d] over their RMS spread
 * sqrt((tr Cov_a + tr Cov_b) / 2), in the full d dimensions: about 0 when both histories give the
 * same distribution, large when the prior depends on the history.
 */
export function separation(a: ArrayLike<number>, b: ArrayLike<number>, count: number, d: number): number {
  const stats = (p: ArrayLike<number>) => {
    const mean = new Float64Array(d);
    for (let n = 0; n < count; n++) for (let j = 0; j < d; j++) mean[j] += p[n * d + j] / count;
    let tr = 0;
    for (let n = 0; n < count; n++) for (let j = 0; j < d; j++) tr += (p[n * d + j] - mean[j]) ** 2 / (count - 1);
    return { mean, tr };
  };
  const sa = stats(a);
  const sb = stats(b);
  const spread = Math.sqrt((sa.tr + sb.tr) / 2);
  const gap = Math.hypot(...sa.mean.map((m, j) => m - sb.mean[j]));
  return spread > 0 ? gap / spread : gap > 0 ? Infinity : 0;
}
