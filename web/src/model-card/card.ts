// The model card's content as data: what the clips are, and what the served models can and cannot
// do, read from the measured numbers in results.json (never typed in), so the card follows each
// evaluation run. Pure functions, tested in Node (tests/web/explainer.test.ts).
import type { ClipIndex, Manifest, ModelEntry } from '../contract/types';
import PAPERS_BIB from '../../../contract/papers.bib?raw';
import type { Results, Row, Stat, Table } from '../results/data';
import { fmt } from '../results/format';
import { refusedOf } from '../results/rows';
import { ahead, beatenLine, flagOf, labelFor, VERDICT_BASELINES, verdictNumbers } from '../results/verdicts';

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

/** The card's data section, from results.json's `data` (the people, takes and seconds the models learned from
 * and are tested on), never from the clips this site serves. Null when results.json has no data summary. */
export interface DataFacts {
  lines: string[];
  actions: { action: string; group: string; train: [number, number, number]; test: [number, number, number] }[];
}

const secs = (x: number) => (x >= 100 ? x.toFixed(0) : x.toFixed(1));

export function dataFacts(results: Results | null): DataFacts | null {
  const d = results?.data;
  if (!d) return null;
  const train = d.train_people_list ?? [];
  const lines = [
    `${d.clips} takes of ${d.actions} actions, ${d.joints} joints in metres at ${d.fps} frames per second, in the world frame (the root travels over the floor).`,
    `Held out: ${d.heldout_people.length} people (subjects ${d.heldout_people.join(', ')}) give ${d.heldout_takes} takes (${secs(d.heldout_seconds)} s) of `
      + `${d.heldout_actions.length} actions (${d.heldout_actions.map(pretty).join(', ')}); no model saw them, and every claim rests on them alone.`,
    `Training: ${train.length || d.train_people} other performers${train.length ? ` (${train.join(', ')})` : ''} give ${d.train_takes} takes (${secs(d.train_seconds)} s).`
      + (d.balance ? ` Balance: ${d.balance}.` : ''),
  ];
  if (d.train_only_actions?.length) {
    lines.push(`Trained on but never tested (no held-out person performs them): ${d.train_only_actions.map(pretty).join(', ')}; no number here says how the models do on them.`);
  }
  const actions = Object.entries(d.per_action ?? {}).map(([action, x]) => ({ action, group: x.group,
    train: [x.train.people.length, x.train.takes, x.train.seconds] as [number, number, number],
    test: [x.test.people.length, x.test.takes, x.test.seconds] as [number, number, number] }));
  return { lines, actions };
}

const pretty = (s: string) => s.replace(/_/g, ' ');

/** Which paper each served method comes from (contract/papers.bib key); the baselines come from none. */
const PAPER_KEYS: Record<string, string> = { wat: 'mao2022weakly', wat_transformer: 'mao2022weakly', lcp_vae: 'aliakbarian2021contextually', keyposes: 'kiciroglu2022keyposes' };
const PAPER_SHORT: Record<string, string> = { mao2022weakly: 'Mao, Liu, Salzmann, CVPR 2022', aliakbarian2021contextually: 'Aliakbarian et al., ICCV 2021', kiciroglu2022keyposes: 'Kiciroglu, Wang, Salzmann, Fua, 3DV 2022' };

/** A paper's title as contract/papers.bib gives it. */
export function paperTitle(key: string, bib: string = PAPERS_BIB): string | null {
  const entry = new RegExp(`@\\w+\\{${key},([\\s\\S]*?)\\n\\}`).exec(bib);
  return entry ? /title\s*=\s*\{(.+?)\},?\s*$/m.exec(entry[1])?.[1] ?? null : null;
}

/** The paper a served method comes from, by its name: "Weakly-supervised Action … (Mao, Liu, Salzmann, CVPR 2022)". */
export function paperOf(method: string): string {
  const key = PAPER_KEYS[method];
  if (!key) return 'baseline (no paper)';
  return `${paperTitle(key) ?? key} (${PAPER_SHORT[key]})`;
}

