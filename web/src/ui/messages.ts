// The message banner: load and contract errors, and the last-resort handler for uncaught errors.
import { el } from './dom';

export type MessageLevel = 'error' | 'warning' | 'info';

export class MessageBanner {
  private readonly list: HTMLUListElement;
  private readonly byKey = new Map<string, HTMLLIElement>();

  constructor(container: HTMLElement) {
    this.list = el('ul', { class: 'messages-list' });
    container.replaceChildren(this.list);
  }

  /** Show a message; a message with the same key replaces the previous one. */
  show(text: string, level: MessageLevel = 'error', key?: string): void {
    if (key) this.clear(key);
    const dismiss = el('button', { type: 'button', class: 'message-dismiss', 'aria-label': 'Dismiss message' }, '×');
    const item = el('li', { class: `message message-${level}`, role: level === 'info' ? 'status' : 'alert' },
      el('span', { class: 'message-text' }, text), dismiss);
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
