// The Model card page: the data, the served models, what they can and cannot do (numbers read from
// results.json when the page runs), known failure modes, and how to cite. docs/MODEL_CARD.md is written
// from the same results.json by the evaluation (export/eval/card.py), with the same five-line summary.
import '../explainer/page.css';
import './model-card.css';
import type { ClipIndex, Manifest } from '../contract/types';
import { fetchContract } from '../contract/validate';
import { sharedManifest } from '../embed/shared';
import { parseResults, type Results } from '../results/data';
import { cell } from '../results/format';
import { SITE_VERSION } from '../share/version';
import { el } from '../ui/dom';
import { cardColumns, cardSummary, classifierCaveats, dataSummary, failureModes, findings, mergeFindings, PAPERS_BIBTEX, projectBibtex, staleModels, type Finding, type Verdict } from './card';

const pretty = (s: string) => s.replace(/_/g, ' ');
const PAPERS: Record<string, string> = {
  wat: 'Mao, Liu, Salzmann, CVPR 2022',
  lcp_vae: 'Aliakbarian et al., ICCV 2021',
  keyposes: 'Kiciroglu, Wang, Salzmann, Fua, 3DV 2022',
  regression: 'baseline',
  zero_velocity: 'baseline',
};

function section(id: string, title: string, ...children: (Node | string | null)[]): HTMLElement {
  return el('section', { class: 'card-section', id, 'aria-labelledby': `${id}-title` }, el('h2', { id: `${id}-title` }, title), ...children);
}

function dataSection(index: ClipIndex): HTMLElement {
  const d = dataSummary(index);
  const rows = index.clips.map((c) => el('tr', {},
    el('th', { scope: 'row' }, pretty(c.name)), el('td', {}, pretty(c.action)), el('td', { class: 'num' }, String(c.frames)),
    el('td', { class: 'num' }, (c.frames / index.fps).toFixed(2)),
    el('td', {}, c.role === 'test' ? 'test' : c.test.length ? `train, test from frame ${c.test[0][0]}` : 'train')));
  const testOnly = Object.entries(d.testOnly).map(([a, names]) => `${names.length} of ${pretty(a)}`).join(', ');
  const people = (role: (r: string) => boolean) => [...new Set(index.clips.filter((c) => c.subject !== undefined && role(c.role)).map((c) => String(c.subject)))];
  const testPeople = people((r) => r === 'test');
  const trainPeople = people((r) => r !== 'test');
  const datasets = [...new Set(index.clips.map((c) => c.dataset).filter((x): x is string => Boolean(x)))];
  return section('data', 'The data',
    el('p', {}, `${d.clips} motion clips, ${d.seconds.toFixed(1)} s in all at ${d.fps} frames per second, of ${d.actions} actions; `,
      `${d.trainSeconds.toFixed(1)} s are for training and ${d.testSeconds.toFixed(1)} s for testing`,
      testPeople.length ? `: the split keeps each person on one side, and the test clips are by ${testPeople.length} people no model saw `
        + `(${trainPeople.length} others are trained on).` : '.',
      testOnly ? ` Test clips per action: ${testOnly}.` : '',
      ' Positions are 18 joints in metres, y up, in the world frame: the root travels over the floor.'),
    el('details', {}, el('summary', {}, 'How the clips are split'), el('ul', {}, ...index.split_rules.map((r) => el('li', {}, r)))),
    el('p', {}, `Sources: ${datasets.length ? datasets.join('; ') : 'not stated'}. `,
      el('a', { href: './DATA_NOTICE.md' }, 'DATA_NOTICE.md'), ' has every source with its licence; the models are this project\'s, under its MIT licence.'),
    el('details', {}, el('summary', {}, `All ${d.clips} clips and their split`),
      el('div', { class: 'table-wrap', tabindex: 0, role: 'region', 'aria-label': 'Clips' }, el('table', {},
        el('caption', {}, 'Clips, their length and their part of the split'),
        el('thead', {}, el('tr', {}, ...['Clip', 'Action', 'Frames', 'Seconds', 'Split'].map((h) => el('th', { scope: 'col' }, h)))),
        el('tbody', {}, ...rows)))));
}

