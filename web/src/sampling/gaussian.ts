// Reparameterised Gaussian samples with the shared PRNG, for both VAE predictors: WAT's
// z = mu + exp(logvar / 2) * eps (twin of sample_latent() in export/sample/wat.py) and LCP-VAE's
// z = mu_c + (s * sigma_c) * eps (twin of _shift_scale() in export/sample/lcp_vae.py).
// Draw order: eps for `rows` samples of `dims` latents; from one Prng row-major (sample, then
// dimension), or row i from streams[i] (the predictors: samples that nest, rng/prng.ts); two uniforms
// per normal. Arithmetic in float64, rounded to float32 for the graphs.
import { rowNormals, type Prng } from '../rng/prng';

/** mu, sigma [1 or rows, dims]; eps [rows * dims] -> z = mu + (scale * sigma) * eps [rows, dims]. A single
 *  mu row is shared by every sample. */
export function shiftScale(
  mu: ArrayLike<number>, sigma: ArrayLike<number>, eps: Float64Array, rows: number, dims: number, scale = 1,
): Float32Array {
  if (mu.length !== sigma.length || (mu.length !== dims && mu.length !== rows * dims)) {
    throw new RangeError(`shiftScale: mu/sigma of ${mu.length}/${sigma.length} values for ${rows} x ${dims}`);
  }
  if (eps.length !== rows * dims) throw new RangeError(`shiftScale: ${eps.length} normals for ${rows} x ${dims}`);
  const shared = mu.length === dims;
  const z = new Float32Array(rows * dims);
  for (let i = 0; i < rows; i++) {
    const r = shared ? 0 : i;
    for (let j = 0; j < dims; j++) z[i * dims + j] = mu[r * dims + j] + scale * sigma[r * dims + j] * eps[i * dims + j];
  }
  return z;
}

/** mu, logvar [1 or rows, dims]; eps [rows * dims] -> z [rows, dims]. A single mu row is shared by every sample. */
export function reparameterise(
  mu: Float32Array, logvar: Float32Array, eps: Float64Array, rows: number, dims: number, scale = 1,
): Float32Array {
  if (mu.length !== logvar.length || (mu.length !== dims && mu.length !== rows * dims)) {
    throw new RangeError(`reparameterise: mu/logvar of ${mu.length}/${logvar.length} values for ${rows} x ${dims}`);
  }
  if (eps.length !== rows * dims) throw new RangeError(`reparameterise: ${eps.length} normals for ${rows} x ${dims}`);
  return shiftScale(mu, Float64Array.from(logvar, (v) => Math.exp(v / 2)), eps, rows, dims, scale);
}

/** Draws eps (one Prng row-major, or one stream per row) and returns z = mu + scale * exp(logvar / 2) * eps. */
export function sampleGaussian(source: Prng | Prng[], mu: Float32Array, logvar: Float32Array, rows: number, dims: number, scale = 1): Float32Array {
  return reparameterise(mu, logvar, rowNormals(source, rows, dims), rows, dims, scale);
}
