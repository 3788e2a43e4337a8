// Builds the Results page from results.json: summary, claims, copying and memorising, the shape terms,
// figures, the tables (held-out people first, in-sample last), disclosed variants, sanity checks, classifiers.
import type { ClaimPart, Results, Table } from './data';
import { el } from './dom';
import { cell, fmt } from './format';
import { contextPlot, lengthHistograms } from './plots';

const STATUS_CLASS: Record<string, string> = {
  holds: 'status-holds', fails: 'status-fails', inconclusive: 'status-inconclusive', 'not evaluated': 'status-missing',
  'insufficient data': 'status-insufficient', unusable: 'status-unusable', 'by construction': 'status-construction',
  'in-sample': 'status-missing',
};

export function badge(status: string): HTMLElement {
  return el('span', { class: `badge ${STATUS_CLASS[status] ?? 'status-missing'}` }, status);
}

function section(id: string, title: string, ...children: (Node | null)[]): HTMLElement {
  return el('section', { id, class: 'results-section', 'aria-labelledby': `${id}-title` },
    el('h2', { id: `${id}-title` }, title), ...children);
}

const wrap = (table: HTMLElement) => el('div', { class: 'table-wrap' }, table);
const head = (...names: string[]) => el('thead', {}, el('tr', {}, ...names.map((h) => el('th', { scope: 'col' }, h))));

function overview(doc: Results): HTMLElement {
  const models = Object.entries(doc.models);
  const rounds = doc.bootstrap?.rounds;
  return section('overview', 'How these numbers were made',
    el('ul', {},
      el('li', {}, 'Every table that backs a claim is cut from the takes of people no model saw (the held-out people); the in-sample table is labelled and backs none. Every row of a table predicts from the same windows, each model from the last frames of its own history length.'),
      el('li', {}, `K = ${doc.k} futures per history for stochastic models (1 for deterministic ones); training seeds ${doc.training_seeds.join(', ')} × sampling seeds ${doc.sampling_seeds.join(', ')}.`),
      el('li', {}, `Each cell is the mean over runs ± a std that combines a cluster bootstrap over takes${rounds ? ` (${rounds} resamples)` : ''} with the std over runs, so deterministic rows have an uncertainty too. A claim holds only when the paired difference lies in the claimed direction by more than twice that std; fewer than ${doc.min_people ?? 2} held-out people or ${doc.min_takes ?? 5} takes make it insufficient data.`),
      el('li', {}, 'Accuracy columns are the mean over the table’s actions of each action’s accuracy (LCP-VAE’s “mean class accuracy”).'),
      el('li', {}, 'Predictions come from the Python predictor, the code path the end-to-end vectors tie to this site’s predictors; the futures are the raw outputs (bone-projected rows are labelled extras).'),
      el('li', {}, `Evaluation wall time: ${fmt(doc.seconds)} s. Served models: ${models.map(([id, h]) => `${id} (${h.slice(7, 19)}…)`).join(', ') || 'none'}.`)));
}

function summary(doc: Results): HTMLElement | null {
  if (!doc.summary?.length) return null;
  return section('summary', 'In short', el('ul', { class: 'summary' }, ...doc.summary.map((s) => el('li', {}, s))));
}

export function partText(doc: Results, p: ClaimPart): string {
  const col = doc.columns[p.metric];
  const unit = col?.unit ?? '';
  if (p.status === 'not evaluated' && p.missing.length) return `${p.a} vs ${p.b} (${col?.label ?? p.metric}, ${p.table}): missing ${p.missing.join(', ')}`;
  const other = p.metric_b !== p.metric ? ` ${doc.columns[p.metric_b]?.label ?? p.metric_b}` : '';
  const paired = p.a_paired !== undefined && p.b_paired !== undefined && p.a_value && p.b_value
    && (fmt(p.a_paired, unit) !== fmt(p.a_value.mean, unit) || fmt(p.b_paired, unit) !== fmt(p.b_value.mean, unit))
    ? ` on the ${p.items} items both predict: ${fmt(p.a_paired, unit)} vs ${fmt(p.b_paired, unit)};` : '';
  const support = p.people !== undefined ? `; ${p.people} people, ${p.takes} takes` : '';
  return `${p.a} ${cell(p.a_value, unit)} vs ${p.b}${other} ${cell(p.b_value, unit)} (${col?.label ?? p.metric}, ${p.table};${paired} `
    + `difference ${fmt(p.difference, unit)}, 2σ ${fmt(p.bar, unit)}${p.margin ? `, margin ${fmt(p.margin, unit)}` : ''}${support}): ${p.status}`
    + (p.reason ? ` (${p.reason})` : '');
}

