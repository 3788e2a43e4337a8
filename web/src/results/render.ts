// Builds the Results page from results.json: summary, the served learned models against the baselines,
// claims, copying and memorising, the shape terms, figures, the tables (held-out people first, in-sample
// last, each with its realism per action group), disclosed variants, sanity checks, classifiers.
import type { ClaimPart, Results, Table } from './data';
import { el } from './dom';
import { cell, fmt } from './format';
import { contextPlot, lengthHistograms } from './plots';
import { onAccepted, realismTables } from './realism';
import { rowLabel, windowsText } from './rows';
import { ahead, baselineName, beatenLine, labelFor, verdictGrid, verdictText } from './verdicts';

const STATUS_CLASS: Record<string, string> = {
  holds: 'status-holds', fails: 'status-fails', inconclusive: 'status-inconclusive', 'no difference': 'status-nodifference',
  'not evaluated': 'status-missing', 'insufficient data': 'status-insufficient', unusable: 'status-unusable',
  'by construction': 'status-construction', 'in-sample': 'status-missing',
};

// the columns realism.ts shows beside the truth's (PSKL and CMD stay in the main table)
const REALISM = new Set(['mpjpe_cm', 'mpjpe_f_cm', 'follow', 'skate', 'hip_range', 'outside', 'spread_cm', 'full',
  ...[1, 2, 3, 4, 5].flatMap((s) => [`speed_ratio_s${s}`, `root_ratio_s${s}`])]);

/** The badge class of a status (each status has its own; an unknown one looks like "not evaluated"). */
export const statusClass = (status: string) => STATUS_CLASS[status] ?? 'status-missing';

export function badge(status: string): HTMLElement {
  return el('span', { class: `badge ${statusClass(status)}` }, status);
}

function section(id: string, title: string, ...children: (Node | null)[]): HTMLElement {
  return el('section', { id, class: 'results-section', 'aria-labelledby': `${id}-title` },
    el('h2', { id: `${id}-title` }, title), ...children);
}

// a wide table scrolls in its box, which the keyboard can reach (axe: scrollable-region-focusable)
const wrap = (table: HTMLElement, label = 'Table') => el('div', { class: 'table-wrap', tabindex: 0, role: 'region', 'aria-label': label }, table);
const head = (...names: string[]) => el('thead', {}, el('tr', {}, ...names.map((h) => el('th', { scope: 'col' }, h))));

function overview(doc: Results): HTMLElement {
  const models = Object.entries(doc.models);
  const rounds = doc.bootstrap?.rounds;
  return section('overview', 'How these numbers were made',
    el('ul', {},
      el('li', {}, 'Every table that backs a claim is cut from the takes of people no model saw (the held-out people); the in-sample table is labelled and backs none. Every row of a table predicts from the same windows, each model from the last frames of its own history length.'),
      el('li', {}, `K = ${doc.k} futures per history for stochastic models (1 for deterministic ones); training seeds ${doc.training_seeds.join(', ')} × sampling seeds ${doc.sampling_seeds.join(', ')}.`),
      el('li', {}, `Each cell is the mean over runs ± a std that combines a two-level cluster bootstrap — the held-out people resampled, then takes within each drawn person${rounds ? ` (${rounds} resamples)` : ''} — with the std over runs, so deterministic rows have an uncertainty too.`),
      el('li', {}, rulesText(doc)),
      el('li', {}, 'Accuracy columns are the mean over the table’s actions of each action’s accuracy (LCP-VAE’s “mean class accuracy”).'),
      el('li', {}, 'Predictions come from the Python predictor, the code path the end-to-end vectors tie to this site’s predictors; the futures are the raw outputs (bone-projected rows are labelled extras).'),
      el('li', {}, `Evaluation wall time: ${fmt(doc.seconds)} s. Served models: ${models.map(([id, h]) => `${id} (${h.slice(7, 19)}…)`).join(', ') || 'none'}.`)));
}

/** The rules a comparison is judged by, with the numbers results.json states (none are assumed). */
export function rulesText(doc: Results): string {
  const n = doc.comparisons;
  const support = doc.min_people !== undefined && doc.min_takes !== undefined
    ? `fewer than ${doc.min_people} held-out people or ${doc.min_takes} held-out takes among the windows both rows predict make it insufficient data`
    : 'too few held-out people or takes make it insufficient data';
  return 'A comparison holds only when the paired difference (both rows on the same windows) lies in the claimed direction by more than its 2σ bar '
    + `and passes Holm’s step-down correction at family-wise α 0.05 within its family${n ? ` (${n.claims} claim parts; ${n.copying} copying comparisons)` : ''}; `
    + 'a difference below the practical minimum (1 mm or 1% for lengths, 1 point for %, 1% otherwise), or identical predictions, is no difference; '
    + `${support}; a recognition part where the ground truth does not score best is unusable (and says what the data alone would say).`;
}

