// How figures are arranged (overlaid / side by side) and a way back to the default camera.
import type { LayoutMode } from '../viewer/layout';
import { el } from './dom';
import { icon } from './icons';

export interface ViewPanel {
  setLayout(mode: LayoutMode): void;
}

const OPTIONS: { mode: LayoutMode; label: string }[] = [
  { mode: 'overlay', label: 'Overlaid' },
  { mode: 'side', label: 'Side by side' },
];

export function mountViewPanel(
  container: HTMLElement, initial: LayoutMode,
  handlers: { onLayout(mode: LayoutMode): void; onResetView(): void },
): ViewPanel {
  const radios = OPTIONS.map(({ mode, label }) => {
    const input = el('input', { type: 'radio', name: 'layout', value: mode, checked: mode === initial });
    input.addEventListener('change', () => { if (input.checked) handlers.onLayout(mode); });
    return { mode, input, label: el('label', { class: 'segment' }, input, el('span', {}, label)) };
  });
  const reset = el('button', { type: 'button', class: 'text-button', title: 'Reset the camera' }, icon('reset'), 'Reset view');
  reset.addEventListener('click', () => handlers.onResetView());
  container.replaceChildren(
    el('fieldset', { class: 'segmented' }, el('legend', {}, 'Layout (L)'), ...radios.map((r) => r.label)),
    reset,
  );
  return {
    setLayout(mode) { for (const r of radios) r.input.checked = r.mode === mode; },
  };
}
