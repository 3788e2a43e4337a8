// Renders a model's controls from the manifest; the page never needs to know the method.
import type { ControlSpec } from '../contract/types';
import { mountActionSequence } from './action-sequence';
import { el } from './dom';

export type ControlValue = number | boolean | string[];

export interface ControlsView {
  root: HTMLElement;
  values(): Record<string, ControlValue>;
  set(id: string, value: ControlValue): void;
}

function decimals(step: number | undefined): number {
  if (!step) return 2;
  const s = String(step);
  return s.includes('.') ? s.length - s.indexOf('.') - 1 : 0;
}

export function mountControls(specs: ControlSpec[], actions: string[], onChange: () => void): ControlsView {
  const getters = new Map<string, () => ControlValue>();
  const setters = new Map<string, (v: ControlValue) => void>();
  const rows: HTMLElement[] = [];
  for (const spec of specs) {
    const id = `control-${spec.id}`;
    const help = spec.help ? el('p', { class: 'control-help muted', id: `${id}-help` }, spec.help) : null;
    if (spec.type === 'actions') {
      const seq = mountActionSequence(id, spec.label, actions, (spec.default as string[]) ?? [], spec.max_length ?? 5, onChange);
      getters.set(spec.id, () => seq.value());
      setters.set(spec.id, (v) => seq.set(v as string[]));
      rows.push(el('div', { class: 'control-row' }, seq.root, help));
    } else if (spec.type === 'bool') {
      const input = el('input', { type: 'checkbox', id, checked: Boolean(spec.default), 'aria-describedby': help ? `${id}-help` : undefined });
      input.addEventListener('change', onChange);
      getters.set(spec.id, () => input.checked);
      setters.set(spec.id, (v) => { input.checked = Boolean(v); });
      rows.push(el('div', { class: 'control-row control-bool' }, el('label', { for: id }, input, ` ${spec.label}`), help));
    } else if (spec.type === 'int') {
      const input = el('input', { type: 'number', id, min: spec.min, max: spec.max, step: spec.step ?? 1, value: String(spec.default),
        'aria-describedby': help ? `${id}-help` : undefined });
      input.addEventListener('change', onChange);
      getters.set(spec.id, () => Number(input.value));
      setters.set(spec.id, (v) => { input.value = String(v); });
      rows.push(el('div', { class: 'control-row' }, el('label', { for: id }, spec.label), input, help));
    } else {
      const digits = decimals(spec.step);
      const input = el('input', { type: 'range', id, min: spec.min, max: spec.max, step: spec.step ?? 'any', value: String(spec.default),
        'aria-describedby': help ? `${id}-help` : undefined });
      const out = el('output', { for: id, class: 'control-value' }, Number(spec.default).toFixed(digits));
      input.addEventListener('input', () => { out.textContent = Number(input.value).toFixed(digits); });
      input.addEventListener('change', onChange);
      getters.set(spec.id, () => Number(input.value));
      setters.set(spec.id, (v) => { input.value = String(v); out.textContent = Number(v).toFixed(digits); });
      rows.push(el('div', { class: 'control-row' }, el('label', { for: id }, spec.label), el('div', { class: 'range-row' }, input, out), help));
    }
  }
  return {
    root: el('div', { class: 'controls' }, ...rows),
    values() {
      const out: Record<string, ControlValue> = {};
      for (const [id, get] of getters) out[id] = get();
      return out;
    },
    set(id, value) { setters.get(id)?.(value); },
  };
}