function summary(doc: Results): HTMLElement | null {
  if (!doc.summary?.length) return null;
  return section('summary', 'In short', el('ul', { class: 'summary' }, ...doc.summary.map((s) => el('li', {}, s))));
}

/** A part's status; an unusable one also says what the data alone would say. */
export const statusText = (x: { status: string; data_status?: string }) => x.status + (x.data_status ? `; the data would say: ${x.data_status}` : '');

const holmText = (p: { p?: number | null; p_holm?: number }) => (p.p_holm !== undefined ? `, p ${fmt(p.p)}, Holm-adjusted ${fmt(p.p_holm)}` : '');

/** A claim part: both rows on the items both predict (never each row's own mean beside the other's), the count, the bar, p and Holm, the status. */
export function partText(doc: Results, p: ClaimPart): string {
  const col = doc.columns[p.metric];
  const unit = col?.unit ?? '';
  const label = col?.label ?? p.metric;
  if (p.kind === 'trend' && p.values) {
    return `trend of ${label}, ${p.table}, ${p.setting} ${(p.settings ?? []).map((x) => fmt(x)).join(', ')} (on the ${p.items} items every row predicts: `
      + `${p.values.map((v) => fmt(v, unit)).join(' → ')}; change over the range ${fmt(p.difference, unit)}, 2σ ${fmt(p.bar, unit)}${holmText(p)}): ${statusText(p)}`
      + (p.reason ? ` (${p.reason})` : '');
  }
  if (p.status === 'not evaluated' || p.a_paired === undefined || p.b_paired === undefined) {
    return `${p.a} vs ${p.b} (${label}, ${p.table})${p.missing.length ? `: missing ${p.missing.join(', ')}` : ''}: ${statusText(p)}`;
  }
  const other = p.metric_b !== p.metric ? ` ${doc.columns[p.metric_b]?.label ?? p.metric_b}` : '';
  const support = p.people !== undefined ? `, ${p.people} people, ${p.takes} takes` : '';
  return `${p.a} ${fmt(p.a_paired, unit)} vs ${p.b}${other} ${fmt(p.b_paired, unit)} (${label}, ${p.table}; on the ${p.items} items both predict${support}; `
    + `difference ${fmt(p.difference, unit)}, 2σ ${fmt(p.bar, unit)}${p.margin ? `, margin ${fmt(p.margin, unit)}` : ''}${holmText(p)}): ${statusText(p)}`
    + (p.reason ? ` (${p.reason})` : '');
}

function claims(doc: Results): HTMLElement {
  const list = el('ol', { class: 'claims' });
  for (const c of doc.claims) {
    const parts = el('ul', { class: 'claim-parts' }, ...c.parts.map((p) => el('li', {}, partText(doc, p))));
    list.append(el('li', { class: 'claim', 'data-claim': c.id, 'data-status': c.status },
      badge(c.status), c.data_status ? el('span', { class: 'data-status' }, ` the data would say: ${c.data_status}`) : null, ' ',
      el('strong', {}, c.text), ' ', el('span', { class: 'paper' }, `(${c.paper})`),
      c.reason ? el('p', { class: 'claim-reason' }, c.reason) : null, parts));
  }
  const t = doc.tally;
  const tally = t ? el('p', { class: 'tally' }, `${t.holds} hold, ${t.fails} fail, ${t.inconclusive} inconclusive, ${t['no difference'] ?? 0} no difference, `
    + `${t['insufficient data']} insufficient data, ${t.unusable} unusable, ${t['not evaluated']} not evaluated; ${t.by_construction} true by construction (not counted).`) : null;
  return section('claims', 'Paper claims on held-out people', tally, el('p', { class: 'rules' }, rulesText(doc)), list);
}

function verdicts(doc: Results): HTMLElement | null {
  const { bases, lines } = verdictGrid(doc);
  if (!lines.length) return null;
  const body = el('tbody', {}, ...lines.map((l) => el('tr', { 'data-served': `${l.table}:${l.row}` },
    el('th', { scope: 'row' }, labelFor(doc, l.row)), el('td', {}, `${ahead(doc, l.table)} (${l.table})`),
    ...l.cells.map((v) => el('td', {}, v ? badge(v.status) : null, ' ', v ? verdictText(doc, v, false) : '— (itself)')))));
  return section('verdicts', 'Served learned models against the baselines',
    el('p', {}, `Each model the site serves that learns from data (${(doc.served_learned ?? []).join(', ')}) against standing still, the regression GRU and `
      + 'the nearest training window’s future, on held-out people: best-of-K ADE (root-relative) of both rows on the same windows (those the model accepts), with their count. '
      + 'A model beats a baseline when its ADE is lower by more than the 2σ bar and the comparison passes Holm’s correction over the copying comparisons.'),
    el('ul', { class: 'beaten' }, ...VERDICT_LINES(doc).map((x) => el('li', {}, x))),
    wrap(el('table', { class: 'results-table verdicts' }, head('served model', 'ahead', ...bases.map((b) => `vs ${baselineName(doc, b)}`)), body), 'Served learned models against the baselines'));
}

