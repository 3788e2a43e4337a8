// The "How it works" page: five figures, each driven by the predictors' own TypeScript. Figures
// mount one after another; one that fails says so in its own place and the others still work.
import './explainer.css';
import { el } from '../ui/dom';
import { loadExplainerData, type ExplainerData } from './data';
import { mountDctFigure } from './dct-figure';
import { mountKeyposeFigure } from './keypose-figure';
import { mountPriorFigure } from './prior-figure';
import { mountTemperatureFigure } from './temperature-figure';
import { mountVarianceFigure } from './variance-figure';

const FIGURES: [string, (host: HTMLElement, data: ExplainerData) => Promise<void>][] = [
  ['the DCT smoothness figure', mountDctFigure],
  ['the variance stopping figure', mountVarianceFigure],
  ['the keypose extraction figure', mountKeyposeFigure],
  ['the temperature figure', mountTemperatureFigure],
  ['the prior figure', mountPriorFigure],
];

async function main(): Promise<void> {
  const host = document.getElementById('figures');
  if (!host) return;
  document.body.dataset.status = 'loading';
  let data: ExplainerData;
  try {
    data = await loadExplainerData(new URL('./', document.baseURI).href);
  } catch (err) {
    host.replaceChildren(el('p', { class: 'error', role: 'alert' }, `The clips could not be loaded, so the figures cannot be drawn: ${(err as Error).message}`));
    document.body.dataset.status = 'error';
    return;
  }
  host.replaceChildren();
  if (data.manifestProblem) {
    host.append(el('p', { class: 'error', role: 'alert' }, `The models could not be loaded (${data.manifestProblem}); figures that need a model say so.`));
  }
  for (const [name, mount] of FIGURES) {
    try {
      await mount(host, data);
    } catch (err) {
      host.append(el('p', { class: 'error', role: 'alert' }, `Could not draw ${name}: ${(err as Error).message}`));
    }
  }
  document.body.dataset.status = 'ready';
}

void main();
