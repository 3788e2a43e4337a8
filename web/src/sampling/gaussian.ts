// Reparameterised Gaussian samples with the shared PRNG, twin of sample_latent() in
// export/sample/wat.py: z = mu + exp(logvar / 2) * eps (times an optional scale on the spread).
// Draw order: eps for `rows` samples of `dims` latents, row-major (sample, then dimension), two
// uniforms per normal. Arithmetic in float64, rounded to float32 for the graphs.
import type { Prng } from '../rng/prng';

/** mu, logvar [1 or rows, dims]; eps [rows * dims] -> z [rows, dims]. A single mu row is shared by every sample. */
export function reparameterise(
  mu: Float32Array, logvar: Float32Array, eps: Float64Array, rows: number, dims: number, scale = 1,
): Float32Array {
  if (mu.length !== logvar.length || (mu.length !== dims && mu.length !== rows * dims)) {
    throw new RangeError(`reparameterise: mu/logvar of ${mu.length}/${logvar.length} values for ${rows} x ${dims}`);
  }
  if (eps.length !== rows * dims) throw new RangeError(`reparameterise: ${eps.length} normals for ${rows} x ${dims}`);
  const shared = mu.length === dims;
  const z = new Float32Array(rows * dims);
  for (let i = 0; i < rows; i++) {
    const r = shared ? 0 : i;
    for (let j = 0; j < dims; j++) {
      const sd = scale * Math.exp(logvar[r * dims + j] / 2);
      z[i * dims + j] = mu[r * dims + j] + sd * eps[i * dims + j];
    }
  }
  return z;
}

/** Draws eps from `prng` (rows x dims, row-major) and returns z = mu + scale * exp(logvar / 2) * eps. */
export function sampleGaussian(prng: Prng, mu: Float32Array, logvar: Float32Array, rows: number, dims: number, scale = 1): Float32Array {
  return reparameterise(mu, logvar, prng.normals(rows * dims), rows, dims, scale);
}
