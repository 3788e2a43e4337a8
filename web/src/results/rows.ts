// How a row is labelled wherever a table shows it: its windows with its refusal rate, and a mark when its
// futures are not predictions (results.json `flag`). Shared by the Results page and the Model card page.
import type { Row, Table } from './data';
import { fmt } from './format';

/** How many of the table's windows a row refuses (older results carry only its items). */
export function refusedOf(r: Row, t: Table): number {
  const of = t.items ?? t.windows ?? 0;
  return r.refused?.items ?? Math.max(0, of - (r.items ?? of));
}

/** "98/148 (33.8% refused)": a row's windows, with its refusal rate when it refuses some. */
export function windowsText(r: Row, t: Table): string {
  const of = t.items ?? t.windows ?? 0;
  const out = refusedOf(r, t);
  return `${r.items ?? ''}/${of}${out && of ? ` (${fmt((100 * out) / of, '%')}% refused)` : ''}`;
}

/** A row's label, marked when its futures are not predictions (they count in no tally). */
export function rowLabel(r: Row): string {
  return r.flag ? `${r.label} — does not predict: ${r.flag}` : r.label;
}
