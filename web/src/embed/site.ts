// Where the site lives, from this script's own URL rather than the page's, so the widget works
// on a host page anywhere on the origin (or under any sub-path).
// The build puts every script chunk in assets/ (vite.config.ts), so the root is one level up;
// the dev server serves this file from src/embed/. (import.meta.env.DEV cannot tell the two
// apart: it follows NODE_ENV, which test runners set for builds too.)
const here = new URL(import.meta.url);

/** True when the dev server runs the sources (no service worker, no built entry script). */
export const FROM_SOURCES: boolean = /\/src\/embed\/site\.ts$/.test(here.pathname);

/** The site root URL, ending in '/'. */
export const SITE_ROOT: string = new URL(FROM_SOURCES ? '../../' : '../', here).href;

/** The one script a host page includes (a stable name; vite.config.ts gives the entry this file name). */
export const EMBED_SCRIPT: string = new URL(FROM_SOURCES ? 'src/embed/element.ts' : 'assets/motion-futures.js', SITE_ROOT).href;
