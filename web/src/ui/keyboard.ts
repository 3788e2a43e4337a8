// Playback shortcuts for one widget instance (see keys.ts for the mapping). Keys act on the
// instance that has focus; the page's own widget also takes keys pressed while nothing is focused.
import { keyAction, type KeyAction } from './keys';

export interface KeyboardOptions {
  /** Also act on keys pressed with nothing focused (the page's body): for a widget that is the page. */
  unfocused?: boolean;
}

export function bindKeyboard(root: HTMLElement, perform: (action: KeyAction) => void, options: KeyboardOptions = {}): () => void {
  const onKey = (e: KeyboardEvent) => {
    if (e.defaultPrevented || e.isComposing) return;
    // The element that really has focus, inside the widget's shadow root.
    const target = (e.composedPath()[0] ?? null) as HTMLElement | null;
    const action = keyAction(e, target instanceof Element ? target : null);
    if (!action) return;
    e.preventDefault(); // Space would scroll the page
    perform(action);
  };
  const onPageKey = (e: KeyboardEvent) => {
    if (e.target === document.body || e.target === document.documentElement) onKey(e);
  };
  root.addEventListener('keydown', onKey);
  if (options.unfocused) window.addEventListener('keydown', onPageKey);
  return () => {
    root.removeEventListener('keydown', onKey);
    window.removeEventListener('keydown', onPageKey);
  };
}
