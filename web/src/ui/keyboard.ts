// Global playback shortcuts (see keys.ts for the mapping).
import { keyAction, type KeyAction } from './keys';

export function bindKeyboard(target: Window, perform: (action: KeyAction) => void): () => void {
  const onKey = (e: KeyboardEvent) => {
    if (e.defaultPrevented || e.isComposing) return;
    const action = keyAction(e, document.activeElement as HTMLElement | null);
    if (!action) return;
    e.preventDefault(); // Space would scroll the page
    perform(action);
  };
  target.addEventListener('keydown', onKey);
  return () => target.removeEventListener('keydown', onKey);
}