function modelsSection(manifest: Manifest | null, problem: string | null): HTMLElement {
  if (!manifest) return section('models', 'The models', el('p', { class: 'error', role: 'alert' }, `The model manifest could not be loaded: ${problem}`));
  const fps = manifest.fps;
  const rows = manifest.models.map((m) => el('tr', {},
    el('th', { scope: 'row' }, m.label), el('td', {}, PAPERS[m.method] ?? m.method),
    el('td', { class: 'num' }, `${m.params.history_frames} (${(m.params.history_frames / fps).toFixed(2)} s)`),
    el('td', { class: 'num' }, `${m.params.future_frames} (${(m.params.future_frames / fps).toFixed(2)} s)`),
    el('td', {}, el('code', {}, m.hash.replace(/^sha256:/, '').slice(0, 12)))));
  return section('models', 'The models',
    el('p', {}, `This site serves ${manifest.models.length} models (models/manifest.json), trained on the training parts of the clips above. `,
      'They run in the browser (onnxruntime-web); the sampling around the networks is the same TypeScript on every page.'),
    el('div', { class: 'table-wrap', tabindex: 0, role: 'region', 'aria-label': 'Served models' }, el('table', {},
      el('caption', {}, 'Served models'),
      el('thead', {}, el('tr', {}, ...['Model', 'Paper', 'History frames', 'Future frames', 'Hash'].map((h) => el('th', { scope: 'col' }, h)))),
      el('tbody', {}, ...rows))));
}

const VERDICTS: [Verdict, string][] = [['can', 'Can'], ['cannot', 'Cannot'], ['unknown', 'Not shown or not measured']];

function findingList(list: Finding[]): HTMLElement {
  return el('ul', { class: 'findings' }, ...list.map((f) => el('li', { class: `finding finding-${f.verdict}` }, f.text, ' ', el('span', { class: 'source' }, `(${f.source})`))));
}

function resultsSection(results: Results | null, problem: string | null, manifest: Manifest | null): HTMLElement {
  if (!results) {
    return section('measured', 'What the models can and cannot do',
      el('p', { class: 'error', role: 'alert' }, `The measured numbers (results.json) could not be loaded: ${problem}`));
  }
  const all = mergeFindings(findings(results));
  const stale = manifest ? staleModels(results, manifest) : [];
  const groups = VERDICTS.map(([v, title]) => {
    const list = all.filter((f) => f.verdict === v);
    return list.length ? el('div', { class: `verdict verdict-${v}`, 'data-verdict': v }, el('h3', {}, `${title} (${list.length})`), findingList(list)) : null;
  });
  const tables = results.tables.filter((t) => t.rows.some((r) => r.values)).map((t) => {
    const cols = cardColumns(t);
    const head = el('tr', {}, el('th', { scope: 'col' }, 'Row'), ...cols.map((c) => {
      const col = results.columns[c];
      return el('th', { scope: 'col' }, `${col.label}${col.unit ? ` (${col.unit})` : ''}${col.better ? (col.better === 'lower' ? ' ↓' : ' ↑') : ''}`);
    }));
    const body = t.rows.filter((r) => r.values).map((r) => el('tr', {}, el('th', { scope: 'row' }, r.label),
      ...cols.map((c) => el('td', { class: 'num' }, cell(r.values![c], results.columns[c].unit)))));
    return el('div', { class: 'table-wrap', tabindex: 0, role: 'region', 'aria-label': t.title }, el('table', { 'data-table': t.id },
      el('caption', {}, `${t.title}: ${t.windows ? `${t.windows} histories, ` : ''}K = ${t.k}`),
      el('thead', {}, head), el('tbody', {}, ...body)));
  });
  return section('measured', 'What the models can and cannot do',
    el('p', {}, `Every number here is read from results.json when this page opens (python -m export evaluate; K = ${results.k}, `,
      `training seeds ${results.training_seeds.join(', ')}, sampling seeds ${results.sampling_seeds.join(', ')}; mean over runs ± a std combining a bootstrap over held-out takes with the seeds). `,
      el('a', { href: './results.html' }, 'The Results page'), ' has every column, the per-action lengths and the paper claims in full.'),
    stale.length ? el('div', { class: 'stale', role: 'note', 'data-testid': 'stale-models' }, el('strong', {}, 'Not measured as served: '),
      el('ul', {}, ...stale.map((x) => el('li', {}, `${x.label}: ${x.problem}.`)))) : null,
    ...groups,
    el('h3', {}, 'The recognition numbers rest on these classifiers'),
    el('ul', {}, ...classifierCaveats(results).map((c) => el('li', {}, c))),
    el('details', { class: 'card-tables' }, el('summary', {}, el('h3', { class: 'inline-heading' }, `Selected columns (${tables.length} tables)`)),
      el('p', { class: 'muted' }, '↓ lower is better, ↑ higher is better. ADE and MPJPE best of K: the sample closest to the captured future.'),
      ...tables));
}