const VERDICT_LINES = (doc: Results) => ['zero-velocity', 'regression-gru', 'nearest-window'].map((b) => beatenLine(doc, b)).filter((x): x is string => x !== null);

function copying(doc: Results): HTMLElement | null {
  if (!doc.copying?.length) return null;
  const body = el('tbody');
  for (const c of doc.copying) {
    body.append(el('tr', { 'data-copying': `${c.table}:${c.row}:${c.baseline}`, 'data-status': c.status },
      el('td', {}, c.table), el('th', { scope: 'row' }, c.label), el('td', {}, c.baseline_label),
      el('td', { class: 'num' }, String(c.items ?? '')),
      el('td', { class: 'num' }, c.a_paired !== undefined ? `${fmt(c.a_paired, 'm')} / ${fmt(c.b_paired, 'm')}` : '—'),
      el('td', { class: 'num' }, fmt(c.difference, 'm')), el('td', { class: 'num' }, fmt(c.bar, 'm')),
      el('td', { class: 'num' }, c.p_holm !== undefined ? fmt(c.p_holm) : '—'),
      el('td', {}, badge(c.status)), el('td', {}, c.verdict)));
  }
  const unscored = doc.tables.filter((t) => t.truth && !t.in_sample).flatMap((t) => t.rows.filter((r) => r.flag && r.kind === 'model').map((r) => `${r.label} in ${t.id} (does not predict: ${r.flag})`));
  return section('copying', 'Copying and memorising',
    el('p', {}, 'Every model against the baselines that copy the history (repeat its last cycle), memorise the training people (the nearest training window’s future), stand still, or regress (the GRU): best-of-K ADE (root-relative) of both rows on the same windows, with their count. A model that does not beat the nearest training window reports memorisation.'),
    wrap(el('table', { class: 'results-table' }, head('table', 'model', 'baseline', 'windows', 'ADE model / baseline (m)', 'difference (m)', '2σ (m)', 'Holm-adjusted p', 'status', 'verdict'), body), 'Copying and memorising'),
    unscored.length ? el('p', { class: 'unscored' }, `Not scored, as their futures are not predictions: ${unscored.join('; ')}.`) : null);
}

function shape(doc: Results): HTMLElement | null {
  if (!doc.shape?.length) return null;
  const body = el('tbody');
  for (const s of doc.shape) {
    const unit = doc.columns[s.metric]?.unit ?? '';
    const t = doc.tables.find((x) => x.id === s.table);
    const win = (id: string) => { const r = t?.rows.find((x) => x.id === id); return r && t ? windowsText(r, t) : '—'; };
    body.append(el('tr', { 'data-shape': `${s.table}:${s.with}:${s.metric}` }, el('th', { scope: 'row' }, s.with), el('td', {}, s.table),
      el('td', { class: 'num' }, `${win(s.with)} / ${win(s.without)}`),
      el('td', {}, doc.columns[s.metric]?.label ?? s.metric), el('td', { class: 'num' }, cell(s.with_value, unit)),
      el('td', { class: 'num' }, cell(s.without_value, unit)), el('td', { class: 'num' }, fmt(s.ratio)),
      el('td', {}, `${s.within ? 'yes' : 'no'}${s.flag ? ` (does not predict: ${s.flag})` : ''}`)));
  }
  return section('shape', 'With and without the shape terms',
    el('p', {}, `Each stochastic model against its ablation without the seam layer, fixed bone lengths and floor term (issue 17): is the model without them within ${Math.round(100 * doc.shape[0].tolerance)}% of the model with them (never, when a row does not predict)? A measurement, not a claim; each row’s windows are beside it.`),
    wrap(el('table', { class: 'results-table' }, head('model', 'table', 'windows (with / without)', 'metric', 'with', 'without', 'without / with', 'within'), body), 'With and without the shape terms'));
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
    wrap(el('table', { class: 'results-table' }, head('check', 'table', 'expected', 'measured', 'result'), body), 'Sanity checks'));
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
    wrap(el('table', { class: 'results-table' }, head('classifier', 'train', 'held-out (snippets)', 'held-out (mean per action)', 'chance'), body), 'Action classifiers'),
    el('h3', {}, 'Held-out accuracy per action (%)'),
    wrap(el('table', { class: 'results-table' }, head('action', ...names), perAction), 'Held-out accuracy per action'),
    ...entries.filter(([, r]) => r.motionless_class).map(([name, r]) =>
      el('p', {}, `A motionless snippet is classified by ${name} as `, el('strong', {}, String(r.motionless_class)), '.')));
}

