// Options from an element's attributes and, for a widget that is the page, the page URL (which
// wins). The same names work in both places: see README "Embedding".
import type { ViewOptions } from '../ui/app';
import type { Theme } from './widget';

/** Options of the element alone: not part of a link's state, kept in a page URL like the view options. */
export const ELEMENT_KEYS = ['theme', 'offline'] as const;

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

/** light, dark, or (anything else, or nothing) auto: the reader's system. */
export function theme(params: [string, string][]): Theme {
  const v = new Map(params).get('theme')?.trim().toLowerCase();
  return v === 'light' || v === 'dark' ? v : 'auto';
}

/** The host asked for offline use (`offline` attribute, `offline=1` in an iframe's URL). */
export function offlineAsked(params: [string, string][]): boolean {
  return flag(new Map(params).get('offline'), false);
}

/** The params without the element's own options: what the link state is read from. */
export function linkParams(params: [string, string][]): [string, string][] {
  return params.filter(([k]) => !(ELEMENT_KEYS as readonly string[]).includes(k));
}

/** The page URL's view options, which stay in the URL when the state part is rewritten. */
export function viewQuery(search: string): [string, string][] {
  return [...new URLSearchParams(search)].filter(([k]) => ['controls', 'autoplay', 'predict', ...ELEMENT_KEYS].includes(k));
}
