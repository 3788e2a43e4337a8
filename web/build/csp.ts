// The site's content-security policy: its own origin only, for scripts, workers, wasm and
// connections. Every built page carries it as a <meta> tag (so a plain static server, the USB stick's
// `python3 -m http.server`, enforces it too) and `vite preview` sends it as a header (which also
// reaches the workers and the service worker: a <meta> policy does not). The browser test is
// tests/e2e/csp.e2e.test.ts; what a host page needs is in the README's Embedding section.
import type { Plugin } from 'vite';

const DIRECTIVES: [string, string][] = [
  ['default-src', "'self'"],
  // onnxruntime-web compiles its wasm in the predictor and graph workers: 'wasm-unsafe-eval' allows
  // WebAssembly compilation and nothing else (no eval, no inline script). The contract validators
  // are compiled at build time (web/build/precompiled-validators.ts), so Ajv needs no eval either.
  ['script-src', "'self' 'wasm-unsafe-eval'"],
  // Module workers (predictor, graphs) and the service worker, all from assets/ and sw.js.
  ['worker-src', "'self'"],
  // The manifest, models, clips, results and the wasm.
  ['connect-src', "'self'"],
  // The pages set style attributes (the scrubber's marks, colour swatches, the import panel) and
  // embed.html has a <style> block; styles run no code.
  ['style-src', "'self' 'unsafe-inline'"],
  // The pages' icon is `data:,`. Pictures and recordings leave as blob: downloads, which are not images.
  ['img-src', "'self' data:"],
  ['font-src', "'self'"],
  ['object-src', "'none'"],
  ['base-uri', "'self'"],
  ['form-action', "'self'"],
  // No frame-ancestors: embed.html is meant for iframes on other sites (and a <meta> cannot carry it).
];

export const CONTENT_SECURITY_POLICY: string = DIRECTIVES.map(([name, value]) => `${name} ${value}`).join('; ');

/** The policy as the first thing after <meta charset> (a <meta> policy covers only what follows it). */
export function cspMeta(policy: string = CONTENT_SECURITY_POLICY): Plugin {
  const tag = `<meta http-equiv="Content-Security-Policy" content="${policy.replace(/"/g, '&quot;')}" />`;
  return {
    name: 'motion-futures:csp-meta',
    // The dev server injects its own inline styles and client: the policy is for the built site.
    apply: 'build',
    transformIndexHtml: {
      order: 'pre',
      handler(html, ctx) {
        const at = /<meta\s+charset=[^>]*>/i.exec(html) ?? /<head[^>]*>/i.exec(html);
        if (!at) throw new Error(`${ctx.filename}: no <head> to put the content-security policy in`);
        const end = at.index + at[0].length;
        return `${html.slice(0, end)}\n    ${tag}${html.slice(end)}`;
      },
    },
  };
}