function failureSection(results: Results | null, manifest: Manifest | null, index: ClipIndex): HTMLElement {
  return section('failures', 'Known failure modes',
    el('p', {}, 'Seen in the measured numbers above (and read from results.json like them):'),
    el('ul', {}, ...failureModes(results, index, manifest).map((t) => el('li', {}, t))));
}

function citeSection(): HTMLElement {
  const block = (id: string, text: string, label: string) => {
    const pre = el('pre', { id, tabindex: 0, 'aria-label': label }, el('code', {}, text));
    const copy = el('button', { type: 'button', class: 'copy-button' }, 'Copy');
    copy.addEventListener('click', () => {
      void navigator.clipboard?.writeText(text).then(() => { copy.textContent = 'Copied'; }, () => { copy.textContent = 'Select and copy the text'; });
    });
    return el('div', { class: 'bibtex' }, pre, copy);
  };
  return section('cite', 'How to cite',
    el('p', {}, 'If you use this site or its figures, cite the method papers and this project (CITATION.cff in the repository has the same entry).'),
    el('h3', {}, 'This project'), block('bibtex-project', projectBibtex(SITE_VERSION), 'BibTeX for this project'),
    el('h3', {}, 'The papers and the data'), block('bibtex-papers', PAPERS_BIBTEX, 'BibTeX for the three papers and the data (DeepMimic, CMU)'));
}

async function main(): Promise<void> {
  const host = document.getElementById('card');
  if (!host) return;
  document.body.dataset.status = 'loading';
  const root = new URL('./', document.baseURI).href;
  let index: ClipIndex;
  try {
    index = await fetchContract(`${root}clips/index.json`, 'clip-index');
  } catch (err) {
    host.replaceChildren(el('p', { class: 'error', role: 'alert' }, `The clip index could not be loaded: ${(err as Error).message}`));
    document.body.dataset.status = 'error';
    return;
  }
  const [manifest, results] = await Promise.all([
    sharedManifest(root).then((m) => ({ m, problem: null }), (err: Error) => ({ m: null, problem: err.message })),
    fetch(new URL('results.json', root)).then(async (res) => {
      if (!res.ok) throw new Error(`HTTP ${res.status}; run python -m export evaluate`);
      return { r: parseResults(await res.json()), problem: null };
    }).catch((err: Error) => ({ r: null, problem: err.message })),
  ]);
  host.replaceChildren(
    el('section', { class: 'card-summary', 'aria-labelledby': 'summary-title', 'data-testid': 'card-summary' },
      el('h2', { id: 'summary-title' }, 'In short'),
      el('ul', {}, ...cardSummary(results.r, manifest.m, index).map((line) => el('li', {}, line)))),
    el('p', { class: 'lede' }, 'What the predictors on this site were trained on, what they can and cannot do, where they fail, and how to cite them.'),
    el('nav', { 'aria-label': 'On this page', class: 'toc' }, el('ul', {},
      ...[['data', 'Data'], ['models', 'Models'], ['measured', 'Can and cannot'], ['failures', 'Failure modes'], ['cite', 'Cite']]
        .map(([id, t]) => el('li', {}, el('a', { href: `#${id}` }, t))))),
    dataSection(index), modelsSection(manifest.m, manifest.problem), resultsSection(results.r, results.problem, manifest.m),
    failureSection(results.r, manifest.m, index), citeSection());
  document.body.dataset.status = 'ready';
}

void main();
