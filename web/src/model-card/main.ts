// The Model card page: the data (results.json's data summary), the served models, each served learned model
// against the baselines, what they can and cannot do (numbers read from results.json when the page runs),
// known failure modes, and how to cite. docs/MODEL_CARD.md is written
// from the same results.json by the evaluation (export/eval/card.py), with the same five-line summary.
import '../explainer/page.css';
import './model-card.css';
import type { ClipIndex, Manifest } from '../contract/types';
import { fetchContract } from '../contract/validate';
import { sharedManifest } from '../embed/shared';
import { parseResults, type Results } from '../results/data';
import { cell } from '../results/format';
import { rowLabel, windowsText } from '../results/rows';
import { ahead, baselineName, beatenLine, labelFor, VERDICT_BASELINES, verdictGrid, verdictText } from '../results/verdicts';
import { SITE_VERSION } from '../share/version';
import { el } from '../ui/dom';
import { cardColumns, cardGaps, cardSummary, classifierCaveats, dataFacts, dataSummary, failureModes, findings, horizonFrames, mergeFindings, paperOf, PAPERS_BIBTEX, projectBibtex, staleModels, type Finding, type Verdict } from './card';

const pretty = (s: string) => s.replace(/_/g, ' ');

function section(id: string, title: string, ...children: (Node | string | null)[]): HTMLElement {
  return el('section', { class: 'card-section', id, 'aria-labelledby': `${id}-title` }, el('h2', { id: `${id}-title` }, title), ...children);
}

/** The data the models learned from and are tested on, from results.json (the clips this site offers are listed apart). */
function dataSection(results: Results | null, index: ClipIndex): HTMLElement {
  const facts = dataFacts(results);
  const site = dataSummary(index);
  const rows = index.clips.map((c) => el('tr', {},
    el('th', { scope: 'row' }, pretty(c.name)), el('td', {}, pretty(c.action)), el('td', { class: 'num' }, String(c.frames)),
    el('td', { class: 'num' }, (c.frames / index.fps).toFixed(2)),
    el('td', {}, c.role === 'test' ? 'test' : c.test.length ? `train, test from frame ${c.test[0][0]}` : 'train')));
  const datasets = [...new Set(index.clips.map((c) => c.dataset).filter((x): x is string => Boolean(x)))];
  const perAction = facts?.actions.length ? el('div', { class: 'table-wrap', tabindex: 0, role: 'region', 'aria-label': 'Data per action' }, el('table', { 'data-testid': 'data-per-action' },
    el('caption', {}, 'People, takes and seconds per action, training and held out'),
    el('thead', {}, el('tr', {}, ...['Action', 'Group', 'Training people', 'Training takes', 'Training s', 'Held-out people', 'Held-out takes', 'Held-out s'].map((h) => el('th', { scope: 'col' }, h)))),
    el('tbody', {}, ...facts.actions.map((a) => el('tr', {}, el('th', { scope: 'row' }, pretty(a.action)), el('td', {}, a.group),
      ...[...a.train, ...a.test].map((x, i) => el('td', { class: 'num' }, i % 3 === 2 ? (x >= 100 ? x.toFixed(0) : x.toFixed(1)) : String(x)))))))) : null;
  return section('data', 'The data',
    facts ? el('ul', { 'data-testid': 'data-facts' }, ...facts.lines.map((l) => el('li', {}, l)))
      : el('p', { class: 'error', role: 'alert' }, 'results.json has no data summary: run python -m export evaluate.'),
    perAction,
    el('details', {}, el('summary', {}, 'How the takes are split'), el('ul', {}, ...index.split_rules.map((r) => el('li', {}, r)))),
    el('p', {}, `Sources: ${datasets.length ? datasets.join('; ') : 'not stated'}. `,
      el('a', { href: './DATA_NOTICE.md' }, 'DATA_NOTICE.md'), ' has every source with its licence; the models are this project\'s, under its MIT licence.'),
    el('details', {}, el('summary', {}, `The ${site.clips} clips this site offers as histories (${site.seconds.toFixed(1)} s; not the training data)`),
      el('div', { class: 'table-wrap', tabindex: 0, role: 'region', 'aria-label': 'Clips' }, el('table', {},
        el('caption', {}, 'Clips on this site, their length and their part of the split'),
        el('thead', {}, el('tr', {}, ...['Clip', 'Action', 'Frames', 'Seconds', 'Split'].map((h) => el('th', { scope: 'col' }, h)))),
        el('tbody', {}, ...rows)))));
}

/** Each served learned model against zero-velocity, the regression GRU and the nearest window, its verdicts beside their paired numbers. */
function baselinesSection(results: Results | null): HTMLElement | null {
  if (!results?.verdicts?.length) return null;
  const { bases, lines } = verdictGrid(results);
  return section('baselines', 'Against the baselines',
    el('p', {}, 'Best-of-K ADE (root-relative) on held-out people, each served learned model and the baseline on the same windows (those the model accepts), with their count; “beats” needs a difference beyond the 2σ bar that also passes Holm’s correction over the copying comparisons.'),
    el('ul', { 'data-testid': 'beaten' }, ...VERDICT_BASELINES.map((b) => beatenLine(results, b)).filter((x): x is string => x !== null).map((x) => el('li', {}, x))),
    el('div', { class: 'table-wrap', tabindex: 0, role: 'region', 'aria-label': 'Served learned models against the baselines' }, el('table', { 'data-testid': 'verdicts' },
      el('caption', {}, 'Served learned models against the baselines'),
      el('thead', {}, el('tr', {}, ...['Model', 'Ahead', ...bases.map((b) => `vs ${baselineName(results, b)}`)].map((h) => el('th', { scope: 'col' }, h)))),
      el('tbody', {}, ...lines.map((l) => el('tr', { 'data-served': `${l.table}:${l.row}` }, el('th', { scope: 'row' }, labelFor(results, l.row)),
        el('td', {}, `${ahead(results, l.table)} (${l.table})`), ...l.cells.map((v) => el('td', {}, v ? verdictText(results, v) : '— (itself)'))))))));
}

