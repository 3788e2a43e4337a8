// Motion realism on the Results page (Evaluation v3): per table, the realism measures of the served models
// and baselines over each row's windows, then per action group over the group's windows, the truth's
// value beside a row only where both are on the same windows; and a row that refuses windows set beside
// the truth and the baselines on exactly the windows it accepts. docs/RESULTS.md has the same tables
// (export/eval/report.py, section "Motion realism").
import type { Results, Row, Stat, Table } from './data';
import { el } from './dom';
import { fmt } from './format';
import { refusedOf, rowLabel, windowsText } from './rows';

// a wide table scrolls in its box, which the keyboard can reach (axe: scrollable-region-focusable)
const wrap = (table: HTMLElement, label = 'Table') => el('div', { class: 'table-wrap', tabindex: 0, role: 'region', 'aria-label': label }, table);
const head = (...names: string[]) => el('thead', {}, el('tr', {}, ...names.map((h) => el('th', { scope: 'col' }, h))));

/** The rows a realism table shows: the ground truth, the baselines and the served models. */
export function realismRows(doc: Results, t: Table): Row[] {
  return t.rows.filter((r) => r.values && !r.skipped
    && (r.kind === 'oracle' || r.kind === 'baseline' || (r.kind === 'model' && r.id in doc.models)));
}

/** The share of windows a calibrated sampler of K futures leaves the truth outside: 100/(K+1). */
export const calibrated = (r: Row) => ((r.k ?? 1) > 1 ? fmt(100 / ((r.k ?? 1) + 1), '%') : '—');

type Group = { items: number; people: number; takes: number; values: Record<string, Stat> };

/** A row's windows in a group: the items of its per-item values there, of the group's. */
export function groupWindows(g: Group): number {
  for (const c of ['mpjpe_cm', 'ade', 'length']) if (g.values[c]) return g.values[c].n;
  return 0;
}

const plural = (n: number, one: string, many = `${one}s`) => `${n} ${n === 1 ? one : many}`;

/** One realism table: a line per row with its windows, its values and the truth's beside them on the same windows. */
function realismTable(t: Table, rows: Row[], line: (r: Row) => { windows: string; value: (c: string) => string; truth: (c: string) => string },
  jump: boolean, group = ''): HTMLElement {
  const joint = t.columns.filter((c) => c.startsWith('speed_ratio_s'));
  const root = t.columns.filter((c) => c.startsWith('root_ratio_s'));
  const body = el('tbody', {}, ...rows.map((r) => {
    const { windows, value, truth } = line(r);
    const cells = [value('mpjpe_cm'), value('mpjpe_f_cm'), value('ade'), joint.map(value).join(' · ') || '—', root.map(value).join(' · ') || '—',
      value('follow'), truth('follow'), value('skate'), truth('skate'), value('outside'), calibrated(r), value('spread_cm'), value('full'),
      ...(jump ? [value('hip_range'), truth('hip_range')] : [])];
    return el('tr', { 'data-row': r.id }, el('th', { scope: 'row' }, rowLabel(r)), el('td', { class: 'num' }, windows),
      ...cells.map((x) => el('td', { class: 'num' }, x)));
  }));
  return wrap(el('table', { class: 'results-table realism', 'data-group': group || undefined },
    head('row', 'windows', 'per joint (cm)', 'per joint at the horizon (cm)', 'ADE (m)', 'joint speed / truth’s, by second (×)',
      'root speed / truth’s, by second (×)', 'ρ', 'truth’s ρ', 'skating (m/s)', 'captures’ skating (m/s)', 'truth outside (%)',
      'calibrated 100/(K+1) (%)', 'spread (cm)', 'full length (%)', ...(jump ? ['hip range (m)', 'captures’ hip range (m)'] : [])), body), `${t.title}: motion realism${group ? `, ${group}` : ''}`);
}

const unitOf = (doc: Results, c: string) => doc.columns[c]?.unit ?? '';

