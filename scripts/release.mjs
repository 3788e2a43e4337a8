#!/usr/bin/env node
// make release: build the site, write THIRD_PARTY_NOTICES.md for the packages the build really
// bundles, and zip dist/ as release/motion-futures-<version>.zip (one folder inside, named by
// the version, so hosts can keep old releases side by side and old permalinks keep working).
//   node scripts/release.mjs [--out DIR]
import { spawnSync } from 'node:child_process';
import { existsSync, mkdirSync, mkdtempSync, readdirSync, readFileSync, rmSync, statSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, relative } from 'node:path';
import { fileURLToPath } from 'node:url';
import { zipSync } from 'fflate';

const ROOT = fileURLToPath(new URL('..', import.meta.url));
const DIST = join(ROOT, 'dist');
const pkg = JSON.parse(readFileSync(join(ROOT, 'package.json'), 'utf8'));
const args = process.argv.slice(2);
const outDir = args.includes('--out') ? args[args.indexOf('--out') + 1] : join(ROOT, 'release');
const name = `motion-futures-${pkg.version}`;

function fail(message) {
  console.error(`release: ${message}`);
  process.exit(1);
}

// --- 1. build, recording the packages every chunk (page and worker builds) contains ----------------
const work = mkdtempSync(join(tmpdir(), 'mf-release-'));
const listFile = join(work, 'bundled.txt');
writeFileSync(listFile, '');
const build = spawnSync(join(ROOT, 'node_modules/.bin/vite'), ['build', '--logLevel', 'warn'], {
  cwd: ROOT, stdio: 'inherit', env: { ...process.env, NODE_ENV: 'production', MF_BUNDLED_PACKAGES: listFile },
});
if (build.status !== 0) fail('vite build failed');
const bundled = new Set(readFileSync(listFile, 'utf8').split('\n').filter(Boolean));
rmSync(work, { recursive: true, force: true });
if (!bundled.size) fail('the build reported no bundled packages (is the bundledPackages plugin in vite.config.ts?)');
// The service worker's runtime is bundled by workbox-build, outside Vite: its modules mark themselves.
for (const f of readdirSync(DIST).filter((f) => /^(sw|workbox-[^/]*)\.js$/.test(f))) {
  for (const m of readFileSync(join(DIST, f), 'utf8').matchAll(/workbox:([a-z-]+):/g)) bundled.add(`workbox-${m[1]}`);
}

// --- 2. third-party notices -------------------------------------------------------------------------
/** Copyright lines for packages that ship no licence file of their own. */
const COPYRIGHT = {
  'onnxruntime-web': 'Copyright (c) Microsoft Corporation.',
  'onnxruntime-common': 'Copyright (c) Microsoft Corporation.',
};
const MIT = (holder) => `MIT License

${holder}

Permission is hereby granted, free of charge, to any person obtaining a copy
of this software and associated documentation files (the "Software"), to deal
in the Software without restriction, including without limitation the rights
to use, copy, modify, merge, publish, distribute, sublicense, and/or sell
copies of the Software, and to permit persons to whom the Software is
furnished to do so, subject to the following conditions:

The above copyright notice and this permission notice shall be included in all
copies or substantial portions of the Software.

THE SOFTWARE IS PROVIDED "AS IS", WITHOUT WARRANTY OF ANY KIND, EXPRESS OR
IMPLIED, INCLUDING BUT NOT LIMITED TO THE WARRANTIES OF MERCHANTABILITY,
FITNESS FOR A PARTICULAR PURPOSE AND NONINFRINGEMENT. IN NO EVENT SHALL THE
AUTHORS OR COPYRIGHT HOLDERS BE LIABLE FOR ANY CLAIM, DAMAGES OR OTHER
LIABILITY, WHETHER IN AN ACTION OF CONTRACT, TORT OR OTHERWISE, ARISING FROM,
OUT OF OR IN CONNECTION WITH THE SOFTWARE OR THE USE OR OTHER DEALINGS IN THE
SOFTWARE.`;

