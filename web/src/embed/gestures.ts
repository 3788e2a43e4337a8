// On someone else's page the widget must not take the page's scrolling, as embedded maps do not:
// the wheel scrolls the page unless ctrl/⌘ is held or the widget has focus (a click into it gives it
// focus), one finger scrolls the page, two fingers orbit. A one-line hint says how, when a gesture was
// let through to the page. The orbit controls (three.js OrbitControls on the canvas) see only what
// is meant for them: the listeners here sit on the canvas's container and stop the rest in the
// capture phase, before it reaches the canvas.

/** Mac keyboards say ⌘ for the key that zooms. */
const MOD = /Mac|iPhone|iPad/.test(navigator.platform) ? '⌘' : 'Ctrl';
export const WHEEL_HINT = `${MOD} + scroll to zoom, or click the stage first`;
export const TOUCH_HINT = 'Use two fingers to turn the view';
const HINT_MS = 1600;

/** Keep the page's scrolling over `stage` (the viewer's container); returns the undo. */
export function cooperativeGestures(host: HTMLElement, stage: HTMLElement, hint: HTMLElement): () => void {
  let timer = 0;
  const say = (text: string) => {
    hint.textContent = text;
    hint.hidden = false;
    clearTimeout(timer);
    timer = window.setTimeout(() => { hint.hidden = true; }, HINT_MS);
  };
  const wheel = (e: WheelEvent) => {
    if (e.ctrlKey || e.metaKey || host.matches(':focus-within')) { hint.hidden = true; return; }
    e.stopPropagation(); // the orbit controls never see it, so the browser scrolls the page
    say(WHEEL_HINT);
  };
  // The canvas allows the browser's one-finger pan (widget.css: touch-action); a gesture of two
  // fingers is kept from the browser. The orbit controls see one finger only, the first on the canvas
  // (another may be on a figure's label), and its moves only while a second finger is down: for one
  // pointer they turn the view (for two they would dolly and pan), and a lone finger's moves before
  // the browser takes the pan must not turn it. Its down and up still pass, so a tap picks a figure.
  const down = new Set<number>();
  let first: number | null = null;
  const touches = (e: TouchEvent) => {
    if (e.touches.length >= 2) { if (e.cancelable) e.preventDefault(); hint.hidden = true; }
    else if (e.type === 'touchmove') say(TOUCH_HINT);
  };
  const pointer = (e: PointerEvent) => {
    if (e.pointerType !== 'touch') return;
    const ends = e.type === 'pointerup' || e.type === 'pointercancel';
    if (e.type === 'pointerdown') {
      down.add(e.pointerId);
      if (first === null && e.target instanceof HTMLCanvasElement) first = e.pointerId;
    } else if (ends) down.delete(e.pointerId);
    if (e.pointerId !== first || (e.type === 'pointermove' && down.size < 2)) e.stopPropagation();
    if (ends && e.pointerId === first) first = null;
  };
  const capture = { capture: true, passive: false } as const;
  stage.addEventListener('wheel', wheel, capture);
  stage.addEventListener('touchstart', touches, capture);
  stage.addEventListener('touchmove', touches, capture);
  const kinds = ['pointerdown', 'pointermove', 'pointerup', 'pointercancel'] as const;
  for (const k of kinds) stage.addEventListener(k, pointer, true);
  return () => {
    clearTimeout(timer);
    stage.removeEventListener('wheel', wheel, capture);
    stage.removeEventListener('touchstart', touches, capture);
    stage.removeEventListener('touchmove', touches, capture);
    for (const k of kinds) stage.removeEventListener(k, pointer, true);
  };
}
