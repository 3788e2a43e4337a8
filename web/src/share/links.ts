// Turning a state into something to share: a permalink to the full page, an embed snippet for
// the custom element, and an iframe snippet for embed.html.
import type { Manifest } from '../contract/types';
import { encodeState, type ShareState } from './url-state';

export interface EmbedView {
  controls: 'full' | 'minimal';
  autoplay: boolean;
}

function escapeAttr(text: string): string {
  return text.replace(/&/g, '&amp;').replace(/"/g, '&quot;').replace(/</g, '&lt;').replace(/>/g, '&gt;');
}

/** The full page (the site root's index.html) showing this state. */
export function permalink(siteRoot: string, state: ShareState, manifest: Manifest): string {
  const url = new URL(siteRoot);
  url.search = new URLSearchParams(encodeState(state, manifest)).toString();
  return url.href;
}

/** One script include and one tag; attributes are the link's parameters. */
export function embedSnippet(scriptUrl: string, state: ShareState, manifest: Manifest, view: EmbedView): string {
  const attrs = encodeState(state, manifest).map(([k, v]) => `${k}="${escapeAttr(v)}"`);
  attrs.push(`controls="${view.controls}"`);
  if (view.autoplay) attrs.push('autoplay');
  return `<script type="module" src="${escapeAttr(scriptUrl)}"></script>\n`
    + `<motion-futures ${attrs.join(' ')} style="height: 480px"></motion-futures>`;
}

/** The same widget in an iframe: embed.html with the link's parameters plus the view options; as wide as its
 * column up to 720 px at 3 : 2 (the README's snippet), so it never widens a phone page. */
export function iframeSnippet(siteRoot: string, state: ShareState, manifest: Manifest, view: EmbedView): string {
  const url = new URL('embed.html', siteRoot);
  const q = new URLSearchParams(encodeState(state, manifest));
  q.set('controls', view.controls);
  if (view.autoplay) q.set('autoplay', '1');
  url.search = q.toString();
  return `<iframe src="${escapeAttr(url.href)}" title="motion-futures" style="width: 100%; max-width: 720px; aspect-ratio: 3 / 2; min-height: 400px; border: 0" allow="clipboard-write"></iframe>`;
}
