// The service worker (built by vite-plugin-pwa, precaching the whole site) is registered only by
// the site's own pages, never by a widget on a host page, whose URL is not the site's scope.
import { FROM_SOURCES, SITE_ROOT } from './site';

/** Register once the page has done its first work, so precaching never competes with it. */
export function registerServiceWorker(after: Promise<unknown>): void {
  if (FROM_SOURCES || !('serviceWorker' in navigator)) return;
  const register = () => {
    navigator.serviceWorker.register(new URL('sw.js', SITE_ROOT), { scope: SITE_ROOT }).catch((err) => {
      console.warn(`offline use is unavailable: ${(err as Error).message}`);
    });
  };
  void after.finally(() => setTimeout(register, 0));
}
