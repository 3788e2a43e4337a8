// The Results page: fetch results.json next to the page (works under any sub-path) and render it.
import './results.css';
import { parseResults } from './data';
import { el } from './dom';
import { renderResults } from './render';

async function main(): Promise<void> {
  const root = document.getElementById('results');
  if (!root) return;
  document.body.dataset.status = 'loading';
  try {
    const res = await fetch(new URL('results.json', document.baseURI));
    if (!res.ok) throw new Error(`results.json could not be loaded (HTTP ${res.status}); run \`python -m export evaluate\``);
    renderResults(root, parseResults(await res.json()));
    document.body.dataset.status = 'ready';
  } catch (err) {
    root.replaceChildren(el('p', { class: 'error', role: 'alert' }, err instanceof Error ? err.message : String(err)));
    document.body.dataset.status = 'error';
  }
}

void main();
