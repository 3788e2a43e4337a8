// The model card's content as data: what the clips are, and what the served models can and cannot
// do, read from the measured numbers in results.json (never typed in), so the card follows each
// evaluation run. Pure functions, tested in Node (tests/web/explainer.test.ts).
import type { ClipIndex, Manifest } from '../contract/types';
import PAPERS_BIB from '../../../contract/papers.bib?raw';
import type { Results, Row, Stat, Table } from '../results/data';
import { fmt } from '../results/format';

export interface DataSummary {
  clips: number;
  actions: number;
  fps: number;
  seconds: number;
  /** Seconds of frames in the training parts of the split, and in the test parts. */
  trainSeconds: number;
  testSeconds: number;
  /** Clips that are wholly test (a second take of an action), by action. */
  testOnly: Record<string, string[]>;
}

const span = (ranges: [number, number][]) => ranges.reduce((s, [a, b]) => s + (b - a), 0);

export function dataSummary(index: ClipIndex): DataSummary {
  if (!index.clips.length) throw new Error('clips/index.json lists no clips');
  const frames = index.clips.reduce((s, c) => s + c.frames, 0);
  const testOnly: Record<string, string[]> = {};
  for (const c of index.clips) if (c.role === 'test') (testOnly[c.action] ??= []).push(c.name);
  return {
    clips: index.clips.length,
    actions: new Set(index.clips.map((c) => c.action)).size,
    fps: index.fps,
    seconds: frames / index.fps,
    trainSeconds: index.clips.reduce((s, c) => s + span(c.train), 0) / index.fps,
    testSeconds: index.clips.reduce((s, c) => s + span(c.test), 0) / index.fps,
    testOnly,
  };
}

export type Verdict = 'can' | 'cannot' | 'unknown';

export interface Finding {
  verdict: Verdict;
  text: string;
  /** Where the numbers come from: "results.json, table walker_5s". */
  source: string;
}

const val = (row: Row | undefined, metric: string): Stat | null => row?.values?.[metric] ?? null;
const rowsOf = (t: Table) => t.rows.filter((r) => r.kind === 'model' && !r.skipped && r.values);
const seconds = (frames: number, fps: number) => `${Number((frames / fps).toFixed(2))} s`;
const times = (x: number) => `${x.toFixed(1)}×`;
/** Rows of one trained model (e.g. Keyposes at several temperatures) share its hash. */
const modelKey = (r: Row) => Object.values(r.hashes ?? {})[0] ?? r.id;

function withUnit(results: Results, metric: string, v: number): string {
  const unit = results.columns[metric]?.unit ?? '';
  return `${fmt(v, unit)}${unit ? (unit === '%' ? ' %' : ` ${unit}`) : ''}`;
}

/** Per trained model (e.g. over all Keyposes temperatures), the row with the best value of a metric. */
function bestPerGroup(results: Results, t: Table, metric: string): Row[] {
  const better = results.columns[metric]?.better;
  const best = new Map<string, Row>();
  for (const r of rowsOf(t)) {
    const v = val(r, metric);
    if (!v) continue;
    const cur = best.get(modelKey(r));
    const cv = val(cur, metric);
    if (!cur || !cv || (better === 'higher' ? v.mean > cv.mean : v.mean < cv.mean)) best.set(modelKey(r), r);
  }
  return [...best.values()];
}

/**
 * What the models can and cannot do, each statement with its numbers:
 * - accuracy against the zero-velocity baseline (best of K MPJPE at the table's horizon);
 * - whether a model draws different futures at all (diversity);
 * - how rough its motion is against the captured frames (the smoothness loss, WAT Eq. 4);
 * - how recognisable its futures are against the ground truth (the MOAC classifier);
 * - the paper claims results.json checks, with their status; rows not evaluated, with the reason.
 */
