// What every widget on a page shares: one manifest fetch and one predictor worker per site, so
// two instances hold one copy of each model. Each instance predicts under its own view id, so a
// request supersedes only its own instance's previous one (web/src/predictor/scheduler.ts).
import type { Manifest } from '../contract/types';
import { fetchContract } from '../contract/validate';
import { PredictorClient } from '../predictor/client';

const manifests = new Map<string, Promise<Manifest>>();
const clients = new Map<string, PredictorClient>();
let views = 0;

export function sharedManifest(siteRoot: string): Promise<Manifest> {
  let m = manifests.get(siteRoot);
  if (!m) {
    m = fetchContract(`${siteRoot}models/manifest.json`, 'manifest');
    m.catch(() => manifests.delete(siteRoot)); // a later instance may retry
    manifests.set(siteRoot, m);
  }
  return m;
}

/** The worker for this site, created on first use; throws ModelLoadError without WebAssembly. */
export function sharedClient(siteRoot: string, manifest: Manifest): PredictorClient {
  let c = clients.get(siteRoot);
  if (!c) {
    c = new PredictorClient(siteRoot, manifest);
    clients.set(siteRoot, c);
  }
  return c;
}

/** A view id no other instance on this page has. */
export function newViewId(): string {
  views += 1;
  return `view-${views}`;
}