function licenceText(dir, meta) {
  const file = readdirSync(dir).find((f) => /^(licen[cs]e|copying)(\.(md|txt))?$/i.test(f));
  if (file) return readFileSync(join(dir, file), 'utf8').trim();
  const holder = COPYRIGHT[meta.name] ?? (meta.author ? `Copyright (c) ${typeof meta.author === 'string' ? meta.author : meta.author.name}` : null);
  if (meta.license === 'MIT' && holder) return MIT(holder);
  fail(`${meta.name} ships no licence file and its licence (${meta.license}) has no text here: add it to COPYRIGHT or write its text`);
}

function repository(meta) {
  const r = typeof meta.repository === 'string' ? meta.repository : meta.repository?.url;
  return (r ?? meta.homepage ?? '').replace(/^git\+/, '').replace(/\.git$/, '');
}

const sections = [...bundled].sort().map((id) => {
  const dir = join(ROOT, 'node_modules', id);
  if (!existsSync(join(dir, 'package.json'))) fail(`bundled package ${id} is not in node_modules`);
  const meta = JSON.parse(readFileSync(join(dir, 'package.json'), 'utf8'));
  const extra = id === 'onnxruntime-web'
    ? '\nThe WebAssembly build of ONNX Runtime (assets/ort-wasm-*.wasm) also contains the third-party components listed in\n'
      + "ONNX Runtime's ThirdPartyNotices.txt (https://github.com/microsoft/onnxruntime/blob/main/ThirdPartyNotices.txt).\n"
    : '';
  return `## ${meta.name} ${meta.version}\n\nLicence: ${meta.license}${repository(meta) ? ` · ${repository(meta)}` : ''}\n${extra}\n\`\`\`text\n${licenceText(dir, meta)}\n\`\`\`\n`;
});
const notices = `# Third-party notices

The built site (\`dist/\`, and every release zip) bundles the following packages. This file is
generated by \`make release\` (scripts/release.mjs) from the packages the build actually put into
its scripts, with each package's own licence text.

${sections.join('\n')}`;
const noticesPath = join(ROOT, 'THIRD_PARTY_NOTICES.md');
const before = existsSync(noticesPath) ? readFileSync(noticesPath, 'utf8') : '';
writeFileSync(noticesPath, notices);
writeFileSync(join(DIST, 'THIRD_PARTY_NOTICES.md'), notices);
if (before !== notices) console.log('release: THIRD_PARTY_NOTICES.md changed: commit it with the release');
for (const f of ['LICENSE', 'DATA_NOTICE.md']) {
  if (!existsSync(join(DIST, f))) fail(`dist/${f} is missing (vite.config.ts siteFiles copies it from the repository root)`);
}

// --- 3. the zip ---------------------------------------------------------------------------------------
const howTo = `motion-futures ${pkg.version}

A static site: stochastic human motion prediction running in your browser. It needs no internet.
Browsers will not run its WebAssembly from file://, so serve this folder with any static web
server that sends .wasm files as application/wasm. With Python 3.8 or newer:

    cd ${name}
    python3 -m http.server 8000 --bind 127.0.0.1

then open http://127.0.0.1:8000/ . After one visit the site also works with the network off.

LICENSE, THIRD_PARTY_NOTICES.md and DATA_NOTICE.md say what you may do with it.
`;
const files = {};
const add = (dir) => {
  for (const f of readdirSync(dir)) {
    const path = join(dir, f);
    if (statSync(path).isDirectory()) add(path);
    else files[`${name}/${relative(DIST, path).split('\\').join('/')}`] = [readFileSync(path), { level: /\.(onnx|wasm|js|json|html|css|md|svg|webmanifest|txt)$|LICENSE$/.test(f) ? 6 : 0 }];
  }
};
add(DIST);
files[`${name}/README.txt`] = [new TextEncoder().encode(howTo), { level: 6 }];
// A fixed timestamp, so the same tree gives the same zip.
const zip = zipSync(files, { mtime: new Date('2020-01-01T00:00:00Z') });
mkdirSync(outDir, { recursive: true });
const zipPath = join(outDir, `${name}.zip`);
writeFileSync(zipPath, zip);
console.log(`release: ${relative(ROOT, zipPath) || zipPath} (${(zip.length / 1e6).toFixed(1)} MB, ${Object.keys(files).length} files, `
  + `bundled packages: ${[...bundled].sort().join(', ')})`);
