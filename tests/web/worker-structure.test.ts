// onnxruntime runs only in the worker: no module reachable from a page entry imports it.
import { describe, expect, it } from 'vitest';
import { existsSync, readFileSync, readdirSync } from 'node:fs';
import { dirname, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

const web = fileURLToPath(new URL('../../web/', import.meta.url));
const IMPORT = /(?:import|export)\s[^'"]*?from\s*['"]([^'"]+)['"]|import\s*\(\s*['"]([^'"]+)['"]\s*\)|import\s+['"]([^'"]+)['"]/g;

function resolveLocal(from: string, spec: string): string | null {
  if (!spec.startsWith('.')) return null;
  const base = resolve(dirname(from), spec);
  for (const cand of [base, `${base}.ts`, `${base}/index.ts`]) if (existsSync(cand) && cand.endsWith('.ts')) return cand;
  return null;
}

/** Every module the page entry reaches through static and dynamic imports (not through new Worker). */
function reachable(entry: string): Map<string, string[]> {
  const seen = new Map<string, string[]>();
  const stack = [entry];
  while (stack.length) {
    const file = stack.pop()!;
    if (seen.has(file)) continue;
    const src = readFileSync(file, 'utf8');
    const specs = [...src.matchAll(IMPORT)].map((m) => m[1] ?? m[2] ?? m[3]);
    seen.set(file, specs);
    for (const s of specs) { const r = resolveLocal(file, s); if (r) stack.push(r); }
  }
  return seen;
}

describe('worker structure', () => {
  const entries = readdirSync(web).filter((f) => f.endsWith('.html'))
    .flatMap((html) => [...readFileSync(resolve(web, html), 'utf8').matchAll(/<script[^>]+src="([^"]+\.ts)"/g)].map((m) => resolve(web, m[1])));

  it('finds the page entries', () => {
    expect(entries.length).toBeGreaterThan(0);
  });

  it('no main-thread module imports onnxruntime', () => {
    for (const entry of entries) {
      for (const [file, specs] of reachable(entry)) {
        const bad = specs.filter((s) => s.startsWith('onnxruntime'));
        expect(bad, `${file} imports ${bad.join(', ')}`).toEqual([]);
        expect(file.endsWith('worker.ts'), `${file} is a worker but is imported by the page`).toBe(false);
      }
    }
  });

  it('the worker is the module that imports onnxruntime', () => {
    const worker = readFileSync(resolve(web, 'src/predictor/worker.ts'), 'utf8');
    expect(worker).toMatch(/import\(\s*'onnxruntime-web\/wasm'\s*\)/);
  });
});