function claims(doc: Results): HTMLElement {
  const list = el('ol', { class: 'claims' });
  for (const c of doc.claims) {
    const parts = el('ul', { class: 'claim-parts' }, ...c.parts.map((p) => el('li', {}, partText(doc, p))));
    list.append(el('li', { class: 'claim', 'data-claim': c.id, 'data-status': c.status },
      badge(c.status), ' ', el('strong', {}, c.text), ' ', el('span', { class: 'paper' }, `(${c.paper})`),
      c.reason ? el('p', { class: 'claim-reason' }, c.reason) : null, parts));
  }
  const t = doc.tally;
  const tally = t ? el('p', { class: 'tally' }, `${t.holds} hold, ${t.fails} fail, ${t.inconclusive} inconclusive, ${t['insufficient data']} insufficient data, `
    + `${t.unusable} unusable, ${t['not evaluated']} not evaluated; ${t.by_construction} true by construction (not counted).`) : null;
  return section('claims', 'Paper claims on held-out people', tally, list);
}

function copying(doc: Results): HTMLElement | null {
  if (!doc.copying?.length) return null;
  const body = el('tbody');
  for (const c of doc.copying) {
    body.append(el('tr', { 'data-copying': `${c.table}:${c.row}:${c.baseline}`, 'data-status': c.status },
      el('td', {}, c.table), el('th', { scope: 'row' }, c.label), el('td', {}, c.baseline_label),
      el('td', { class: 'num' }, fmt(c.difference, 'm')), el('td', { class: 'num' }, fmt(c.bar, 'm')),
      el('td', {}, badge(c.status)), el('td', {}, c.verdict)));
  }
  return section('copying', 'Copying and memorising',
    el('p', {}, 'Every model against the baselines that copy the history (repeat its last cycle) and memorise the training people (the nearest training window’s future): best-of-K ADE (root-relative), paired on the windows both predict. A model that does not beat the nearest training window reports memorisation.'),
    wrap(el('table', { class: 'results-table' }, head('table', 'model', 'baseline', 'ADE difference (m)', '2σ (m)', 'status', 'verdict'), body)));
}

function shape(doc: Results): HTMLElement | null {
  if (!doc.shape?.length) return null;
  const body = el('tbody');
  for (const s of doc.shape) {
    const unit = doc.columns[s.metric]?.unit ?? '';
    body.append(el('tr', { 'data-shape': `${s.table}:${s.with}:${s.metric}` }, el('th', { scope: 'row' }, s.with), el('td', {}, s.table),
      el('td', {}, doc.columns[s.metric]?.label ?? s.metric), el('td', { class: 'num' }, cell(s.with_value, unit)),
      el('td', { class: 'num' }, cell(s.without_value, unit)), el('td', { class: 'num' }, fmt(s.ratio)),
      el('td', {}, s.within ? 'yes' : 'no')));
  }
  return section('shape', 'With and without the shape terms',
    el('p', {}, `Each stochastic model against its ablation without the seam layer, fixed bone lengths and floor term (issue 17): is the model without them within ${Math.round(100 * doc.shape[0].tolerance)}% of the model with them? A measurement, not a claim.`),
    wrap(el('table', { class: 'results-table' }, head('model', 'table', 'metric', 'with', 'without', 'without / with', 'within'), body)));
}

