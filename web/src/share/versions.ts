// Old permalinks name the version that made them. A release unpacks into its own folder
// (motion-futures-<version>/, scripts/release.mjs), so a host that keeps releases side by side
// serves an old version next to the new one; this finds it.

export const RELEASE_PREFIX = 'motion-futures-';

/** Where release `version` would sit beside this site, or null for a malformed version. */
export function releaseUrl(siteRoot: string, version: string): string | null {
  if (!/^\d+\.\d+\.\d+([-+][0-9A-Za-z.-]+)?$/.test(version)) return null;
  return new URL(`../${RELEASE_PREFIX}${version}/`, siteRoot).href;
}

/**
 * The URL of release `version` when the host serves it beside this site, else null. Every build
 * carries version.json (vite.config.ts), so a server that answers any path with a page is not
 * mistaken for an old release.
 */
export async function olderRelease(siteRoot: string, version: string, fetcher: typeof fetch = fetch): Promise<string | null> {
  const url = releaseUrl(siteRoot, version);
  if (!url || url === siteRoot) return null;
  try {
    const res = await fetcher(`${url}version.json`);
    const doc = res.ok ? await res.json() as { version?: unknown } : null;
    return doc?.version === version ? url : null;
  } catch {
    return null; // offline, no such release, or not JSON
  }
}
