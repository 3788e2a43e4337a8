// Build the site and serve dist/ with `vite preview` as a child process, stopped by its PID.
import { spawn, type ChildProcess } from 'node:child_process';
import { createServer } from 'node:net';
import { resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

export const ROOT = fileURLToPath(new URL('../..', import.meta.url));
// absolute, so a build can run in another tree (buildTree)
const VITE = resolve(ROOT, 'node_modules/.bin/vite');

export interface PreviewServer {
  /** Site URL ending in '/', e.g. http://127.0.0.1:41234/ or .../sub/path/ */
  url: string;
  pid: number;
  stop(): Promise<void>;
}

function run(args: string[], timeoutMs: number, cwd = ROOT): Promise<void> {
  return new Promise((resolve, reject) => {
    const child = spawn(VITE, args, { cwd, stdio: ['ignore', 'pipe', 'pipe'], env: { ...process.env, NO_COLOR: '1' } });
    let output = '';
    child.stdout!.on('data', (d) => { output += d; });
    child.stderr!.on('data', (d) => { output += d; });
    const timer = setTimeout(() => { if (child.pid) process.kill(child.pid, 'SIGKILL'); }, timeoutMs);
    child.on('error', (err) => { clearTimeout(timer); reject(err); });
    child.on('exit', (code, signal) => {
      clearTimeout(timer);
      if (code === 0) resolve();
      else reject(new Error(`vite ${args.join(' ')} failed (${signal ?? `exit ${code}`}):\n${output.slice(-4000)}`));
    });
  });
}

/** `vite build` into dist/, or into outDir (the benchmark builds its own, so it never shares dist/ with tests). */
export function buildSite(timeoutMs = 300_000, outDir?: string): Promise<void> {
  // vite resolves a relative outDir against its root (web/), so pass it absolute
  const out = outDir ? ['--outDir', resolve(ROOT, outDir), '--emptyOutDir'] : [];
  return run(['build', '--logLevel', 'warn', ...out], timeoutMs);
}

/** `vite build` of another source tree (its own vite.config.ts, package.json, web/ and public/) into outDir. */
export function buildTree(tree: string, outDir: string, timeoutMs = 300_000): Promise<void> {
  return run(['build', '--logLevel', 'warn', '--outDir', resolve(ROOT, outDir), '--emptyOutDir'], timeoutMs, tree);
}

export function freePort(): Promise<number> {
  return new Promise((resolve, reject) => {
    const srv = createServer();
    srv.unref();
    srv.on('error', reject);
    srv.listen(0, '127.0.0.1', () => {
      const { port } = srv.address() as { port: number };
      srv.close(() => resolve(port));
    });
  });
}

/** Normalise a sub-path to '/a/b/' form ('' and '/' mean the root). */
export function normaliseBasePath(path = '/'): string {
  const inner = path.split('/').filter(Boolean).join('/');
  return inner ? `/${inner}/` : '/';
}

async function waitUntilServing(url: string, child: ChildProcess, log: () => string, timeoutMs: number): Promise<void> {
  const deadline = Date.now() + timeoutMs;
  let exited: string | null = null;
  child.once('exit', (code, signal) => { exited = signal ?? `exit ${code}`; });
  while (Date.now() < deadline) {
    if (exited) throw new Error(`vite preview stopped (${exited}) before serving:\n${log()}`);
    try {
      const res = await fetch(url, { signal: AbortSignal.timeout(2000) });
      if (res.ok) return;
    } catch { /* not listening yet */ }
    await new Promise((r) => setTimeout(r, 250));
  }
  throw new Error(`vite preview did not answer at ${url} within ${timeoutMs} ms:\n${log()}`);
}

export async function startPreview(options: { basePath?: string; port?: number; timeoutMs?: number; outDir?: string } = {}): Promise<PreviewServer> {
  const basePath = normaliseBasePath(options.basePath);
  const port = options.port ?? await freePort();
  const args = ['preview', '--host', '127.0.0.1', '--port', String(port), '--strictPort'];
  // The build uses a relative base, so the same dist/ can be served under any path.
  if (basePath !== '/') args.push('--base', basePath);
  if (options.outDir) args.push('--outDir', resolve(ROOT, options.outDir));
  const child = spawn(VITE, args, { cwd: ROOT, stdio: ['ignore', 'pipe', 'pipe'], env: { ...process.env, NO_COLOR: '1' } });
  if (!child.pid) throw new Error('vite preview did not start');
  const pid = child.pid;
  let output = '';
  child.stdout!.on('data', (d) => { output += d; });
  child.stderr!.on('data', (d) => { output += d; });
  const exited = new Promise<void>((resolve) => child.once('exit', () => resolve()));

  const stop = async () => {
    if (child.exitCode !== null || child.signalCode !== null) return;
    process.kill(pid, 'SIGTERM');
    const killed = await Promise.race([exited.then(() => true), new Promise<boolean>((r) => setTimeout(() => r(false), 5000))]);
    if (!killed && child.exitCode === null && child.signalCode === null) {
      process.kill(pid, 'SIGKILL');
      await exited;
    }
  };

  const url = `http://127.0.0.1:${port}${basePath}`;
  try {
    await waitUntilServing(url, child, () => output.slice(-4000), options.timeoutMs ?? 60_000);
  } catch (err) {
    await stop();
    throw err;
  }
  return { url, pid, stop };
}
