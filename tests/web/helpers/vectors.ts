// The shared test vectors and their tolerances (export/tolerance.py): exact things are compared
// exactly by each test; every float within the tolerance the file states, derived from the
// family's measured float32-vs-float64 gap when Python wrote it.
import { readFileSync } from 'node:fs';

export interface About {
  text: string;
  float32_vs_float64_gap: number | Record<string, number>;
  tolerance: number | Record<string, number>;
}

export function readVector<T>(name: string): T & { about: About } {
  return JSON.parse(readFileSync(new URL(`../../../contract/vectors/${name}.json`, import.meta.url), 'utf8')) as T & { about: About };
}

/** The file's float tolerance (per model for the end-to-end vector). */
export function tolerance(doc: { about: About }, model?: string): number {
  const t = doc.about.tolerance;
  if (typeof t === 'number') return t;
  if (model === undefined || !(model in t)) throw new Error(`the vector has one tolerance per model; name one of ${Object.keys(t).join(', ')}`);
  return t[model];
}

/** Largest |got - want| (the lengths must agree). */
export function worstDiff(got: ArrayLike<number>, want: ArrayLike<number>): number {
  if (got.length !== want.length) throw new Error(`length ${got.length} != ${want.length}`);
  let w = 0;
  for (let i = 0; i < want.length; i++) w = Math.max(w, Math.abs(got[i] - want[i]));
  return w;
}
