// Which window of the current clip is the history: its start frame, with the split it falls in.
import type { Motion } from '../motion/clip';
import { movingStart } from '../motion/moving-start';
import { el } from './dom';

export interface HistoryPicker {
  root: HTMLElement;
  /** Set the clip and the history length; keeps the start when it still fits. `title`: the clip's
   *  readable name (ui/clip-name.ts), else its name. */
  setClip(m: Motion | null, historyFrames: number, title?: string): void;
  start(): number;
  setStart(f: number): void;
}

/** The default start: the beginning of the test part when there is one, else frame 0, moved past a
 *  standing start when the history still fits in that part (motion/moving-start.ts). */
export function defaultStart(m: Motion, historyFrames: number): number {
  const [a, b] = m.test.find(([s, e]) => e - s >= historyFrames) ?? [0, m.frames];
  const moving = movingStart(m.positions, m.frames, m.joints, m.fps, a);
  return moving + historyFrames <= b ? moving : a;
}

/** Which part of the split a window [a, b) lies in. */
export function splitLabel(m: Motion, a: number, b: number): string {
  if (m.origin?.kind === 'dropped-file') return `from your file ${m.origin.file}`;
  const inside = (ranges: [number, number][]) => ranges.some(([s, e]) => a >= s && b <= e);
  if (inside(m.test)) return 'test part';
  if (inside(m.train)) return 'training part (in-sample)';
  return 'crosses the train/test boundary';
}

export function mountHistoryPicker(onChange: () => void): HistoryPicker {
  const input = el('input', { type: 'number', id: 'history-start', min: 0, step: 1, value: '0' });
  const range = el('input', { type: 'range', id: 'history-start-range', min: 0, step: 1, value: '0', 'aria-label': 'History start frame' });
  const note = el('p', { class: 'muted history-note', 'aria-live': 'polite' });
  let motion: Motion | null = null;
  let n = 1;
  let title = '';
  const update = () => {
    if (!motion) { note.textContent = 'Pick a clip first.'; return; }
    const s = Number(input.value);
    note.textContent = `History: frames ${s}–${s + n - 1} of ${title} (${(n / motion.fps).toFixed(2)} s, ${splitLabel(motion, s, s + n)}).`;
  };
  const clamp = (v: number) => Math.max(0, Math.min(Number(input.max) || 0, Math.round(v)));
  input.addEventListener('change', () => { input.value = String(clamp(Number(input.value))); range.value = input.value; update(); onChange(); });
  range.addEventListener('input', () => { input.value = range.value; update(); });
  range.addEventListener('change', () => onChange());
  const root = el('div', { class: 'control-row history-picker' },
    el('label', { for: 'history-start' }, 'History start frame'),
    el('div', { class: 'range-row' }, range, input), note);
  return {
    root,
    setClip(m, historyFrames, readable) {
      const keep = motion?.name === m?.name ? Number(input.value) : null;
      motion = m;
      title = readable ?? m?.name ?? '';
      n = historyFrames;
      const max = m ? Math.max(0, m.frames - historyFrames) : 0;
      input.max = range.max = String(max);
      const start = m ? (keep !== null && keep <= max ? keep : defaultStart(m, historyFrames)) : 0;
      input.value = range.value = String(start);
      input.disabled = range.disabled = !m || m.frames < historyFrames;
      update();
      if (m && m.frames < historyFrames) note.textContent = `${m.name} has ${m.frames} frames; this model needs ${historyFrames} for its history.`;
    },
    start: () => Number(input.value),
    setStart(f) { input.value = range.value = String(clamp(f)); update(); },
  };
}
