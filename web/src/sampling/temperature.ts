// softmax(logits / T) and drawing an index from it with one uniform, twin of the sampling part of
// export/ops/proximity.py. The margin is the uniform's distance to the nearest inner CDF bound:
// a runtime difference smaller than it cannot change the draw.

export function softmax(x: ArrayLike<number>, temperature: number): Float64Array {
  if (!(temperature > 0)) throw new RangeError(`the temperature must be positive, got ${temperature}`);
  const out = new Float64Array(x.length);
  let max = -Infinity;
  for (let i = 0; i < x.length; i++) max = Math.max(max, x[i] / temperature);
  let sum = 0;
  for (let i = 0; i < x.length; i++) {
    out[i] = Math.exp(x[i] / temperature - max);
    sum += out[i];
  }
  for (let i = 0; i < x.length; i++) out[i] /= sum;
  return out;
}

/** The first index whose cumulative probability exceeds u (u in [0, 1)), and u's margin. */
export function sampleIndex(logits: ArrayLike<number>, temperature: number, u: number): { index: number; margin: number } {
  const p = softmax(logits, temperature);
  const cdf = new Float64Array(p.length);
  let acc = 0;
  for (let i = 0; i < p.length; i++) {
    acc += p[i];
    cdf[i] = acc;
  }
  let index = p.length - 1; // u at or past the rounded total: the last index
  for (let i = 0; i < p.length; i++) {
    if (u < cdf[i]) {
      index = i;
      break;
    }
  }
  let margin = Infinity;
  if (index > 0) margin = u - cdf[index - 1];
  if (index < p.length - 1) margin = Math.min(margin, cdf[index] - u);
  return { index, margin };
}