export function resultsTable(doc: Results, t: Table): HTMLElement {
  // the realism columns have their own table, with the truth's values beside (realism.ts)
  const columns = t.columns.filter((c) => !REALISM.has(c) || !t.truth || Boolean(t.in_sample));
  const headRow = el('tr', {}, el('th', { scope: 'col' }, 'row'), el('th', { scope: 'col' }, 'windows'), el('th', { scope: 'col' }, 'runs'),
    ...columns.map((c) => {
      const col = doc.columns[c];
      const arrow = col.better === 'lower' ? ' ↓' : col.better === 'higher' ? ' ↑' : '';
      return el('th', { scope: 'col', 'data-column': c }, `${col.label}${col.unit ? ` (${col.unit})` : ''}${arrow}`);
    }));
  const body = el('tbody');
  const notes = el('ul', { class: 'notes' });
  for (const r of t.rows) {
    if (r.skipped) {
      body.append(el('tr', { class: 'skipped', 'data-row': r.id }, el('th', { scope: 'row' }, r.label),
        el('td', { colspan: columns.length + 2 }, `skipped: ${r.skipped}`)));
      continue;
    }
    body.append(el('tr', { 'data-row': r.id, class: `kind-${r.kind}${r.flag ? ' flagged' : ''}` }, el('th', { scope: 'row' }, rowLabel(r)),
      el('td', { class: 'num' }, windowsText(r, t)),
      el('td', { class: 'num' }, String(r.runs ?? '')),
      ...columns.map((c) => el('td', { class: 'num' }, cell(r.values?.[c], doc.columns[c].unit)))));
    for (const n of r.notes) notes.append(el('li', {}, `${r.label}: ${n}`));
  }
  for (const n of t.notes) notes.append(el('li', {}, n));
  const people = t.people?.length ? ` · ${t.takes} takes of ${t.people.length} people (${t.people.join(', ')})` : '';
  const mm = t.mmade;
  const acts = t.actions;
  const byAction = t.truth && !t.in_sample && t.rows.some((r) => r.by_action?.ade)
    ? el('details', { class: 'by-action' }, el('summary', {}, 'ADE best of K (root-relative, m) per action'),
      wrap(el('table', { class: 'results-table' }, head('row', ...acts),
        el('tbody', {}, ...t.rows.filter((r) => r.by_action?.ade).map((r) => el('tr', {}, el('th', { scope: 'row' }, rowLabel(r)),
          ...acts.map((a) => el('td', { class: 'num' }, fmt(r.by_action!.ade[a]))))))), `${t.title}: ADE per action`)) : null;
  return el('article', { class: 'table-block', id: `table-${t.id}`, 'data-table': t.id },
    el('h3', {}, t.title, t.in_sample ? el('span', { class: 'in-sample' }, ' (in-sample: backs no claim)') : null),
    el('p', { class: 'table-meta' }, `History ${t.history_frames} frames${t.context_frames && t.context_frames > (t.history_frames ?? 0) ? ` (context up to ${t.context_frames})` : ''} · horizon ${t.horizon_frames} frames (${(t.horizon_frames / doc.fps).toFixed(1)} s) · K = ${t.k}${t.windows ? ` · ${t.windows} windows` : ''}${people}`),
    el('p', {}, t.about),
    t.exceptions?.length ? el('p', { class: 'exceptions' }, `Horizon exceptions (no held-out take holds history + horizon; never padded): ${t.exceptions.map((e) => e.action).join(', ')}.`) : null,
    mm ? el('p', { class: 'mmade-note' }, `MMADE/MMFDE: similar histories lie within ${fmt(mm.threshold)} m of a window’s last pose (median set ${fmt(mm.median_set)}; `
      + `${mm.alone} windows have only themselves and count with their own truth). Sensitivity at ${fmt(mm.half.threshold)} m and ${fmt(mm.double.threshold)} m is in results.json and RESULTS.md.`) : null,
    wrap(el('table', { class: 'results-table main' }, el('thead', {}, headRow), body), t.title),
    byAction, realismTables(doc, t), onAccepted(doc, t),
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
    overview(doc), summary(doc), verdicts(doc), claims(doc), copying(doc), shape(doc), figures(doc),
    section('tables', 'Tables', ...tables.map((t) => resultsTable(doc, t))),
    variants(doc), sanity(doc), classifiers(doc), skipped(doc)].filter((x): x is HTMLElement => x !== null));
}
