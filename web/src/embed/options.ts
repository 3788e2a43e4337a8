// Options from an element's attributes and, for a widget that is the page, the page URL (which
// wins). The same names work in both places: see README "Embedding".
import type { ViewOptions } from '../ui/app';

/** Attributes any element may carry that are not options. */
const HTML_ATTRIBUTES = new Set(['id', 'class', 'style', 'tabindex', 'title', 'lang', 'dir', 'hidden', 'slot', 'part', 'role', 'page']);

export function attributeParams(host: Element): [string, string][] {
  return host.getAttributeNames()
    .filter((n) => !HTML_ATTRIBUTES.has(n) && !/^(data|aria)-|^on/.test(n))
    .map((n) => [n, host.getAttribute(n) ?? '']);
}

/** A boolean option: present without a value, 1/true/yes, or 0/false/no. */
export function flag(value: string | undefined, fallback: boolean): boolean {
  if (value === undefined) return fallback;
  const v = value.trim().toLowerCase();
  if (['', '1', 'true', 'yes', 'on'].includes(v)) return true;
  if (['0', 'false', 'no', 'off'].includes(v)) return false;
  return fallback;
}

export function viewOptions(params: [string, string][], page: boolean): ViewOptions {
  const q = new Map(params);
  return {
    controls: q.get('controls') === 'full' ? 'full' : 'minimal',
    autoplay: flag(q.get('autoplay'), false),
    autoPredict: flag(q.get('predict'), true),
    page,
  };
}

/** The page URL's view options, which stay in the URL when the state part is rewritten. */
export function viewQuery(search: string): [string, string][] {
  return [...new URLSearchParams(search)].filter(([k]) => ['controls', 'autoplay', 'predict'].includes(k));
}