function variants(doc: Results): HTMLElement | null {
  const v = doc.variants;
  if (!v) return null;
  const rules = Object.entries(v.keypose_rules ?? {});
  return section('variants', 'Choices that change the numbers',
    el('ul', {},
      el('li', {}, 'Eq. 4 both ways: as printed, the squared norm (mm²), and as the authors’ code computes it, the unsquared per-pose norm (mm). Ranking of the models: ',
        ...v.eq4.map((e) => el('span', { class: 'eq4' }, `${e.table}: ${e.same_order ? 'same order' : 'different orders'}. `))),
      el('li', {}, 'Keyposes: the paper’s tables interpolate linearly between keyposes (rows “linear”, the claims’ rows); the site serves the refinement network (“refined: served”).'),
      el('li', {}, `Keypose extraction: the paper’s text stops on the mean error (served and trained); the authors’ code on the maximum error (row “max-error extraction”, an evaluation variant). Keyposes per ${v.keypose_history_frames}-frame held-out history:`)),
    rules.length ? wrap(el('table', { class: 'results-table' }, head('action', 'histories', 'mean-error rule', 'max-error rule'),
      el('tbody', {}, ...rules.map(([a, r]) => el('tr', {}, el('th', { scope: 'row' }, a), el('td', { class: 'num' }, String(r.histories)),
        el('td', { class: 'num' }, fmt(r.mean)), el('td', { class: 'num' }, fmt(r.max))))))) : null);
}

function sanity(doc: Results): HTMLElement {
  const body = el('tbody');
  for (const s of doc.sanity) {
    body.append(el('tr', { 'data-sanity': s.id },
      el('td', {}, s.text), el('td', {}, s.table ?? '—'), el('td', { class: 'num' }, fmt(s.expected)),
      el('td', { class: 'num' }, fmt(s.measured)), el('td', {}, badge(s.passed ? 'holds' : 'fails'))));
  }
  return section('sanity', 'Sanity checks (each can fail)',
    el('p', {}, 'Where the ground truth does not score best on a classifier, the recognition claims of that table are unusable.'),
    wrap(el('table', { class: 'results-table' }, head('check', 'table', 'expected', 'measured', 'result'), body)));
}

function classifiers(doc: Results): HTMLElement {
  const entries = Object.entries(doc.classifiers);
  const body = el('tbody');
  for (const [name, r] of entries) {
    body.append(el('tr', {}, el('th', { scope: 'row' }, name), el('td', { class: 'num' }, fmt(r.train_accuracy, '%')),
      el('td', { class: 'num' }, fmt(r.test_accuracy, '%')), el('td', { class: 'num' }, fmt(r.test_balanced_accuracy, '%')),
      el('td', { class: 'num' }, fmt(r.chance, '%'))));
  }
  const names = entries.filter(([n]) => !n.endsWith('_shuffled')).map(([n]) => n);
  const actions = [...new Set(entries.flatMap(([, r]) => Object.keys(r.test_groups)))].sort();
  const perAction = el('tbody', {}, ...actions.map((a) => el('tr', {}, el('th', { scope: 'row' }, a),
    ...names.map((n) => el('td', { class: 'num' }, doc.classifiers[n].test_groups[a] ? fmt(doc.classifiers[n].test_groups[a].accuracy, '%') : '—')))));
  const chosen = names.filter((n) => doc.classifiers[n].selection).map((n) => {
    const s = doc.classifiers[n].selection!;
    return el('li', {}, `${n}: leave-one-person-out chose ${s.chosen} (folds: ${s.people.join(', ')}; `
      + s.candidates.map((c) => `${c.name} ${fmt(c.score, '%')} %`).join(', ') + ')');
  });
  return section('classifiers', 'Action classifiers',
    el('p', {}, `Trained on the training people only, on ${doc.classifier_config.snippet_frames}-frame snippets; accuracies in % of held-out snippets (people no classifier saw). Architecture and augmentation were chosen by leave-one-person-out validation inside the training people, never by the test.`),
    chosen.length ? el('ul', { class: 'notes' }, ...chosen) : null,
    wrap(el('table', { class: 'results-table' }, head('classifier', 'train', 'held-out (snippets)', 'held-out (mean per action)', 'chance'), body)),
    el('h3', {}, 'Held-out accuracy per action (%)'),
    wrap(el('table', { class: 'results-table' }, head('action', ...names), perAction)),
    ...entries.filter(([, r]) => r.motionless_class).map(([name, r]) =>
      el('p', {}, `A motionless snippet is classified by ${name} as `, el('strong', {}, String(r.motionless_class)), '.')));
}