/** How far a served model predicts by default: its horizon control's default (seconds), else its future frames. */
export function horizonFrames(m: ModelEntry, fps: number): number {
  const c = m.controls.find((x) => x.id === 'horizon');
  return typeof c?.default === 'number' ? Math.round(c.default * fps) : m.params.future_frames;
}

export type Verdict = 'can' | 'cannot' | 'unknown';

export interface Finding {
  verdict: Verdict;
  text: string;
  /** Where the numbers come from: "results.json, table heldout_5s". */
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

/** How many of the table's windows a row predicts, and whether that is all of them. */
const predictsAll = (r: Row, t: Table) => refusedOf(r, t) === 0;

/** The captured frames' value of `metric` on exactly the windows `r` predicts, or null when results.json
 * does not hold it (a row that refuses windows has the truth's values on its windows only in `paired`). */
export function truthOn(t: Table, r: Row, metric: string): number | null {
  const oracle = t.rows.find((x) => x.kind === 'oracle' && x.values);
  if (predictsAll(r, t)) return val(oracle, metric)?.mean ?? null;
  const x = r.paired?.rows.oracle?.[metric];
  return x === undefined || x === null ? null : x;
}

/**
 * What the models can and cannot do, each statement with its numbers, every pair on the same windows:
 * - the served learned models against standing still (results.json `verdicts`: best-of-K ADE, paired, after Holm);
 * - whether a model draws different futures at all (diversity);
 * - how rough its motion is against the captured frames on its windows (the smoothness loss, WAT Eq. 4);
 * - how recognisable its futures are against the captured ones on its windows (the MOAC classifier);
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
    // The evaluation's own paired verdicts against standing still: both rows on the model's windows, after Holm.
    const verdicts = (results.verdicts ?? []).filter((v) => v.table === t.id && v.baseline === 'zero-velocity' && v.a_paired !== null && !flagOf(results, v));
    for (const v of verdicts) {
      const verdict: Verdict = v.status === 'holds' ? 'can' : v.status === 'fails' ? 'cannot' : 'unknown';
      out.push({ verdict, source: `${src}, verdicts (paired on the model's windows, after Holm)`,
        text: `${labelFor(results, v.row)} ${verdict === 'can' ? 'comes closer to' : verdict === 'cannot' ? 'comes no closer to' : 'is not shown to come closer to'} `
          + `the captured future than standing still: best-of-${t.k} ADE over ${seconds(t.horizon_frames, fps)} ${withUnit(results, 'ade', v.a_paired!)} `
          + `against ${withUnit(results, 'ade', v.b_paired!)} for zero-velocity on the same ${v.items} windows (${where}).` });
    }
    // Older results have no verdicts: an unpaired mean only for rows that predict every window zero-velocity does.
    const mpjpe = t.columns.includes('mpjpe_h_best') ? 'mpjpe_h_best' : t.columns.includes('mpjpe_1s_best') ? 'mpjpe_1s_best' : null;
    if (t.truth && zero && mpjpe && !results.verdicts && predictsAll(zero, t)) {
      const z = val(zero, mpjpe)!;
      for (const r of bestPerGroup(results, t, mpjpe)) {
        if (r.id === zero.id || !predictsAll(r, t) || r.flag) continue;
        const v = val(r, mpjpe)!;
        const lower = v.mean < z.mean;
        out.push({ verdict: lower ? 'can' : 'cannot', source: src,
          text: `${r.label} ${lower ? 'comes closer to' : 'comes no closer to'} the captured future than standing still: best-of-${r.k ?? t.k} MPJPE `
            + `${mpjpe === 'mpjpe_h_best' ? `at ${seconds(t.horizon_frames, fps)}` : 'over 1 s'} ${withUnit(results, mpjpe, v.mean)} against `
            + `${withUnit(results, mpjpe, z.mean)} for zero-velocity on the same ${t.items ?? t.windows ?? '?'} windows (${where}).` });
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
    if (oracle && t.columns.includes('smooth')) {
      const byModel = new Map<string, string[]>();
      for (const r of rowsOf(t)) {
        const s = val(r, 'smooth');
        const rough = truthOn(t, r, 'smooth');
        if (s && rough && s.mean > 2 * rough) {
          byModel.set(modelKey(r), [...(byModel.get(modelKey(r)) ?? []),
            `${r.label} ${withUnit(results, 'smooth', s.mean)} against ${withUnit(results, 'smooth', rough)} (${times(s.mean / rough)}) on its ${r.items ?? t.items} windows`]);
        }
      }
      for (const [key, each] of byModel) {
        const first = rowsOf(t).find((r) => modelKey(r) === key)!;
        out.push({ verdict: 'cannot', source: src, text: `${each.length > 1 ? `${first.label.replace(/\s*\(.*\)$/, '')} at every setting` : first.label} moves more `
          + `roughly than captured motion on the same windows: smoothness loss (WAT Eq. 4) ${each.join(', ')} (${where}).` });
      }
    }
    if (oracle && val(oracle, 'acc_moac')) {
      for (const r of rowsOf(t)) {
        const a = val(r, 'acc_moac');
        const truth = truthOn(t, r, 'acc_moac');
        if (a && truth && truth > 0 && a.mean < 0.5 * truth) {
          out.push({ verdict: 'cannot', source: src, text: `${r.label}'s futures are seldom recognised as the history's action: MOAC accuracy `
            + `${withUnit(results, 'acc_moac', a.mean)} against ${withUnit(results, 'acc_moac', truth)} for the captured future on the same ${r.items ?? t.items} windows (${where}).` });
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
    const nums = c.parts.filter((p) => p.a_paired !== undefined && p.b_paired !== undefined).map((p) => {
      const a = rowLabel(results, p.table, p.a);
      const b = rowLabel(results, p.table, p.b);
      return `${a} ${withUnit(results, p.metric, p.a_paired!)} vs ${b} ${withUnit(results, p.metric_b, p.b_paired!)} (${results.columns[p.metric]?.label ?? p.metric}, on the same ${p.items} items)`;
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
  // each model's pair stays together: zero-velocity's value is on that model's windows
  { re: /^(.+?) (comes closer to|comes no closer to|is not shown to come closer to) the captured future than standing still: (best-of-\d+ (?:MPJPE|ADE) (?:at|over) [^ ]+ s) (.+? against .+?) for zero-velocity (on the same \d+ windows) \((.+)\)\.$/,
    lead: (m) => `${m[2] === 'comes closer to' ? 'Closer to' : m[2] === 'comes no closer to' ? 'No closer to' : 'Not shown closer to'} the captured future than standing still (${m[3]}, the model against zero-velocity on the model's windows; ${m[6]})` },
  { re: /^(.+?) (draws different futures for one history): diversity (.+?) \((.+)\)\.$/,
    lead: (m) => `Different futures for one history (diversity; ${m[4]})` },
  { re: /^(.+?) (draws a single future): diversity 0 \((.+)\)\.$/, lead: (m) => `A single future (diversity 0; ${m[3]})` },
  { re: /^(.+?)'s futures are (seldom recognised as the history's action): MOAC accuracy (.+? against .+?) for the captured future (on the same \d+ windows) \((.+)\)\.$/,
    lead: (m) => `Futures seldom recognised as the history's action (MOAC accuracy, the model against the captured future on the model's windows; ${m[5]})` },
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
      const value = i === 0 ? `${m[4]} ${m[5]}` : i === 1 ? m[3] : i === 2 ? null : `${m[3]} ${m[4]}`;
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
 * The card's summary, five lines at most: results.json's own `summary` when the evaluation writes one (the
 * same lines as docs/MODEL_CARD.md), else lines drawn from results.json as the page reads it: the data, which
 * served learned models are shown to beat each baseline, and how the paper claims fare.
 */
export function cardSummary(results: Results | null, manifest: Manifest | null, index: ClipIndex): string[] {
  if (results?.summary?.length) return results.summary.slice(0, 5);
  const facts = dataFacts(results);
  const site = dataSummary(index);
  const lines = facts ? [facts.lines[1], facts.lines[2]] : [`This site offers ${site.clips} motion clips as histories (${site.seconds.toFixed(0)} s, ${site.actions} actions).`];
  if (manifest) lines.push(`${manifest.models.length} models are served: ${manifest.models.map((m) => m.label).join('; ')}.`);
  if (!results) return [...lines, 'The measured numbers (results.json) could not be loaded.'];
  lines.push(...VERDICT_BASELINES.map((b) => beatenLine(results, b)).filter((x): x is string => x !== null));
  const count = (s: string) => results.claims.filter((c) => c.status === s).length;
  const statuses = ['holds', 'fails', 'inconclusive', 'no difference', 'insufficient data', 'unusable', 'not evaluated', 'by construction'];
  lines.push(`Paper claims: ${statuses.map((x) => `${count(x)} ${x}`).join(', ')}.`);
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

/** The held-out table with ground truth that predicts furthest ahead (heldout_5s in the full evaluation). */
export function longestTable(results: Results | null): Table | undefined {
  return [...(results?.tables ?? [])].filter((t) => t.truth && !t.in_sample && t.rows.some((r) => r.values))
    .sort((a, b) => b.horizon_frames - a.horizon_frames)[0];
}

/** The served learned models (results.json `served_learned`); older results: the served model rows but zero-velocity. */
const servedLearned = (results: Results) => results.served_learned ?? Object.keys(results.models).filter((id) => id !== 'zero-velocity');

/**
 * The failure modes seen in the measured numbers, each with them, and what the section looked for and did
 * not find (a table or column results.json lacks: `missing`, which the card test requires to be empty).
 */
export function failureChecks(results: Results | null, index: ClipIndex, manifest: Manifest | null): { texts: string[]; missing: string[] } {
  const out: string[] = [];
  const missing: string[] = [];
  const u = (metric: string, x: number) => (results ? withUnit(results, metric, x) : String(x));
  const t = longestTable(results);
  if (results && !t) missing.push('a held-out table with ground truth');
  if (results && t) {
    const where = `${t.title.charAt(0).toLowerCase()}${t.title.slice(1)}`;
    for (const r of t.rows.filter((x) => x.flag)) out.push(`${r.label} does not predict in ${where}: ${r.flag}; it counts in no tally.`);
    const speed = t.columns.filter((c) => c.startsWith('speed_ratio_s')).pop();
    if (!speed) missing.push(`the speed ratios in table ${t.id}`);
    const served = t.rows.filter((r) => servedLearned(results).includes(r.id) && r.values && !r.flag);
    if (speed) {
      const second = speed.replace('speed_ratio_s', '');
      const slow = served.filter((r) => (val(r, speed)?.mean ?? 1) < 0.5);
      const fast = served.filter((r) => (val(r, speed)?.mean ?? 1) > 2);
      if (slow.length) out.push(`Slowing down to a halt: in second ${second} of ${where} the joints of ${slow.map((r) => `${r.label} move at ${u(speed, val(r, speed)!.mean)}`).join(', ')} `
        + 'the captured speed on the same windows (a ratio of 1 moves as people do).');
      if (fast.length) out.push(`Moving too fast: in second ${second} of ${where} the joints of ${fast.map((r) => `${r.label} move at ${u(speed, val(r, speed)!.mean)}`).join(', ')} the captured speed on the same windows.`);
    }
    if (!t.columns.includes('skate')) missing.push(`foot skating in table ${t.id}`);
    const sliding = served.flatMap((r) => {
      const mine = val(r, 'skate')?.mean;
      const truth = truthOn(t, r, 'skate');
      return mine !== undefined && truth && mine > 2 * truth ? [`${r.label} ${u('skate', mine)} against ${u('skate', truth)} for the captures on its ${r.items ?? t.items} windows`] : [];
    });
    if (sliding.length) out.push(`Feet slide while planted (foot skating, the median speed of a foot in contact, ${where}): ${sliding.join('; ')}.`);
    const zero = t.rows.find((r) => r.id === 'zero-velocity' && r.values);
    const oracle = t.rows.find((r) => r.kind === 'oracle' && r.values);
    const [zPose, oPose] = [val(zero, 'acc_pose')?.mean, val(oracle, 'acc_pose')?.mean];
    if (zero && predictsAll(zero, t) && zPose !== undefined && oPose !== undefined && zPose >= oPose) {
      out.push(`Standing still scores well: a future that does not move is recognised by the pose classifier as often as the captured future `
        + `(accuracy ${u('acc_pose', zPose)} against ${u('acc_pose', oPose)} on the same ${t.items ?? t.windows} windows, ${where}). High recognition accuracy alone does not mean lifelike motion.`);
    }
  }
  const facts = results?.data;
  if (results && !facts?.per_action) missing.push('results.data.per_action');
  if (facts?.per_action) {
    const tested = Object.entries(facts.per_action).filter(([, x]) => x.test.takes > 0).map(([a]) => pretty(a));
    const all = Object.keys(facts.per_action).length;
    out.push(`Only ${tested.length} of ${all} actions have held-out people (${tested.join(', ')}): no number here says how the models do on the others, `
      + 'which are trained on only.');
  }
  if (manifest) {
    const longest = Math.max(...manifest.models.map((m) => m.params.history_frames));
    const short = index.clips.filter((c) => c.frames < longest && !c.loops).map((c) => c.name.replace(/_/g, ' '));
    if (short.length) out.push(`Clips on this site shorter than the longest history (${longest} frames) cannot give that model a history: ${short.join(', ')}.`);
  }
  if (results && !results.verdicts) missing.push('results.verdicts');
  const memo = (results?.verdicts ?? []).filter((v) => v.baseline === 'nearest-window' && v.status !== 'holds' && v.status !== 'not evaluated' && !flagOf(results!, v));
  if (memo.length) {
    out.push(`Not shown to beat the nearest training window's future on held-out people (memorisation is not ruled out): `
      + `${memo.map((v) => `${labelFor(results!, v.row)} at ${ahead(results!, v.table)} (${verdictNumbers(results!, v)})`).join('; ')}.`);
  }
  out.push('Few people per action: a model has seen a few ways to do each action, and the held-out people are few; a comparison '
    + `resting on too few people or takes${results?.min_people !== undefined ? ` (fewer than ${results.min_people} people or ${results.min_takes} takes)` : ''} is reported as insufficient data.`);
  out.push('Skeletons have 18 joints, without hands, foot orientation or face.');
  return { texts: out, missing };
}

/** The failure modes seen in the measured numbers (see failureChecks). */
export function failureModes(results: Results | null, index: ClipIndex, manifest: Manifest | null): string[] {
  return failureChecks(results, index, manifest).texts;
}

/** Sections of the card page that find no data in results.json or the manifest (empty when every one does). */
export function cardGaps(results: Results | null, index: ClipIndex, manifest: Manifest | null): string[] {
  if (!results) return ['results.json could not be read'];
  const gaps: string[] = [];
  if (!dataFacts(results)?.actions.length) gaps.push('The data: results.json has no data.per_action');
  if (!results.summary?.length) gaps.push('In short: results.json has no summary');
  if (!results.verdicts?.length) gaps.push('Against the baselines: results.json has no verdicts');
  for (const v of results.verdicts ?? []) if (!results.tables.some((t) => t.id === v.table)) gaps.push(`Against the baselines: table ${v.table} is not in results.json`);
  if (!manifest) gaps.push('The models: the manifest could not be read');
  gaps.push(...failureChecks(results, index, manifest).missing.map((m) => `Known failure modes: results.json has no ${m}`));
  return [...new Set(gaps)];
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
  note    = {WAT, LCP-VAE and Keyposes trained on CMU motion capture (DeepMimic clips as training only), run with onnxruntime-web}
}`;
}
