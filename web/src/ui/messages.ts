// The message banner (one sentence per message, details behind a toggle, over the stage) and the
// last-resort handler for uncaught errors. A message naming the bring-your-own guide links to it.
import { el } from './dom';
import { linkified } from './guide-link';

export type MessageLevel = 'error' | 'warning' | 'info';

/** The longest summary shown on one line; longer messages keep their whole text behind "Details". */
export const SUMMARY_CHARS = 120;

/**
 * One sentence for the stage, and the whole text when the sentence leaves something out: the first
 * sentence when it is short, else the text up to the last clause boundary (': ' or '; ') that keeps
 * it short, else its first words.
 */
export function summarise(text: string): { summary: string; details: string | null } {
  const flat = text.replace(/\s+/g, ' ').trim();
  const sentence = /^(.+?[.!?])(\s|$)/.exec(flat)?.[1] ?? flat;
  if (sentence.length <= SUMMARY_CHARS) return { summary: sentence, details: sentence === flat ? null : text };
  const head = flat.slice(0, SUMMARY_CHARS);
  const cut = Math.max(head.lastIndexOf(': '), head.lastIndexOf('; '));
  if (cut >= 20) return { summary: `${head.slice(0, cut)}.`, details: text };
  const word = head.lastIndexOf(' ');
  return { summary: `${head.slice(0, word > 20 ? word : SUMMARY_CHARS)}…`, details: text };
}

/**
 * The message banner: load and contract errors, link problems and warnings, each one sentence with
 * the rest behind a "Details" toggle. It lies over the top of the stage, so a message never moves it.
 */
export class MessageBanner {
  private readonly list: HTMLUListElement;
  private readonly byKey = new Map<string, HTMLLIElement>();

  constructor(container: HTMLElement) {
    this.list = el('ul', { class: 'messages-list' });
    container.replaceChildren(this.list);
  }

  /** Show a message; a message with the same key replaces the previous one. `details` (or, when
   *  absent, whatever one sentence of `text` leaves out) goes behind a toggle. */
  show(text: string, level: MessageLevel = 'error', key?: string, details?: string): void {
    if (key) this.clear(key);
    const short = summarise(text);
    const more = details ?? short.details;
    const dismiss = el('button', { type: 'button', class: 'message-dismiss', 'aria-label': 'Dismiss message' }, '×');
    const item = el('li', { class: `message message-${level}`, role: level === 'info' ? 'status' : 'alert' },
      el('span', { class: 'message-text' }, ...linkified(short.summary)),
      more ? el('details', { class: 'message-details' }, el('summary', {}, 'Details'), el('p', {}, ...linkified(more))) : null,
      dismiss);
    dismiss.addEventListener('click', () => { item.remove(); if (key) this.byKey.delete(key); });
    if (key) this.byKey.set(key, item);
    this.list.append(item);
  }

  error(err: unknown, key?: string): void {
    this.show(describeError(err), 'error', key);
  }

  clear(key?: string): void {
    if (key === undefined) { this.list.replaceChildren(); this.byKey.clear(); return; }
    this.byKey.get(key)?.remove();
    this.byKey.delete(key);
  }
}

export function describeError(err: unknown): string {
  if (err instanceof Error) return err.name === 'ContractError' || err.name === 'Error' ? err.message : `${err.name}: ${err.message}`;
  return String(err);
}

/** Uncaught errors and rejections go to the banner instead of leaving a silently broken page. */
export function catchUncaught(banner: MessageBanner): void {
  window.addEventListener('error', (e) => {
    banner.show(`Unexpected error: ${e.error ? describeError(e.error) : e.message}`, 'error');
  });
  window.addEventListener('unhandledrejection', (e) => {
    banner.show(`Unexpected error: ${describeError(e.reason)}`, 'error');
  });
}
