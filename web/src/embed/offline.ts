// The service worker (built by vite-plugin-pwa, precaching the whole site) is registered only by
// the site's own pages, never by a widget on a host page, whose URL is not the site's scope.
// The page says when it is safe to go offline: the worker's own state change to "activated" comes
// only after its install event has put every precached file in the cache, and the size shown is what
// the caches then hold.
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
export function registerServiceWorker(after: Promise<unknown>, report: (s: OfflineState) => void = () => {}): void {
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
    navigator.serviceWorker.register(new URL('sw.js', SITE_ROOT), { scope: SITE_ROOT }).then((registration) => {
      const pending = registration.installing ?? registration.waiting;
      if (pending) watch(pending);
      else if (registration.active) watch(registration.active);
      registration.addEventListener('updatefound', () => { if (registration.installing) watch(registration.installing); });
    }).catch((err) => {
      console.warn(`offline use is unavailable: ${(err as Error).message}`);
      report({ state: 'failed' });
    });
  };
  void after.finally(() => setTimeout(register, 0));
}
