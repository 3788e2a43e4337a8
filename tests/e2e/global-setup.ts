// Vitest global setup for the browser tests: build once, serve dist/, hand tests the URL.
// E2E_BASE_PATH=/some/path/ serves the site under a sub-path; E2E_SKIP_BUILD=1 reuses an existing dist/.
import type { TestProject } from 'vitest/node';
import { buildSite, startPreview } from './server';

declare module 'vitest' {
  export interface ProvidedContext {
    /** The served site's URL, ending in '/'. */
    baseUrl: string;
  }
}

export default async function setup(project: TestProject): Promise<() => Promise<void>> {
  if (process.env.E2E_SKIP_BUILD !== '1') await buildSite();
  const server = await startPreview({ basePath: process.env.E2E_BASE_PATH });
  project.provide('baseUrl', server.url);
  return () => server.stop();
}
