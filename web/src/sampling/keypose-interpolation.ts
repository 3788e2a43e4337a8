// From keyposes back to frames (Keyposes paper, Eq. 3), twin of export/ops/keypose_interpolation.py:
// linear interpolation between consecutive keyposes, the first segment starting from the present
// pose so the future joins the history without a jump.

/** Frame of each keypose after the present (the present is t = 0). */
export function keyposeTimes(durations: number[]): number[] {
  let t = 0;
  return durations.map((d) => (t += d));
}

/** present [J*3], keyposes [n*J*3] reached after durations[i] frames each -> frames t = 1..frames as
 *  [frames*J*3]; past the last keypose its pose is held. */
export function interpolateKeyposes(present: ArrayLike<number>, keyposes: ArrayLike<number>, durations: number[], frames: number): Float64Array {
  const s = present.length;
  const n = durations.length;
  if (keyposes.length !== n * s) throw new RangeError(`${keyposes.length / s} keyposes but ${n} durations`);
  for (const d of durations) if (!(d >= 1)) throw new RangeError(`keypose durations must be at least 1 frame, got ${d}`);
  const ends = keyposeTimes(durations);
  const out = new Float64Array(frames * s);
  let seg = 0;
  for (let f = 0; f < frames; f++) {
    const t = f + 1;
    while (seg < n && t > ends[seg]) seg++;
    if (seg === n) {
      for (let i = 0; i < s; i++) out[f * s + i] = n ? keyposes[(n - 1) * s + i] : present[i];
      continue;
    }
    const step = t - (ends[seg] - durations[seg]);
    for (let i = 0; i < s; i++) {
      const start = seg === 0 ? present[i] : keyposes[(seg - 1) * s + i];
      out[f * s + i] = start + (step * (keyposes[seg * s + i] - start)) / durations[seg];
    }
  }
  return out;
}
