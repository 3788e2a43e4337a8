// The shared PRNG: xoshiro128** seeded by splitmix32, and Box-Muller normals.
// Twin of export/rng.py; contract/vectors/prng.json pins both. Every normal consumes exactly
// two uniforms (u1, u2) and arrays fill row-major, so draws line up across languages.
// Samples that nest (issue 30 item 6): a predictor gives sample i its own stream, streams(seed, K)[i] =
// Prng(seed) advanced by i x 2^64 draws (xoshiro128**'s jump), so sample i's numbers depend on
// (seed, i) only and raising K adds samples without changing the first ones. Stream 0 is Prng(seed).

export const MAX_SEED = 0xffffffff;

// xoshiro128**'s jump polynomial (export/rng.py JUMP, checked there against 2^64 steps).
const JUMP = [0x8764000b, 0xf542d2d3, 0x6fa035c3, 0x77f2db5b];

function rotl(x: number, k: number): number {
  return ((x << k) | (x >>> (32 - k))) >>> 0;
}

export class Prng {
  private s: Uint32Array;

  constructor(seed: number) {
    if (!Number.isInteger(seed) || seed < 0 || seed > MAX_SEED) {
      throw new RangeError(`seed must be an integer in 0..${MAX_SEED}, got ${seed}`);
    }
    this.s = new Uint32Array(4);
    let state = seed >>> 0;
    for (let i = 0; i < 4; i++) {
      state = (state + 0x9e3779b9) >>> 0;
      let t = state ^ (state >>> 16);
      t = Math.imul(t, 0x21f0aaad);
      t ^= t >>> 15;
      t = Math.imul(t, 0x735a2d97);
      t ^= t >>> 15;
      this.s[i] = t >>> 0;
    }
    if ((this.s[0] | this.s[1] | this.s[2] | this.s[3]) === 0) this.s[0] = 1;
  }

  copy(): Prng {
    const out = new Prng(0);
    out.s.set(this.s);
    return out;
  }

  /** Advance the state by 2^64 draws: the streams before and after never overlap within 2^64 draws. */
  jump(): void {
    const acc = new Uint32Array(4);
    for (const word of JUMP) {
      for (let b = 0; b < 32; b++) {
        if ((word >>> b) & 1) for (let i = 0; i < 4; i++) acc[i] ^= this.s[i];
        this.nextU32();
      }
    }
    this.s.set(acc);
  }

  nextU32(): number {
    const s = this.s;
    const result = Math.imul(rotl(Math.imul(s[1], 5) >>> 0, 7), 9) >>> 0;
    const t = (s[1] << 9) >>> 0;
    s[2] ^= s[0];
    s[3] ^= s[1];
    s[1] ^= s[2];
    s[0] ^= s[3];
    s[2] ^= t;
    s[3] = rotl(s[3], 11);
    return result;
  }

  /** In [0, 1), exactly u32 / 2^32. */
  uniform(): number {
    return this.nextU32() / 4294967296;
  }

  normal(): number {
    const u1 = 1 - this.uniform(); // (0, 1], so the log is finite
    const u2 = this.uniform();
    return Math.sqrt(-2 * Math.log(u1)) * Math.cos(2 * Math.PI * u2);
  }

  normals(n: number): Float64Array {
    const out = new Float64Array(n);
    for (let i = 0; i < n; i++) out[i] = this.normal();
    return out;
  }
}

/** One generator per sample: [Prng(seed), then each 2^64 draws further on]. Twin of streams() in export/rng.py. */
export function streams(seed: number, count: number): Prng[] {
  if (!Number.isInteger(count) || count < 0) throw new RangeError(`the stream count must be a non-negative integer, got ${count}`);
  const out: Prng[] = [];
  const g = new Prng(seed);
  for (let i = 0; i < count; i++) {
    if (i) g.jump();
    out.push(g.copy());
  }
  return out;
}

/** [rows * n] normals: from one generator row-major, or row i from source[i] (one stream per sample). */
export function rowNormals(source: Prng | Prng[], rows: number, n: number): Float64Array {
  if (source instanceof Prng) return source.normals(rows * n);
  if (source.length !== rows) throw new RangeError(`${source.length} streams for ${rows} samples`);
  const out = new Float64Array(rows * n);
  source.forEach((g, i) => out.set(g.normals(n), i * n));
  return out;
}