export function findings(results: Results): Finding[] {
  const out: Finding[] = [];
  const fps = results.fps;
  const single = new Set<string>(); // a deterministic model is said to draw one future once, not per table
  for (const t of results.tables) {
    const src = `results.json, table ${t.id}`;
    const where = `${t.title.charAt(0).toLowerCase()}${t.title.slice(1)}`;
    const zero = t.rows.find((r) => r.id === 'zero-velocity' && r.values);
    const oracle = t.rows.find((r) => r.kind === 'oracle' && r.values);
    // The evaluation's paired comparisons against standing still (2σ bar over takes and seeds), when it made them.
    const paired = (results.copying ?? []).filter((c) => c.table === t.id && c.baseline === 'zero-velocity' && c.a_value && c.b_value);
    if (t.truth && paired.length) {
      for (const c of paired) {
        const verdict: Verdict = c.status === 'holds' ? 'can' : c.status === 'fails' ? 'cannot' : 'unknown';
        out.push({ verdict, source: `${src} (paired on its windows, 2σ bar over takes and seeds)`,
          text: `${c.label} ${verdict === 'can' ? 'comes closer to' : verdict === 'cannot' ? 'comes no closer to' : 'is not shown to come closer to'} `
            + `the captured future than standing still: best-of-${t.k} ADE over ${seconds(t.horizon_frames, fps)} ${withUnit(results, 'ade', c.a_value!.mean)} `
            + `against ${withUnit(results, 'ade', c.b_value!.mean)} for zero-velocity (${where}, ${t.windows ?? '?'} histories).` });
      }
    }
    const mpjpe = t.columns.includes('mpjpe_h_best') ? 'mpjpe_h_best' : t.columns.includes('mpjpe_1s_best') ? 'mpjpe_1s_best' : null;
    if (t.truth && zero && mpjpe && !paired.length) {
      const z = val(zero, mpjpe)!;
      for (const r of bestPerGroup(results, t, mpjpe)) {
        if (r.id === zero.id) continue;
        const v = val(r, mpjpe)!;
        const lower = v.mean < z.mean;
        out.push({ verdict: lower ? 'can' : 'cannot', source: src,
          text: `${r.label} ${lower ? 'comes closer to' : 'comes no closer to'} the captured future than standing still: best-of-${r.k ?? t.k} MPJPE `
            + `${mpjpe === 'mpjpe_h_best' ? `at ${seconds(t.horizon_frames, fps)}` : 'over 1 s'} ${withUnit(results, mpjpe, v.mean)} against `
            + `${withUnit(results, mpjpe, z.mean)} for zero-velocity (${where}, ${t.windows ?? '?'} histories).` });
      }
    }
    if (t.columns.includes('div')) {
      for (const r of bestPerGroup(results, t, 'div')) {
        const d = val(r, 'div')!;
        if (d.mean > 0) {
          out.push({ verdict: 'can', source: src, text: `${r.label} draws different futures for one history: diversity ${withUnit(results, 'div', d.mean)} (${where}).` });
        } else if (!single.has(r.label)) {
          single.add(r.label);
          out.push({ verdict: 'cannot', source: src, text: `${r.label} draws a single future: diversity 0 (${where}).` });
        }
      }
    }
    const rough = oracle ? val(oracle, 'smooth') : null;
    if (rough && t.columns.includes('smooth')) {
      const byModel = new Map<string, Row[]>();
      for (const r of rowsOf(t)) {
        const s = val(r, 'smooth');
        if (s && s.mean > 2 * rough.mean) byModel.set(modelKey(r), [...(byModel.get(modelKey(r)) ?? []), r]);
      }
      for (const rows of byModel.values()) {
        const each = rows.map((r) => `${r.label} ${withUnit(results, 'smooth', r.values!.smooth.mean)} (${times(r.values!.smooth.mean / rough.mean)})`);
        out.push({ verdict: 'cannot', source: src, text: `${rows.length > 1 ? `${rows[0].label.replace(/\s*\(.*\)$/, '')} at every setting` : rows[0].label} moves more `
          + `roughly than captured motion: smoothness loss (WAT Eq. 4) ${each.join(', ')}, against ${withUnit(results, 'smooth', rough.mean)} for the captured frames (${where}).` });
      }
    }
    const acc = oracle ? val(oracle, 'acc_moac') : null;
    if (acc && acc.mean > 0) {
      for (const r of rowsOf(t)) {
        const a = val(r, 'acc_moac');
        if (a && a.mean < 0.5 * acc.mean) {
          out.push({ verdict: 'cannot', source: src, text: `${r.label}'s futures are seldom recognised as the history's action: MOAC accuracy `
            + `${withUnit(results, 'acc_moac', a.mean)} against ${withUnit(results, 'acc_moac', acc.mean)} for the captured future (${where}).` });
        }
      }
    }
    const skipped = new Map<string, string[]>();
    for (const r of t.rows) if (r.skipped) skipped.set(r.skipped, [...(skipped.get(r.skipped) ?? []), r.label]);
    for (const [reason, labels] of skipped) {
      out.push({ verdict: 'unknown', source: src, text: `${labels.join(', ')}: not measured in ${where}: ${reason}.` });
    }
  }
  for (const c of results.claims) {
    const nums = c.parts.filter((p) => p.a_value && p.b_value).map((p) => {
      const a = rowLabel(results, p.table, p.a);
      const b = rowLabel(results, p.table, p.b);
      return `${a} ${withUnit(results, p.metric, p.a_value!.mean)} vs ${b} ${withUnit(results, p.metric_b, p.b_value!.mean)} (${results.columns[p.metric]?.label ?? p.metric})`;
    });
    const verdict: Verdict = c.status === 'holds' ? 'can' : c.status === 'fails' ? 'cannot' : 'unknown';
    out.push({ verdict, source: `results.json, claim ${c.id}`,
      text: `${c.paper}: “${c.text}” — ${c.status} here${nums.length ? `: ${nums.join('; ')}` : ''}.` });
  }
  for (const s of results.skipped) out.push({ verdict: 'unknown', source: 'results.json, skipped', text: `${s.label}: not evaluated (${s.reason}).` });
  return out;
}