export function resultsTable(doc: Results, t: Table): HTMLElement {
  const headRow = el('tr', {}, el('th', { scope: 'col' }, 'row'), el('th', { scope: 'col' }, 'windows'), el('th', { scope: 'col' }, 'runs'),
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
        el('td', { colspan: t.columns.length + 2 }, `skipped: ${r.skipped}`)));
      continue;
    }
    body.append(el('tr', { 'data-row': r.id, class: `kind-${r.kind}` }, el('th', { scope: 'row' }, r.label),
      el('td', { class: 'num' }, `${r.items ?? ''}/${t.items ?? t.windows ?? ''}`),
      el('td', { class: 'num' }, String(r.runs ?? '')),
      ...t.columns.map((c) => el('td', { class: 'num' }, cell(r.values?.[c], doc.columns[c].unit)))));
    for (const n of r.notes) notes.append(el('li', {}, `${r.label}: ${n}`));
  }
  for (const n of t.notes) notes.append(el('li', {}, n));
  const people = t.people?.length ? ` · ${t.takes} takes of ${t.people.length} people (${t.people.join(', ')})` : '';
  const mm = t.mmade;
  const acts = t.actions;
  const byAction = t.truth && !t.in_sample && t.rows.some((r) => r.by_action?.ade)
    ? el('details', { class: 'by-action' }, el('summary', {}, 'ADE best of K (root-relative, m) per action'),
      wrap(el('table', { class: 'results-table' }, head('row', ...acts),
        el('tbody', {}, ...t.rows.filter((r) => r.by_action?.ade).map((r) => el('tr', {}, el('th', { scope: 'row' }, r.label),
          ...acts.map((a) => el('td', { class: 'num' }, fmt(r.by_action!.ade[a]))))))))) : null;
  return el('article', { class: 'table-block', id: `table-${t.id}`, 'data-table': t.id },
    el('h3', {}, t.title, t.in_sample ? el('span', { class: 'in-sample' }, ' (in-sample: backs no claim)') : null),
    el('p', { class: 'table-meta' }, `History ${t.history_frames} frames${t.context_frames && t.context_frames > (t.history_frames ?? 0) ? ` (context up to ${t.context_frames})` : ''} · horizon ${t.horizon_frames} frames (${(t.horizon_frames / doc.fps).toFixed(1)} s) · K = ${t.k}${t.windows ? ` · ${t.windows} windows` : ''}${people}`),
    el('p', {}, t.about),
    t.exceptions?.length ? el('p', { class: 'exceptions' }, `Horizon exceptions (no held-out take holds history + horizon; never padded): ${t.exceptions.map((e) => e.action).join(', ')}.`) : null,
    mm ? el('p', { class: 'mmade-note' }, `MMADE/MMFDE: similar histories lie within ${fmt(mm.threshold)} m of a window’s last pose (median set ${fmt(mm.median_set)}; `
      + `${mm.alone} windows have only themselves and count with their own truth). Sensitivity at ${fmt(mm.half.threshold)} m and ${fmt(mm.double.threshold)} m is in results.json and RESULTS.md.`) : null,
    wrap(el('table', { class: 'results-table main' }, el('thead', {}, headRow), body)),
    byAction,
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
  const tables = [...doc.tables].sort((a, b) => Number(Boolean(a.in_sample)) - Number(Boolean(b.in_sample)));
  root.replaceChildren(...[
    overview(doc), summary(doc), claims(doc), copying(doc), shape(doc), figures(doc),
    section('tables', 'Tables', ...tables.map((t) => resultsTable(doc, t))),
    variants(doc), sanity(doc), classifiers(doc), skipped(doc)].filter((x): x is HTMLElement => x !== null));
}
