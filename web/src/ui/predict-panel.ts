// The predictor's inputs: model, history window, seed, the model's own controls, and Predict.
// K keeps its value across model switches (clamped to the new model's range), so the first view's
// K = 5 stays; a deterministic model (no K) disables the seed and says why. "Plant feet" is the
// site's, not a model's (predictor/foot-plant.ts): on, the feet on the floor carry the root.
import type { Manifest, ModelEntry } from '../contract/types';
import { MAX_SEED } from '../rng/prng';
import { mountControls, type ControlsView } from './controls';
import { el, type StatusSink } from './dom';
import { mountHistoryPicker, type HistoryPicker } from './history-picker';

export interface PredictPanel {
  model(): ModelEntry;
  history: HistoryPicker;
  controls(): ControlsView;
  seed(): number;
  /** Feet on the floor carry the root (predictor/foot-plant.ts); off: the method's own root travel. */
  plantFeet(): boolean;
  setPlantFeet(on: boolean): void;
  /** Choose a model by id (as if picked in the list); false when there is none. */
  selectModel(id: string): boolean;
  setSeed(seed: number): void;
  setBusy(text: string | null, progress?: number): void;
  setStatus(text: string): void;
}

export function mountPredictPanel(container: HTMLElement, manifest: Manifest, initialModel: string | undefined, handlers: {
  onModel(entry: ModelEntry): void; onPredict(): void; onChange(): void; status: StatusSink;
}): PredictPanel {
  const models = manifest.models;
  const select = el('select', { id: 'model-select' }, ...models.map((m) => el('option', { value: m.id }, m.label)));
  if (initialModel && models.some((m) => m.id === initialModel)) select.value = initialModel;
  const description = el('p', { class: 'muted model-description' });
  const history = mountHistoryPicker(handlers.onChange);
  // Wide enough for every seed (up to 10 digits).
  const seedInput = el('input', { type: 'number', id: 'seed', class: 'seed-input', min: 0, max: MAX_SEED, step: 1, value: '1' });
  const dice = el('button', { type: 'button', class: 'text-button', id: 'new-seed', title: 'A new random seed' }, 'New seed');
  const seedNote = el('p', { class: 'muted control-help seed-note', id: 'seed-note', hidden: true });
  const controlsBox = el('div', {});
  const feet = el('input', { type: 'checkbox', id: 'plant-feet', checked: true, 'aria-describedby': 'plant-feet-help' });
  const feetRow = el('div', { class: 'control-row' },
    el('label', { class: 'checkbox-label' }, feet, ' Plant feet'),
    el('p', { class: 'muted control-help', id: 'plant-feet-help' },
      'A foot on the floor stays put and carries the body (a post-process of this site). Off: the root travels as the method predicts it.'));
  feet.addEventListener('change', () => handlers.onChange());
  const predict = el('button', { type: 'button', class: 'primary-button', id: 'predict' }, 'Predict');
  const progress = el('progress', { class: 'load-progress', max: 1, hidden: true });
  const status = el('p', { class: 'muted predict-status', role: 'status', 'aria-live': 'polite' });
  let controls: ControlsView = mountControls([], manifest.actions, handlers.onChange);
  /** The last K a model with K had: the next such model starts from it. */
  let keptK: number | null = null;

  const current = () => models.find((m) => m.id === select.value) ?? models[0];
  const showModel = () => {
    const m = current();
    const before = controls.values().k;
    if (typeof before === 'number') keptK = before;
    description.textContent = m.description ?? '';
    controls = mountControls(m.controls, manifest.actions, handlers.onChange);
    const k = m.controls.find((c) => c.id === 'k');
    if (k && keptK !== null) controls.set('k', Math.max(k.min ?? 1, Math.min(k.max ?? keptK, keptK)));
    controlsBox.replaceChildren(controls.root);
    // Without K the model draws one future, the same for every seed.
    const deterministic = !k;
    seedInput.disabled = dice.disabled = deterministic;
    seedNote.hidden = !deterministic;
    seedNote.textContent = deterministic ? `${m.label} is deterministic: every seed gives the same future, so the seed is off.` : '';
    if (deterministic) seedInput.setAttribute('aria-describedby', 'seed-note'); else seedInput.removeAttribute('aria-describedby');
    handlers.onModel(m);
  };
  select.addEventListener('change', () => { showModel(); handlers.onChange(); });
  seedInput.addEventListener('change', () => {
    const v = Math.max(0, Math.min(MAX_SEED, Math.round(Number(seedInput.value) || 0)));
    seedInput.value = String(v);
    handlers.onChange();
  });
  dice.addEventListener('click', () => { seedInput.value = String(Math.floor(Math.random() * MAX_SEED)); handlers.onChange(); });
  predict.addEventListener('click', () => handlers.onPredict());

  container.replaceChildren(
    el('div', { class: 'control-row' }, el('label', { for: 'model-select' }, 'Model'), select, description),
    history.root,
    el('div', { class: 'control-row seed-row' }, el('label', { for: 'seed' }, 'Seed'), el('div', { class: 'range-row' }, seedInput, dice), seedNote),
    controlsBox,
    feetRow,
    el('div', { class: 'predict-row' }, predict, el('span', { class: 'muted' }, 'or press P; any change predicts again')),
    progress, status,
  );
  showModel();
  return {
    model: current,
    history,
    controls: () => controls,
    seed: () => Number(seedInput.value),
    plantFeet: () => feet.checked,
    setPlantFeet(on) { feet.checked = on; },
    selectModel(id) {
      if (!models.some((m) => m.id === id)) return false;
      if (select.value !== id) { select.value = id; showModel(); }
      return true;
    },
    setSeed(seed) { seedInput.value = String(Math.max(0, Math.min(MAX_SEED, Math.round(seed)))); },
    setBusy(text, fraction) {
      predict.disabled = text !== null && fraction !== undefined;
      progress.hidden = fraction === undefined;
      if (fraction !== undefined) progress.value = fraction;
      if (text !== null) status.textContent = text;
      handlers.status('predictStatus', text === null ? 'idle' : 'busy');
    },
    setStatus(text) { status.textContent = text; },
  };
}
