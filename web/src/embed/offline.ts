// The service worker (built by vite-plugin-pwa, precaching the whole site) is registered only by
// the site's own pages, never by a widget on a host page, whose URL is not the site's scope.
// The page says when it is safe to go offline: the worker's own state change to "activated" comes
// only after its install event has put every precached file in the cache, and the size shown is what
// the caches then hold.
// A new release never mixes with the old one (tests/e2e/release-update.e2e.test.ts): its service
// worker installs beside the old one and waits (vite.config.ts: no skipWaiting), so the old page keeps
// getting the old release's files; once this page has done its first work it asks the new worker to
// take over, and a page that registered the worker reloads when another takes its place (in this tab
// or another), so it never runs one release's code with the other's manifest, models or clips.
import type { OfflineState } from '../ui/app';
import { FROM_SOURCES, SITE_ROOT } from './site';

/** Bytes and entries the site's caches hold. */
export async function cachedSize(): Promise<{ bytes: number; files: number }> {
  let bytes = 0;
  let files = 0;
  for (const name of await caches.keys()) {
    const cache = await caches.open(name);
    for (const request of await cache.keys()) {
      const response = await cache.match(request);
      if (!response) continue;
      const length = Number(response.headers.get('content-length'));
      bytes += Number.isFinite(length) && length > 0 ? length : (await response.blob()).size;
      files += 1;
    }
  }
  return { bytes, files };
}

/** Register once the page has done its first work, so precaching never competes with it; `report`
 *  hears "saving" while the precache fills and "ready" (with the size) once it is complete. */
export function registerServiceWorker(after: Promise<unknown>, report: (s: OfflineState) => void = () => {},
  holdsUserWork: () => boolean = () => false): void {
  if (FROM_SOURCES || !('serviceWorker' in navigator)) return;
  const ready = async () => {
    try {
      report({ state: 'ready', ...await cachedSize() });
    } catch {
      report({ state: 'ready' });
    }
  };
  const watch = (worker: ServiceWorker) => {
    if (worker.state === 'activated') { void ready(); return; }
    report({ state: 'saving' });
    worker.addEventListener('statechange', () => {
      if (worker.state === 'activated') void ready();
      else if (worker.state === 'redundant') report({ state: 'failed' });
    });
  };
  const register = () => {
    const container = navigator.serviceWorker;
    // Set before anything can change it: null on the first visit, whose worker then claims the page.
    let controller = container.controller;
    container.addEventListener('controllerchange', () => {
      // Another release now answers this page's requests (asked here or by another tab): load it.
      if (controller) location.reload();
      controller = container.controller;
    });
    container.register(new URL('sw.js', SITE_ROOT), { scope: SITE_ROOT }).then((registration) => {
      // A worker installed while another is active is a new release: switch to it now, unless this page
      // holds work a reload would lose (a dropped file): then the new release waits for the next visit,
      // and the old worker keeps serving this page the old release's files, never a mix.
      const takeOver = (worker: ServiceWorker) => {
        if (worker.state === 'installed' && registration.active && !holdsUserWork()) worker.postMessage({ type: 'SKIP_WAITING' });
      };
      const follow = (worker: ServiceWorker) => {
        watch(worker);
        takeOver(worker);
        worker.addEventListener('statechange', () => takeOver(worker));
      };
      const pending = registration.installing ?? registration.waiting;
      if (pending) follow(pending);
      else if (registration.active) watch(registration.active);
      registration.addEventListener('updatefound', () => { if (registration.installing) follow(registration.installing); });
      // Chromium's own check after a reload did not come within 30 s in the update test; ask now
      // (with nothing new this changes nothing; offline there is nothing to ask).
      if (controller && navigator.onLine) registration.update().catch(() => {});
    }).catch((err) => {
      console.warn(`offline use is unavailable: ${(err as Error).message}`);
      report({ state: 'failed' });
    });
  };
  void after.finally(() => setTimeout(register, 0));
}