/** Statements that repeat per model, merged into one per table: the subject, and the text around it. */
const MERGEABLE: { re: RegExp; lead: (m: RegExpExecArray) => string }[] = [
  { re: /^(.+?) (comes closer to|comes no closer to|is not shown to come closer to) the captured future than standing still: (best-of-\d+ (?:MPJPE|ADE) (?:at|over) [^ ]+ s) (.+?) against (.+?) for zero-velocity \((.+)\)\.$/,
    lead: (m) => `${m[2] === 'comes closer to' ? 'Closer to' : m[2] === 'comes no closer to' ? 'No closer to' : 'Not shown closer to'} the captured future than standing still (${m[3]}; zero-velocity ${m[5]}; ${m[6]})` },
  { re: /^(.+?) (draws different futures for one history): diversity (.+?) \((.+)\)\.$/,
    lead: (m) => `Different futures for one history (diversity; ${m[4]})` },
  { re: /^(.+?) (draws a single future): diversity 0 \((.+)\)\.$/, lead: (m) => `A single future (diversity 0; ${m[3]})` },
  { re: /^(.+?)'s futures are (seldom recognised as the history's action): MOAC accuracy (.+?) against (.+?) for the captured future \((.+)\)\.$/,
    lead: (m) => `Futures seldom recognised as the history's action (MOAC accuracy; captured future ${m[4]}; ${m[5]})` },
];

/**
 * The findings with statements that repeat per model merged: one bullet per kind of statement and
 * table ("Different futures for one history (diversity; test split): WAT (RNN) 0.373 m, …"), in the
 * order the first of each appeared. Statements of one model stay as they are.
 */
export function mergeFindings(list: Finding[]): Finding[] {
  const out: Finding[] = [];
  const groups = new Map<string, { at: number; verdict: Verdict; lead: string; items: string[]; sources: Set<string> }>();
  for (const f of list) {
    let merged = false;
    for (const [i, { re, lead }] of MERGEABLE.entries()) {
      const m = re.exec(f.text);
      if (!m) continue;
      const value = i === 0 ? m[4] : i === 1 ? m[3] : i === 2 ? null : m[3];
      const key = `${f.verdict}|${i}|${lead(m)}`;
      let g = groups.get(key);
      if (!g) {
        g = { at: out.length, verdict: f.verdict, lead: lead(m), items: [], sources: new Set() };
        groups.set(key, g);
        out.push({ verdict: f.verdict, text: '', source: '' });
      }
      g.items.push(value ? `${m[1]} ${value}` : m[1]);
      g.sources.add(f.source);
      merged = true;
      break;
    }
    if (!merged) out.push(f);
  }
  for (const g of groups.values()) {
    out[g.at] = { verdict: g.verdict, text: `${g.lead}: ${g.items.join(', ')}.`, source: [...g.sources].join('; ') };
  }
  return out;
}

/**
 * The card's summary, five lines at most: results.json's own `summary` when the evaluation writes
 * one, else lines drawn from the same findings the card lists (what was served and measured, how
 * many models beat standing still, which draw different futures, how the paper claims fare).
 */
