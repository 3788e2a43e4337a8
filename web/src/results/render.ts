// Builds the Results page from results.json: claims, sanity checks, classifiers, tables, figures.
import type { Results, Table } from './data';
import { el } from './dom';
import { cell, fmt } from './format';
import { contextPlot, lengthHistograms } from './plots';

const STATUS_CLASS: Record<string, string> = {
  holds: 'status-holds', fails: 'status-fails', inconclusive: 'status-inconclusive', 'not evaluated': 'status-missing',
};

function badge(status: string): HTMLElement {
  return el('span', { class: `badge ${STATUS_CLASS[status] ?? 'status-missing'}` }, status);
}

function section(id: string, title: string, ...children: (Node | null)[]): HTMLElement {
  return el('section', { id, class: 'results-section', 'aria-labelledby': `${id}-title` },
    el('h2', { id: `${id}-title` }, title), ...children);
}

function overview(doc: Results): HTMLElement {
  const models = Object.entries(doc.models);
  return section('overview', 'How these numbers were made',
    el('ul', {},
      el('li', {}, `K = ${doc.k} futures per history for stochastic models (1 for deterministic ones); training seeds ${doc.training_seeds.join(', ')} × sampling seeds ${doc.sampling_seeds.join(', ')}.`),
      el('li', {}, 'Each cell is mean ± std over runs. A paper claim holds only when the difference lies in the claimed direction by more than twice the std of the difference; otherwise it is inconclusive (or fails, when it lies the other way by as much).'),
      el('li', {}, 'Accuracy columns are the mean over the table’s actions of each action’s accuracy (LCP-VAE’s “mean class accuracy”): about 90% of the test windows are walking, so plain accuracy would reward a classifier that maps every static input to “walk”.'),
      el('li', {}, 'Predictions come from the Python predictor, the code path the end-to-end vectors tie to this site’s predictors.'),
      el('li', {}, `Evaluation wall time: ${fmt(doc.seconds)} s. Served models: ${models.map(([id, h]) => `${id} (${h.slice(7, 19)}…)`).join(', ') || 'none'}.`)));
}

function claims(doc: Results): HTMLElement {
  const list = el('ol', { class: 'claims' });
  for (const c of doc.claims) {
    const parts = el('ul', { class: 'claim-parts' });
    for (const p of c.parts) {
      const col = doc.columns[p.metric];
      const unit = col?.unit ?? '';
      const other = p.metric_b !== p.metric ? ` ${doc.columns[p.metric_b]?.label ?? p.metric_b}` : '';
      parts.append(el('li', {}, p.status === 'not evaluated'
        ? `${p.a} vs ${p.b} (${col?.label ?? p.metric}, ${p.table}): missing ${p.missing.join(', ')}`
        : `${p.a} ${cell(p.a_value, unit)} vs ${p.b}${other} ${cell(p.b_value, unit)} (${col?.label ?? p.metric}, ${p.table}; difference ${fmt(p.difference, unit)}, 2σ ${fmt(p.bar, unit)}): ${p.status}`));
    }
    list.append(el('li', { class: 'claim', 'data-claim': c.id, 'data-status': c.status },
      badge(c.status), ' ', el('strong', {}, c.text), ' ', el('span', { class: 'paper' }, `(${c.paper})`), parts));
  }
  return section('claims', 'Paper claims on this data', list);
}

function sanity(doc: Results): HTMLElement {
  const body = el('tbody');
  for (const s of doc.sanity) {
    body.append(el('tr', { 'data-sanity': s.id },
      el('td', {}, s.text), el('td', {}, s.table ?? '—'), el('td', { class: 'num' }, fmt(s.expected)),
      el('td', { class: 'num' }, fmt(s.measured)), el('td', {}, badge(s.passed ? 'holds' : 'fails'))));
  }
  return section('sanity', 'Sanity checks (each can fail)',
    el('div', { class: 'table-wrap' }, el('table', { class: 'results-table' },
      el('thead', {}, el('tr', {}, ...['check', 'table', 'expected', 'measured', 'result'].map((h) => el('th', { scope: 'col' }, h)))), body)));
}

function classifiers(doc: Results): HTMLElement {
  const body = el('tbody');
  for (const [name, r] of Object.entries(doc.classifiers)) {
    const g = (k: string) => (r.test_groups[k] ? fmt(r.test_groups[k].accuracy, '%') : '—');
    body.append(el('tr', {}, el('th', { scope: 'row' }, name), el('td', { class: 'num' }, fmt(r.train_accuracy, '%')),
      el('td', { class: 'num' }, fmt(r.test_accuracy, '%')), el('td', { class: 'num' }, fmt(r.test_balanced_accuracy, '%')),
      el('td', { class: 'num' }, g('walker')),
      el('td', { class: 'num' }, g('getup_faceup')), el('td', { class: 'num' }, g('spin')), el('td', { class: 'num' }, fmt(r.chance, '%'))));
  }
  const confusions = el('ul', { class: 'notes' }, ...Object.entries(doc.classifiers).map(([name, r]) => el('li', {},
    `${name}: ` + Object.entries(r.test_groups).map(([g, v]) =>
      `${g} → ${Object.entries(v.predicted ?? {}).map(([a, n]) => `${a} ${n}`).join(', ')}`).join('; '))));
  return section('classifiers', 'Action classifiers',
    el('p', {}, `Trained on the training split only, on ${doc.classifier_config.snippet_frames}-frame snippets; accuracies in % of test snippets.`),
    el('p', { class: 'risk' }, el('strong', {}, 'One take per action. '),
      'Only walking has a second take (the walker clips); the other test snippets are later frames of the take the classifier was trained on. A classifier can learn the take rather than the action, so its verdict on generated motion says less about the action than it seems.'),
    el('div', { class: 'table-wrap' }, el('table', { class: 'results-table' },
      el('thead', {}, el('tr', {}, ...['classifier', 'train', 'test (snippets)', 'test (mean per action)', 'walker (2nd take)', 'getup_faceup tail', 'spin tail', 'chance']
        .map((h) => el('th', { scope: 'col' }, h)))), body)),
    ...Object.entries(doc.classifiers).filter(([, r]) => r.motionless_class).map(([name, r]) =>
      el('p', {}, `A motionless snippet (zero velocity) is classified by ${name} as `, el('strong', {}, String(r.motionless_class)),
        '; every static prediction gets this label from it.')),
    el('p', {}, 'What the test snippets were classified as (snippet counts):'), confusions);
}

