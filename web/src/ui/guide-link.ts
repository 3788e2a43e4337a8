// Links to the served bring-your-own guide (web/bring-your-own.html, from docs/BRING_YOUR_OWN.md) in
// message text: the readers' messages name the page ("see bring-your-own.html#joint-maps"), and the
// import panel and the banner turn that name into a link a visitor can follow, from the site or from a
// widget on a host page (the URL is the site's, not the host's).
import { SITE_ROOT } from '../embed/site';
import { el } from './dom';

export const GUIDE_PAGE = 'bring-your-own.html';

/** The guide's URL on this site, with an optional #section. */
export function guideUrl(anchor = '', root: string = SITE_ROOT): string {
  return new URL(`${GUIDE_PAGE}${anchor}`, root).href;
}

export type Segment = { text: string } | { text: string; anchor: string };

// "bring-your-own.html" with an optional #section, and the repository path the Python messages name
const GUIDE_NAME = /bring-your-own\.html(#[A-Za-z0-9_-]+)?|docs\/BRING_YOUR_OWN\.md(#[A-Za-z0-9_-]+)?/g;

/** Text cut into plain runs and mentions of the guide (each with its #section, or ''). */
export function guideSegments(text: string): Segment[] {
  const out: Segment[] = [];
  let at = 0;
  for (const m of text.matchAll(GUIDE_NAME)) {
    if (m.index > at) out.push({ text: text.slice(at, m.index) });
    out.push({ text: m[0], anchor: m[1] ?? m[2] ?? '' });
    at = m.index + m[0].length;
  }
  if (at < text.length || !out.length) out.push({ text: text.slice(at) });
  return out;
}

/** The text as nodes, each mention of the guide a link to it (in a new tab: the page keeps its motion). */
export function linkified(text: string, root: string = SITE_ROOT): (Node | string)[] {
  return guideSegments(text).map((s) => ('anchor' in s
    ? el('a', { href: guideUrl(s.anchor, root), target: '_blank', rel: 'noopener', class: 'guide-link' }, s.text)
    : s.text));
}