/** The truth's value of `col` on exactly the windows `r` predicts: the oracle's when it predicts them all, its `paired` value else. */
export function truthBeside(t: Table, r: Row, col: string, unit = ''): string {
  if (r.kind === 'oracle') return '—';
  if (!refusedOf(r, t)) return fmt(t.rows.find((x) => x.kind === 'oracle')?.values?.[col]?.mean ?? null, unit);
  const x = r.paired?.rows.oracle?.[col];
  return x === undefined || x === null ? '—' : fmt(x, unit);
}

/** Motion realism of a table's served models and baselines over each row's windows, then per action group (means; the bars are in results.json). */
export function realismTables(doc: Results, t: Table): HTMLElement | null {
  if (!t.truth || t.in_sample) return null;
  const rows = realismRows(doc, t);
  if (!rows.length || !t.columns.includes('mpjpe_cm')) return null;
  const overall = realismTable(t, rows, (r) => ({ windows: windowsText(r, t), value: (c) => (r.values?.[c] ? fmt(r.values[c].mean, unitOf(doc, c)) : '—'),
    truth: (c) => truthBeside(t, r, c, unitOf(doc, c)) }), false);
  const order = doc.data?.groups ?? [...new Set(rows.flatMap((r) => Object.keys(r.by_group ?? {})))];
  const truth = t.rows.find((r) => r.kind === 'oracle');
  const blocks = order.flatMap((name) => {
    const have = rows.filter((r) => r.by_group?.[name]);
    if (!have.length) return [];
    const g0 = have[0].by_group![name];
    const tv = truth?.by_group?.[name]?.values ?? {};
    const table = realismTable(t, have, (r) => {
      const g = r.by_group![name];
      // the truth beside a row only where the row predicts every window of the group
      const whole = groupWindows(g) === g.items && r.kind !== 'oracle';
      return { windows: `${groupWindows(g)}/${g.items}`, value: (c) => (g.values[c] ? fmt(g.values[c].mean, unitOf(doc, c)) : '—'),
        truth: (c) => (whole && tv[c] ? fmt(tv[c].mean, unitOf(doc, c)) : '—') };
    }, name === 'jump', name);
    return [el('h4', { 'data-group': name }, `${name}: ${plural(g0.items, 'window')}, ${plural(g0.people, 'person', 'people')}, ${plural(g0.takes, 'take')}`), table];
  });
  return el('details', { class: 'realism-groups' }, el('summary', {}, 'Motion realism, overall and per action group'),
    el('p', {}, 'Over each row’s own windows (their count beside it; means, the bars are in results.json and RESULTS.md). The truth’s value stands beside a row only where both are on the same windows; the hip’s vertical range is read for jump.'),
    overall, ...blocks);
}

/** Each row that refuses windows beside the truth and the baselines on exactly the windows it accepts. */
export function onAccepted(doc: Results, t: Table): HTMLElement | null {
  const blocks = t.rows.filter((r) => r.paired && Object.keys(r.paired.rows).length).map((r) => {
    const paired = r.paired!;
    const order = [r.id, ...Object.keys(paired.rows).filter((x) => x !== r.id)];
    const cols = Object.keys(doc.columns).filter((c) => order.some((x) => paired.rows[x]?.[c] !== undefined));
    const label = (c: string) => `${doc.columns[c].label}${doc.columns[c].unit ? ` (${doc.columns[c].unit})` : ''}`;
    return el('div', { class: 'on-accepted', 'data-row': r.id },
      el('p', {}, `${r.label} predicts ${paired.items} of the ${t.items ?? t.windows} windows; on exactly those windows, beside the truth and the baselines:`),
      wrap(el('table', { class: 'results-table' }, head('row', ...cols.map(label)),
        el('tbody', {}, ...order.map((x) => el('tr', {}, el('th', { scope: 'row' }, t.rows.find((y) => y.id === x)?.label ?? x),
          ...cols.map((c) => el('td', { class: 'num' }, fmt(paired.rows[x]?.[c] ?? null, doc.columns[c].unit)))))), `${t.title}: on the windows ${r.label} accepts`)));
  });
  return blocks.length ? el('details', { class: 'accepted' }, el('summary', {}, 'On the windows each refusing row accepts'), ...blocks) : null;
}
