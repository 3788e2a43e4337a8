// The served learned models against the baselines (results.json `verdicts`, Evaluation v3): each verdict
// beside its paired numbers, both rows on the same windows with their count, and in plain words which
// models are shown to beat each baseline. The Results page and the Model card page both print these;
// export/eval/report.py writes the same sentences into docs/RESULTS.md and docs/MODEL_CARD.md.
import type { Results, Row, Table, Verdict } from './data';
import { fmt } from './format';

export const VERDICT_BASELINES = ['zero-velocity', 'regression-gru', 'nearest-window'];

/** What a copying status says of a model against a baseline, after Holm. */
const WORDS: Record<string, string> = {
  holds: 'beats', 'no difference': 'is no different from', fails: 'is worse than',
  inconclusive: 'is not shown to beat', 'insufficient data': 'is not shown to beat', 'not evaluated': 'was not compared with',
};

export const tableOf = (doc: Results, id: string): Table | undefined => doc.tables.find((t) => t.id === id);
export const rowOf = (t: Table | undefined, id: string): Row | undefined => t?.rows.find((r) => r.id === id);

/** A row's label wherever results.json names it (a table, or the rows not evaluated), else its id. */
export function labelFor(doc: Results, id: string): string {
  for (const t of doc.tables) {
    const r = rowOf(t, id);
    if (r) return r.label;
  }
  return doc.skipped.find((s) => s.row === id)?.label ?? id;
}

/** How far ahead a table predicts: "2 s". */
export function ahead(doc: Results, tableId: string): string {
  const t = tableOf(doc, tableId);
  return t ? `${Number((t.horizon_frames / doc.fps).toFixed(2))} s` : tableId;
}

/** Why the verdict's model does not predict in its table, or "". */
export const flagOf = (doc: Results, v: Verdict): string => rowOf(tableOf(doc, v.table), v.row)?.flag ?? '';

/** The numbers a verdict rests on: both rows' ADE on the same windows, with their count. */
export function verdictNumbers(doc: Results, v: Verdict): string {
  if (v.a_paired === null || v.a_paired === undefined || v.b_paired === null || v.b_paired === undefined) return 'no windows both predict';
  const c = (doc.copying ?? []).find((x) => x.row === v.row && x.table === v.table && x.baseline === v.baseline);
  const holm = c?.p_holm !== undefined ? `, Holm-adjusted p ${fmt(c.p_holm)}` : '';
  return `${fmt(v.a_paired, 'm')} m against ${fmt(v.b_paired, 'm')} m on the same ${v.items} windows, `
    + `difference ${fmt(v.difference, 'm')} m, 2σ ${fmt(v.bar, 'm')} m${holm}`;
}

/** One verdict beside its paired numbers: "beats (holds): 0.700 m against 0.800 m on the same 97 windows, …"
 * (the status in brackets left out where a badge beside it says it). */
export function verdictText(doc: Results, v: Verdict, withStatus = true): string {
  const flag = flagOf(doc, v);
  if (flag) return `does not predict: ${flag}`;
  return `${WORDS[v.status] ?? v.status}${withStatus ? ` (${v.status})` : ''}: ${verdictNumbers(doc, v)}`;
}

/** "zero-velocity", "the regression GRU", "the nearest training window": a baseline inside a sentence. */
export function baselineName(doc: Results, base: string): string {
  const name = labelFor(doc, base);
  return name.toLowerCase().startsWith('zero') ? name.toLowerCase() : `the ${name.charAt(0).toLowerCase()}${name.slice(1)}`;
}

const unique = <T>(xs: T[]) => [...new Set(xs)];

/** In plain words, which served learned models are shown to beat one baseline, and at which horizons. */
export function beatenLine(doc: Results, base: string): string | null {
  const vs = (doc.verdicts ?? []).filter((v) => v.baseline === base);
  if (!vs.length) return null;
  const horizons = unique(vs.map((v) => v.table)).map((t) => ahead(doc, t)).join(' or ');
  const beats: string[] = [], rest: string[] = [], missing: string[] = [], flagged: string[] = [];
  for (const row of unique(vs.map((v) => v.row))) {
    const mine = vs.filter((v) => v.row === row);
    const won = mine.filter((v) => v.status === 'holds').map((v) => ahead(doc, v.table));
    const label = labelFor(doc, row);
    if (mine.some((v) => flagOf(doc, v))) flagged.push(label);
    else if (won.length) beats.push(`${label} at ${won.join(' and ')}`);
    else if (mine.every((v) => v.status === 'not evaluated')) missing.push(label);
    else rest.push(label);
  }
  const name = baselineName(doc, base);
  const how = 'best-of-K ADE on the same windows, after Holm';
  let text = beats.length
    ? `Shown to beat ${name} (${how}): ${beats.join('; ')}${rest.length ? `; not shown at ${horizons}: ${rest.join(', ')}` : ''}`
    : `No served learned model is shown to beat ${name} at ${horizons} (${how}${rest.length ? `; compared: ${rest.join(', ')})` : ')'}`;
  if (missing.length) text += `; not evaluated: ${missing.join(', ')}`;
  if (flagged.length) text += `; not scored, as they do not predict: ${flagged.join(', ')}`;
  return `${text}.`;
}

/** The verdicts grouped for a table: one line per served model and held-out table, a cell per baseline. */
export function verdictGrid(doc: Results): { bases: string[]; lines: { row: string; table: string; cells: (Verdict | null)[] }[] } {
  const vs = doc.verdicts ?? [];
  const bases = VERDICT_BASELINES.filter((b) => vs.some((v) => v.baseline === b));
  const lines = unique(vs.map((v) => v.row)).flatMap((row) => unique(vs.filter((v) => v.row === row).map((v) => v.table))
    .map((table) => ({ row, table, cells: bases.map((b) => vs.find((v) => v.row === row && v.table === table && v.baseline === b) ?? null) })));
  return { bases, lines };
}
