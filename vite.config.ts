import { defineConfig, type Plugin } from 'vite';
import { VitePWA } from 'vite-plugin-pwa';
import { appendFileSync, existsSync, readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { CONTENT_SECURITY_POLICY, cspMeta } from './web/build/csp';
import { precompiledValidators } from './web/build/precompiled-validators';

const root = fileURLToPath(new URL('./web', import.meta.url));
/** The one script with a stable name (host pages include it by name); every other script has its hash in its name. */
const EMBED_SCRIPT = 'assets/motion-futures.js';
const here = (path: string) => fileURLToPath(new URL(path, import.meta.url));

/** Files every build carries at the top of dist/, so the folder on a USB stick has its licences. */
const SITE_FILES: Record<string, string> = {
  LICENSE: './LICENSE',
  'THIRD_PARTY_NOTICES.md': './THIRD_PARTY_NOTICES.md',
  'DATA_NOTICE.md': './DATA_NOTICE.md',
  'icon.svg': './web/public-pwa/icon.svg',
};

function siteFiles(): Plugin {
  return {
    name: 'motion-futures:site-files',
    apply: 'build',
    generateBundle() {
      for (const [fileName, path] of Object.entries(SITE_FILES)) {
        if (existsSync(here(path))) this.emitFile({ type: 'asset', fileName, source: readFileSync(here(path)) });
      }
      // Which release this folder is: old permalinks find their version by it (web/src/share/versions.ts).
      const { name, version } = JSON.parse(readFileSync(here('./package.json'), 'utf8'));
      this.emitFile({ type: 'asset', fileName: 'version.json', source: `${JSON.stringify({ name, version })}\n` });
    },
  };
}

/**
 * Appends the node_modules packages a build's chunks contain to $MF_BUNDLED_PACKAGES (one per
 * line; the page build and each worker build append), for scripts/release.mjs's notices.
 */
function bundledPackages(): Plugin {
  return {
    name: 'motion-futures:bundled-packages',
    apply: 'build',
    generateBundle(_options, bundle) {
      const out = process.env.MF_BUNDLED_PACKAGES;
      if (!out) return;
      const names = new Set<string>();
      for (const chunk of Object.values(bundle)) {
        if (chunk.type !== 'chunk') continue;
        for (const id of chunk.moduleIds) {
          const m = /node_modules\/((?:@[^/]+\/)?[^/]+)\//.exec(id.replace(/\\/g, '/'));
          if (m) names.add(m[1]);
        }
      }
      appendFileSync(out, [...names].map((n) => `${n}\n`).join(''));
    },
  };
}

// The site lives in web/, serves the artefacts in public/, and works under any sub-path.
export default defineConfig({
  root,
  base: './',
  publicDir: fileURLToPath(new URL('./public', import.meta.url)),
  build: {
    outDir: fileURLToPath(new URL('./dist', import.meta.url)),
    emptyOutDir: true,
    target: 'es2022',
    chunkSizeWarningLimit: 1500,
    // Pages: the predictor, the Results page (export/eval writes public/results.json), How it works
    // and the Model card.
    // Plus embed.html (the widget for iframes) and the widget's own script, which host pages
    // include by a stable name: assets/motion-futures.js.
    rollupOptions: {
      input: {
        main: fileURLToPath(new URL('./web/index.html', import.meta.url)),
        ...(existsSync(here('./web/results.html')) ? { results: here('./web/results.html') } : {}),
        embed: here('./web/embed.html'),
        // The benchmark page (make bench, the memory test): the predictor worker without UI.
        bench: here('./web/bench.html'),
        explainer: here('./web/explainer.html'),
        'model-card': here('./web/model-card.html'),
        // The bring-your-own guide (docs/BRING_YOUR_OWN.md as a page); the import panel's messages link to it.
        'bring-your-own': here('./web/bring-your-own.html'),
        'motion-futures': here('./web/src/embed/element.ts'),
      },
      // The service worker's precache hashing (15 MB) is slow by design; no need to warn each build.
      checks: { bundlerTimings: false },
      output: {
        // Every script sits in assets/: web/src/embed/site.ts finds the site root from that.
        entryFileNames: (chunk) => (chunk.name === 'motion-futures' ? EMBED_SCRIPT : 'assets/[name]-[hash].js'),
        chunkFileNames: 'assets/[name]-[hash].js',
      },
    },
  },
  plugins: [
    // The content-security policy on every page, and the contract validators it needs compiled.
    cspMeta(),
    precompiledValidators(here('./contract')),
    siteFiles(),
    bundledPackages(),
    // Offline: a service worker precaching the whole site, models and the 14 MB wasm included.
    VitePWA({
      strategies: 'generateSW',
      injectRegister: false, // web/src/embed/offline.ts registers it, from the site's own pages only
      registerType: 'autoUpdate',
      manifest: {
        name: 'motion futures',
        short_name: 'motion futures',
        description: 'Stochastic human motion prediction in the browser.',
        start_url: './',
        scope: './',
        display: 'standalone',
        background_color: '#f6f7f9',
        theme_color: '#1f6fc5',
        icons: [{ src: 'icon.svg', sizes: 'any', type: 'image/svg+xml', purpose: 'any' }],
      },
      includeManifestIcons: false, // icon.svg comes from siteFiles() and the glob below
      workbox: {
        globPatterns: ['**/*.{html,js,css,wasm,onnx,json,svg,webmanifest}'],
        // vite-plugin-pwa takes every file in assets/ as named by its hash, so precached without a
        // revision and kept from one release to the next. The embed script is not: with no revision a
        // new release kept the old one, whose imports (the old release's chunks) are gone.
        dontCacheBustURLsMatching: new RegExp(`^assets/(?!${EMBED_SCRIPT.slice('assets/'.length).replace(/\./g, '\\.')}$)`),
        // Workbox skips files over 2 MiB by default, which would leave out the wasm.
        maximumFileSizeToCacheInBytes: 64 * 1024 * 1024,
        // Permalinks carry the state in the query: every query maps to the same cached page.
        ignoreURLParametersMatching: [/.*/],
        navigateFallback: null,
        cleanupOutdatedCaches: true,
        // The first visit's worker takes the page at once; a new release's worker waits until a page
        // asks it to take over and then reloads (web/src/embed/offline.ts), so releases never mix.
        clientsClaim: true,
        skipWaiting: false,
      },
    }),
  ],
  worker: { format: 'es', plugins: () => [precompiledValidators(here('./contract')), bundledPackages()] },
  server: { host: '127.0.0.1', fs: { allow: [fileURLToPath(new URL('.', import.meta.url))] } },
  // The same policy as a header: it also covers the workers and the service worker.
  preview: { host: '127.0.0.1', headers: { 'Content-Security-Policy': CONTENT_SECURITY_POLICY } },
});