export function cardSummary(results: Results | null, manifest: Manifest | null, index: ClipIndex): string[] {
  if (results?.summary?.length) return results.summary.slice(0, 5);
  const d = dataSummary(index);
  const lines = [`Trained and tested on ${d.clips} motion clips (${d.seconds.toFixed(0)} s, ${d.actions} actions); `
    + `${d.testSeconds.toFixed(0)} s are held out for testing.`];
  if (manifest) lines.push(`${manifest.models.length} models are served: ${manifest.models.map((m) => m.label).join('; ')}.`);
  if (!results) return [...lines, 'The measured numbers (results.json) could not be loaded.'];
  const all = findings(results);
  const closer = all.filter((f) => / comes closer to the captured future/.test(f.text));
  const notCloser = all.filter((f) => / comes no closer to the captured future/.test(f.text));
  const name = (f: Finding) => f.text.replace(/ comes (no )?closer to.*$/, '');
  if (closer.length || notCloser.length) {
    lines.push(`Closer to the captured future than standing still: ${[...new Set(closer.map(name))].join(', ') || 'none'}; `
      + `not closer: ${[...new Set(notCloser.map(name))].join(', ') || 'none'}.`);
  }
  const diverse = [...new Set(all.filter((f) => / draws different futures/.test(f.text)).map((f) => f.text.replace(/ draws different futures.*$/, '')))];
  if (diverse.length) lines.push(`${diverse.length} of the measured rows draw different futures for one history; the baselines draw one.`);
  const count = (s: string) => results.claims.filter((c) => c.status === s).length;
  lines.push(`Of ${results.claims.length} paper claims tested, ${count('holds')} hold here, ${count('fails')} fail and ${results.claims.length - count('holds') - count('fails')} are inconclusive.`);
  return lines.slice(0, 5);
}

function rowLabel(results: Results, table: string, row: string): string {
  return results.tables.find((x) => x.id === table)?.rows.find((r) => r.id === row)?.label ?? row;
}

/** Served models whose hash differs from the one results.json measured (or that it did not measure). */
export function staleModels(results: Results, manifest: Manifest): { label: string; problem: string }[] {
  return manifest.models.flatMap((m) => {
    const measured = results.models[m.id];
    if (!measured) return [{ label: m.label, problem: 'not in results.json: no measured numbers for it yet' }];
    if (measured !== m.hash) {
      return [{ label: m.label, problem: `results.json measured version ${measured.replace(/^sha256:/, '').slice(0, 12)}, `
        + `the site serves ${m.hash.replace(/^sha256:/, '').slice(0, 12)}: its numbers below describe the earlier version` }];
    }
    return [];
  });
}

/** The classifiers behind the recognition numbers, and where they fail on test motion. */
export function classifierCaveats(results: Results): string[] {
  const out: string[] = [];
  for (const [id, c] of Object.entries(results.classifiers)) {
    if (id.endsWith('_shuffled')) continue;
    const zero = Object.entries(c.test_groups).filter(([, g]) => g.accuracy === 0).map(([n, g]) => `${n.replace(/_/g, ' ')} (${g.snippets} snippets)`);
    out.push(`${id === 'moac' ? 'MOAC (motion only)' : id === 'pose_gru' ? 'Pose GRU' : id.replace(/_/g, ' ')}: test accuracy ${fmt(c.test_accuracy, '%')} %, balanced `
      + `${fmt(c.test_balanced_accuracy, '%')} % over ${c.classes} actions (chance ${fmt(c.chance, '%')} %)`
      + `${zero.length ? `; it recognises none of ${zero.join(', ')}` : ''}.`);
  }
  return out;
}

/**
 * The failure modes seen in the measured numbers, each with them; an item whose numbers are not in
 * results.json (a later evaluation without that table or row) is left out rather than guessed.
 */
