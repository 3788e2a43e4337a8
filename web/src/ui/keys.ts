// Pure key mapping: which playback action a key press means, given where focus is.

export type KeyAction =
  | { kind: 'toggle' }
  | { kind: 'step'; frames: number }
  | { kind: 'speed'; direction: 1 | -1 }
  | { kind: 'first' }
  | { kind: 'last' }
  | { kind: 'layout' }
  | { kind: 'predict' }
  | { kind: 'sample'; index: number | null }
  | { kind: 'snapshot' }
  | { kind: 'record' };

export interface KeyPress {
  key: string;
  shiftKey?: boolean;
  ctrlKey?: boolean;
  altKey?: boolean;
  metaKey?: boolean;
}

export interface FocusTarget {
  tagName?: string;
  type?: string;
  isContentEditable?: boolean;
}

const TEXT_INPUTS = new Set(['text', 'number', 'search', 'email', 'url', 'tel', 'password', 'date', 'time']);
const NAVIGATION = new Set(['ArrowLeft', 'ArrowRight', 'ArrowUp', 'ArrowDown', 'Home', 'End', 'PageUp', 'PageDown']);

/** Keys the focused control handles itself, so the page must leave alone. */
function ownedByTarget(key: string, target: FocusTarget | null): boolean {
  if (!target) return false;
  if (target.isContentEditable) return true;
  const tag = (target.tagName ?? '').toUpperCase();
  if (tag === 'TEXTAREA' || tag === 'SELECT') return true;
  if (tag === 'INPUT') {
    const type = (target.type ?? 'text').toLowerCase();
    if (TEXT_INPUTS.has(type)) return true;
    if (type === 'range') return NAVIGATION.has(key);
    if (type === 'checkbox' || type === 'radio' || type === 'button' || type === 'submit') {
      return key === ' ' || key === 'Enter' || (type === 'radio' && NAVIGATION.has(key));
    }
  }
  // Space and Enter press a focused button.
  if (tag === 'BUTTON' || tag === 'SUMMARY' || tag === 'A') return key === ' ' || key === 'Enter';
  return false;
}

export function keyAction(e: KeyPress, target: FocusTarget | null): KeyAction | null {
  if (e.ctrlKey || e.altKey || e.metaKey) return null;
  if (ownedByTarget(e.key, target)) return null;
  const big = e.shiftKey ? 10 : 1;
  switch (e.key) {
    case ' ': case 'Spacebar': return { kind: 'toggle' };
    case 'ArrowRight': return { kind: 'step', frames: big };
    case 'ArrowLeft': return { kind: 'step', frames: -big };
    case ']': return { kind: 'speed', direction: 1 };
    case '[': return { kind: 'speed', direction: -1 };
    case 'Home': return { kind: 'first' };
    case 'End': return { kind: 'last' };
    case 'l': case 'L': return { kind: 'layout' };
    case 'p': case 'P': return { kind: 'predict' };
    case 's': case 'S': return { kind: 'snapshot' };
    case 'r': case 'R': return { kind: 'record' };
    case '0': return { kind: 'sample', index: null };
    default:
      if (/^[1-9]$/.test(e.key)) return { kind: 'sample', index: Number(e.key) - 1 };
      return null;
  }
}
