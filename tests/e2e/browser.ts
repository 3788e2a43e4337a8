// Chromium for the browser tests: Debian's binary via playwright-core, a throwaway profile,
// and a record of everything that went wrong on the page (console errors, page errors, failed requests).
import { mkdir, mkdtemp, rm, writeFile } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium, type BrowserContext, type Locator, type Page } from 'playwright-core';

export const CHROMIUM = process.env.E2E_CHROMIUM ?? '/usr/bin/chromium';
export const SCREENSHOTS = fileURLToPath(new URL('./screenshots/', import.meta.url));

const ARGS = [
  '--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
  '--disable-background-networking', '--disable-component-update', '--disable-sync',
];

export interface Problems {
  consoleErrors: string[];
  pageErrors: string[];
  failedRequests: string[];
}

export interface BrowserSession {
  context: BrowserContext;
  page: Page;
  /** What went wrong so far on any page of this session. */
  problems: Problems;
  /** Forget recorded problems (e.g. after a deliberately broken step). */
  resetProblems(): void;
  /** Save a PNG into tests/e2e/screenshots/ and return its bytes. */
  screenshot(name: string, target?: Page | Locator): Promise<Buffer>;
  close(): Promise<void>;
}

export interface BrowserOptions {
  viewport?: { width: number; height: number };
  colorScheme?: 'light' | 'dark';
  /** Extra Chromium flags. */
  args?: string[];
}

function watch(page: Page, problems: Problems): void {
  page.on('console', (msg) => {
    if (msg.type() === 'error') problems.consoleErrors.push(`${msg.text()} (${msg.location().url})`);
  });
  page.on('pageerror', (err) => problems.pageErrors.push(String(err.stack ?? err)));
  page.on('requestfailed', (req) => problems.failedRequests.push(`${req.method()} ${req.url()}: ${req.failure()?.errorText}`));
  page.on('response', (res) => {
    if (res.status() >= 400) problems.failedRequests.push(`${res.request().method()} ${res.url()}: HTTP ${res.status()}`);
  });
}

export async function openBrowser(options: BrowserOptions = {}): Promise<BrowserSession> {
  const profile = await mkdtemp(join(tmpdir(), 'motion-futures-e2e-'));
  let context: BrowserContext;
  try {
    context = await chromium.launchPersistentContext(profile, {
      executablePath: CHROMIUM,
      headless: true,
      args: [...ARGS, ...(options.args ?? [])],
      viewport: options.viewport ?? { width: 1280, height: 800 },
      colorScheme: options.colorScheme ?? 'light',
      timeout: 60_000,
    });
  } catch (err) {
    await rm(profile, { recursive: true, force: true });
    throw err;
  }
  const problems: Problems = { consoleErrors: [], pageErrors: [], failedRequests: [] };
  const existing = context.pages();
  for (const p of existing) watch(p, problems);
  context.on('page', (p) => watch(p, problems));
  const page = existing[0] ?? await context.newPage();
  page.setDefaultTimeout(30_000);

  return {
    context, page, problems,
    resetProblems() {
      problems.consoleErrors.length = 0;
      problems.pageErrors.length = 0;
      problems.failedRequests.length = 0;
    },
    async screenshot(name, target = page) {
      await mkdir(SCREENSHOTS, { recursive: true });
      const png = await target.screenshot({ animations: 'disabled', timeout: 60_000 });
      await writeFile(join(SCREENSHOTS, name), png);
      return png;
    },
    async close() {
      try { await context.close(); } finally { await rm(profile, { recursive: true, force: true }); }
    },
  };
}