function modelsSection(manifest: Manifest | null, problem: string | null): HTMLElement {
  if (!manifest) return section('models', 'The models', el('p', { class: 'error', role: 'alert' }, `The model manifest could not be loaded: ${problem}`));
  const fps = manifest.fps;
  const rows = manifest.models.map((m) => el('tr', {},
    el('th', { scope: 'row' }, m.label), el('td', {}, paperOf(m.method)),
    el('td', { class: 'num' }, `${m.params.history_frames} (${(m.params.history_frames / fps).toFixed(2)} s)`),
    el('td', { class: 'num' }, `${horizonFrames(m, fps)} (${(horizonFrames(m, fps) / fps).toFixed(2)} s)`),
    el('td', {}, el('code', {}, m.hash.replace(/^sha256:/, '').slice(0, 12)))));
  return section('models', 'The models',
    el('p', {}, `This site serves ${manifest.models.length} models (models/manifest.json), trained on the training people above. `,
      'They run in the browser (onnxruntime-web); the sampling around the networks is the same TypeScript on every page.'),
    el('div', { class: 'table-wrap', tabindex: 0, role: 'region', 'aria-label': 'Served models' }, el('table', {},
      el('caption', {}, 'Served models'),
      el('thead', {}, el('tr', {}, ...['Model', 'Paper', 'History frames', 'Default horizon (frames)', 'Hash'].map((h) => el('th', { scope: 'col' }, h)))),
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
    const head = el('tr', {}, el('th', { scope: 'col' }, 'Row'), el('th', { scope: 'col' }, 'Windows'), ...cols.map((c) => {
      const col = results.columns[c];
      return el('th', { scope: 'col' }, `${col.label}${col.unit ? ` (${col.unit})` : ''}${col.better ? (col.better === 'lower' ? ' ↓' : ' ↑') : ''}`);
    }));
    const body = t.rows.filter((r) => r.values).map((r) => el('tr', {}, el('th', { scope: 'row' }, rowLabel(r)), el('td', { class: 'num' }, windowsText(r, t)),
      ...cols.map((c) => el('td', { class: 'num' }, cell(r.values![c], results.columns[c].unit)))));
    return el('div', { class: 'table-wrap', tabindex: 0, role: 'region', 'aria-label': t.title }, el('table', { 'data-table': t.id },
      el('caption', {}, `${t.title}: ${t.windows ? `${t.windows} histories, ` : ''}K = ${t.k}`),
      el('thead', {}, head), el('tbody', {}, ...body)));
  });
  return section('measured', 'What the models can and cannot do',
    el('p', {}, `Every number here is read from results.json when this page opens (python -m export evaluate; K = ${results.k}, `,
      `training seeds ${results.training_seeds.join(', ')}, sampling seeds ${results.sampling_seeds.join(', ')}; mean over runs ± a std combining a bootstrap over held-out people, then takes within people, with the seeds). `,
      'Every pair of numbers set side by side below is on the same windows, with their count; a row that refuses windows says how many. ',
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

/** Said on the page rather than dropped: the sections that found no data in results.json. */
function gapsNote(gaps: string[]): HTMLElement | null {
  return gaps.length ? el('div', { class: 'stale', role: 'note', 'data-testid': 'card-gaps' }, el('strong', {}, 'Sections without data: '),
    el('ul', {}, ...gaps.map((g) => el('li', {}, `${g}.`)))) : null;
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
    el('h3', {}, 'The papers and the data'), block('bibtex-papers', PAPERS_BIBTEX, 'BibTeX for the three papers and the data (CMU, DeepMimic)'));
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
  const baselines = baselinesSection(results.r);
  const toc = [['data', 'Data'], ['models', 'Models'], ...(baselines ? [['baselines', 'Against the baselines']] : []), ['measured', 'Can and cannot'],
    ['failures', 'Failure modes'], ['cite', 'Cite']];
  host.replaceChildren(...[
    el('section', { class: 'card-summary', 'aria-labelledby': 'summary-title', 'data-testid': 'card-summary' },
      el('h2', { id: 'summary-title' }, 'In short'),
      el('ul', {}, ...cardSummary(results.r, manifest.m, index).map((line) => el('li', {}, line)))),
    el('p', { class: 'lede' }, 'What the predictors on this site were trained on, what they can and cannot do, where they fail, and how to cite them.'),
    el('nav', { 'aria-label': 'On this page', class: 'toc' }, el('ul', {},
      ...toc.map(([id, t]) => el('li', {}, el('a', { href: `#${id}` }, t))))),
    gapsNote(cardGaps(results.r, index, manifest.m)),
    dataSection(results.r, index), modelsSection(manifest.m, manifest.problem), baselines,
    resultsSection(results.r, results.problem, manifest.m), failureSection(results.r, manifest.m, index), citeSection(),
  ].filter((x): x is HTMLElement => x !== null));
  document.body.dataset.status = 'ready';
}

void main();