export function failureModes(results: Results | null, index: ClipIndex, manifest: Manifest | null): string[] {
  const out: string[] = [];
  const row = (table: string, id: string) => results?.tables.find((x) => x.id === table)?.rows.find((r) => r.id === id && r.values);
  const v = (table: string, id: string, metric: string) => val(row(table, id), metric)?.mean;
  const u = (metric: string, x: number) => (results ? withUnit(results, metric, x) : String(x));
  const walker = 'walker_5s';
  const [zMoac, oMoac] = [v(walker, 'zero-velocity', 'acc_moac'), v(walker, 'oracle', 'acc_moac')];
  if (zMoac !== undefined && oMoac !== undefined && zMoac >= oMoac) {
    out.push(`Standing still scores well: a future that does not move is recognised as walking by the motion-only classifier as often as `
      + `the captured future (MOAC accuracy ${u('acc_moac', zMoac)} against ${u('acc_moac', oMoac)} on the walker test clips). High recognition `
      + 'accuracy alone does not mean lifelike motion.');
  }
  const [gSpeed, oSpeed, gErr, zErr] = [v(walker, 'regression-gru', 'speed'), v(walker, 'oracle', 'speed'),
    v(walker, 'regression-gru', 'mpjpe_h_best'), v(walker, 'zero-velocity', 'mpjpe_h_best')];
  if (gSpeed !== undefined && oSpeed !== undefined && gErr !== undefined && zErr !== undefined) {
    out.push(`The regression GRU does not settle into a walk: 5 s ahead its pose is ${u('mpjpe_h_best', gErr)} from the captured one `
      + `(zero-velocity: ${u('mpjpe_h_best', zErr)}) and in the last second its joints move at ${u('speed', gSpeed)}, against `
      + `${u('speed', oSpeed)} in the captured walking.`);
  }
  const kp = results?.tables.find((x) => x.id === walker)?.rows.filter((r) => r.group === 'keyposes' && r.values?.smooth) ?? [];
  const oSmooth = v(walker, 'oracle', 'smooth');
  if (kp.length && oSmooth) {
    const ratios = kp.map((r) => r.values!.smooth.mean / oSmooth);
    out.push(`Keyposes moves roughly: it goes from one cluster-centre pose to the next, and its smoothness loss (WAT Eq. 4) is `
      + `${times(Math.min(...ratios))} to ${times(Math.max(...ratios))} that of captured walking (${kp.map((r) => `${r.label} ${u('smooth', r.values!.smooth.mean)}`).join(', ')}; `
      + `captured ${u('smooth', oSmooth)}).`);
  }
  const testActions = [...new Set(index.clips.filter((c) => c.test.length).map((c) => c.action.replace(/_/g, ' ')))];
  const allActions = new Set(index.clips.map((c) => c.action)).size;
  out.push(`Only ${testActions.length} of ${allActions} actions have test motion (${testActions.join(', ')}): no number here says how the models do `
    + 'on the others, whose histories can only come from training clips (in-sample).');
  if (manifest) {
    const longest = Math.max(...manifest.models.map((m) => m.params.history_frames));
    const short = index.clips.filter((c) => c.frames < longest && !c.loops).map((c) => c.name.replace(/_/g, ' '));
    if (short.length) out.push(`Clips shorter than the longest history (${longest} frames) cannot give that model a history: ${short.join(', ')}.`);
  }
  const memo = (results?.copying ?? []).filter((c) => c.baseline === 'nearest-window' && c.status !== 'holds');
  if (memo.length) {
    out.push(`Not shown to beat the nearest training window's future on held-out people (memorisation is not ruled out): `
      + `${[...new Set(memo.map((c) => `${c.label} (${c.table})`))].join(', ')}.`);
  }
  out.push('Few people per action: a model has seen a few ways to do each action, and the held-out people are few; a comparison '
    + 'resting on too few people or takes is reported as insufficient data.');
  out.push('Skeletons have 18 joints, without hands, foot orientation or face.');
  return out;
}

/** A few of each table's columns for the card (the Results page has them all). */
export const CARD_COLUMNS = ['ade', 'fde', 'mpjpe_h_best', 'mpjpe_1s_best', 'apd', 'div', 'acc_moac', 'smooth', 'length'];

export function cardColumns(t: Table): string[] {
  const cols = CARD_COLUMNS.filter((c) => t.columns.includes(c));
  // At a 1 s horizon MPJPE "horizon" and "1 s" are the same number: keep one.
  return t.horizon_frames <= 30 ? cols.filter((c) => c !== 'mpjpe_h_best') : cols.filter((c) => c !== 'mpjpe_1s_best');
}

/** The papers and the data, shared with the generated docs/MODEL_CARD.md (export/eval/card.py). */
export const PAPERS_BIBTEX = PAPERS_BIB.replace(/^%.*\n/gm, '').trim();

/** This project's BibTeX; the version comes from the site (package.json at build time). */
export function projectBibtex(version: string): string {
  return `@software{motion_futures,
  title   = {motion futures: stochastic human motion prediction in the browser},
  author  = {{motion-futures contributors}},
  version = {${version}},
  year    = {2026},
  license = {MIT},
  note    = {WAT, LCP-VAE and Keyposes on DeepMimic motion capture, run with onnxruntime-web}
}`;
}