export function resultsTable(doc: Results, t: Table): HTMLElement {
  const head = el('tr', {}, el('th', { scope: 'col' }, 'row'), el('th', { scope: 'col' }, 'runs'),
    ...t.columns.map((c) => {
      const col = doc.columns[c];
      const arrow = col.better === 'lower' ? ' ↓' : col.better === 'higher' ? ' ↑' : '';
      return el('th', { scope: 'col', 'data-column': c }, `${col.label}${col.unit ? ` (${col.unit})` : ''}${arrow}`);
    }));
  const body = el('tbody');
  const notes = el('ul', { class: 'notes' });
  for (const r of t.rows) {
    if (r.skipped) {
      body.append(el('tr', { class: 'skipped', 'data-row': r.id }, el('th', { scope: 'row' }, r.label),
        el('td', { colspan: t.columns.length + 1 }, `skipped: ${r.skipped}`)));
      continue;
    }
    body.append(el('tr', { 'data-row': r.id, class: `kind-${r.kind}` }, el('th', { scope: 'row' }, r.label),
      el('td', { class: 'num' }, String(r.runs ?? '')),
      ...t.columns.map((c) => el('td', { class: 'num' }, cell(r.values?.[c], doc.columns[c].unit)))));
    for (const n of r.notes) notes.append(el('li', {}, `${r.label}: ${n}`));
  }
  for (const n of t.notes) notes.append(el('li', {}, n));
  return el('article', { class: 'table-block', id: `table-${t.id}`, 'data-table': t.id },
    el('h3', {}, t.title),
    el('p', { class: 'table-meta' }, `${t.history_frames ? `History ${t.history_frames} frames` : 'History: each model’s own (see notes)'} · horizon ${t.horizon_frames} frames (${(t.horizon_frames / doc.fps).toFixed(1)} s) · K = ${t.k}${t.windows ? ` · ${t.windows} windows` : ''}`),
    el('p', {}, t.about),
    el('div', { class: 'table-wrap' }, el('table', { class: 'results-table' }, el('thead', {}, head), body)),
    notes.childElementCount ? el('details', {}, el('summary', {}, `Notes (${notes.childElementCount})`), notes) : null);
}

function figures(doc: Results): HTMLElement {
  const ctx = el('div', { class: 'figure-grid' });
  for (const id of doc.context_plot) {
    const t = doc.tables.find((x) => x.id === id);
    const plot = t ? contextPlot(t) : null;
    if (t && plot) ctx.append(el('figure', { class: 'figure' }, plot, el('figcaption', {}, `${t.title}: diversity against context (whiskers ±1 std).`)));
  }
  const lengths = el('div', { class: 'length-grid' });
  const lt = doc.tables.find((x) => x.id === doc.length_plot);
  if (lt) {
    for (const r of lt.rows) {
      if (r.skipped) continue;
      const plot = lengthHistograms(r, lt.length_edges);
      if (plot) lengths.append(el('figure', { class: 'figure' }, plot, el('figcaption', {}, `${r.label}: predicted lengths per action, first run (${lt.title}); samples per action in brackets.`)));
    }
  }
  return section('figures', 'Figures',
    el('h3', {}, 'Diversity against context (like LCP-VAE Fig. 1)'),
    ctx.childElementCount ? ctx : el('p', {}, 'No row has both a diversity and a context value yet.'),
    el('h3', {}, 'Predicted lengths per action (WAT)'),
    lengths.childElementCount ? lengths : el('p', {}, 'No length data yet.'));
}

function skipped(doc: Results): HTMLElement | null {
  if (doc.skipped.length === 0) return null;
  return section('skipped', 'Rows not evaluated yet',
    el('ul', {}, ...doc.skipped.map((s) => el('li', { 'data-row': s.row }, el('strong', {}, s.label), `: ${s.reason}`))));
}

export function renderResults(root: HTMLElement, doc: Results): void {
  root.replaceChildren(
    overview(doc), claims(doc), figures(doc),
    section('tables', 'Tables', ...doc.tables.map((t) => resultsTable(doc, t))),
    sanity(doc), classifiers(doc), skipped(doc) ?? el('div'));
}
