// Read-outs of a label distribution (Keyposes section 3.3: sampling at a temperature).

/** Shannon entropy in bits. */
export function entropyBits(p: ArrayLike<number>): number {
  let h = 0;
  for (let i = 0; i < p.length; i++) if (p[i] > 0) h -= p[i] * Math.log2(p[i]);
  return h;
}

/** Indices of the `count` largest values, largest first (ties: lower index). */
export function topIndices(x: ArrayLike<number>, count: number): number[] {
  return Array.from({ length: x.length }, (_, i) => i).sort((a, b) => x[b] - x[a] || a - b).slice(0, count);
}

/** Distinct labels over all sequences, and how many sequences repeat a single label throughout. */
export function sequenceStats(sequences: number[][]): { distinct: number; constant: number } {
  const all = new Set(sequences.flat());
  return { distinct: all.size, constant: sequences.filter((s) => s.length > 0 && s.every((l) => l === s[0])).length };
}
