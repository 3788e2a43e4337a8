// "Export": download what is on stage (the history with all K futures of every model on stage, or
// with the selected one, and the ground truth that follows the history as its own figure
// "ground_truth") as GLB (opens in Blender), as clip JSON (the contract's clip format) or as CSV.
// In compare mode each compared model's futures are in the file, named after their model.
//
// Mount API (app.ts wires it):
//   const exporter = mountExportPanel(addSection(panel, 'export', 'Export').body, {
//     shown: () => predictor.last ? shownFromRuns(motion, exportRuns(rows, ...), { selected }) : null,
//     banner, status: o.status,
//   });
//   exporter.refresh();   // after each prediction or selection change (enables the buttons)
import { clipJson } from '../export/clip-json';
import { csvText } from '../export/csv';
import { glbBytes } from '../export/glb';
import { modelsText, type Shown } from '../export/shown';
import { el, type StatusSink } from './dom';
import type { MessageBanner } from './messages';

export type ExportFormat = 'glb' | 'json' | 'csv';

export interface ExportPanelOptions {
  /** What is on stage now, or null when there is no prediction to export. */
  shown(): Shown | null;
  banner?: MessageBanner;
  /** Deliver a file; default: a download through a temporary <a download> link. */
  save?(fileName: string, data: Blob): void;
  /** Reports exportStatus (busy, done, error) and exportFile for tests and styles. */
  status?: StatusSink;
}

export interface ExportPanel {
  root: HTMLElement;
  /** Re-read shown() and update the buttons and the description. */
  refresh(): void;
  /** Export in one format (what the buttons do); resolves to the file name, or null on failure. */
  exportAs(format: ExportFormat): Promise<string | null>;
  /** Forget the last "Saved …": it belonged to what was on stage then. */
  clearStatus(): void;
}

const FORMATS: { id: ExportFormat; label: string; title: string; type: string }[] = [
  { id: 'glb', label: 'GLB', title: 'Animated joints for Blender or any glTF viewer; the ground truth is the node "ground_truth"', type: 'model/gltf-binary' },
  { id: 'json', label: 'JSON', title: 'Clip files of the contract (history + one future each, its source recording the model, seed, controls and foot planting; the ground truth as "<clip>.ground_truth")', type: 'application/json' },
  { id: 'csv', label: 'CSV', title: 'figure, frame, time, joint, x, y, z (metres, y up); compared, a future\'s figure starts with its model; the ground truth\'s rows have figure "ground_truth"', type: 'text/csv' },
];

function download(fileName: string, data: Blob): void {
  const url = URL.createObjectURL(data);
  const a = el('a', { href: url, download: fileName, hidden: true });
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 10_000);
}

/** "walk.regression-gru.3-futures", "walk.regression-gru.sample_2" or, compared, "walk.wat-rnn+lcp-vae.6-futures". */
export function exportBaseName(s: Shown): string {
  const what = s.futures.length === 1 ? `sample_${s.futures[0].sample + 1}` : `${s.futures.length}-futures`;
  return [s.name, modelsText(s), what].filter(Boolean).join('.');
}

/** What the export holds, in words: one model's futures, or each compared model's. */
export function exportDescription(s: Shown): string {
  const truth = s.truth ? ' and the ground truth' : '';
  const runs = s.runs.map((r, i) => ({ name: r.label ?? r.model ?? 'a model', n: s.futures.filter((f) => f.run === i).length })).filter((r) => r.n > 0);
  const of = s.runs.length > 1 ? ` of ${runs.map((r) => r.name).join(' and ')}` : '';
  const one = (s.selected ?? null) !== null ? s.selected! : s.futures.length === 1 ? s.futures[0].sample : null;
  if (one !== null) return `The history of ${s.name} with future #${one + 1}${of}${truth}.`;
  if (s.runs.length > 1) {
    return `The history of ${s.name} with the futures of ${runs.map((r) => `${r.name} (${r.n})`).join(' and ')}${truth}, `
      + 'each named after its model (select one to save only it).';
  }
  return `The history of ${s.name} with all ${s.futures.length} futures${truth} (select one to save only it).`;
}

export function mountExportPanel(container: HTMLElement, options: ExportPanelOptions): ExportPanel {
  const save = options.save ?? download;
  const what = el('p', { class: 'muted export-what' });
  const status = el('p', { class: 'muted export-status', role: 'status', 'aria-live': 'polite' });
  const buttons = FORMATS.map((f) => el('button', { type: 'button', class: 'text-button', id: `export-${f.id}`, title: f.title, disabled: true }, f.label));
  container.replaceChildren(what, el('div', { class: 'export-buttons' }, ...buttons), status);

  const refresh = () => {
    let s: Shown | null = null;
    try { s = options.shown(); } catch { s = null; }
    buttons.forEach((b) => { b.disabled = !s; });
    what.textContent = !s ? 'Predict first: the history and its futures can then be saved.' : exportDescription(s);
  };

  const exportAs = async (format: ExportFormat): Promise<string | null> => {
    const spec = FORMATS.find((f) => f.id === format)!;
    const s = options.shown();
    if (!s) { status.textContent = 'Nothing to export yet: predict first.'; return null; }
    const fileName = `${exportBaseName(s)}.${format}`;
    status.textContent = `Writing ${fileName}…`;
    options.status?.('exportStatus', 'busy');
    try {
      const data = format === 'glb' ? await glbBytes(s) : format === 'json' ? clipJson(s) : csvText(s);
      const blob = new Blob([data], { type: spec.type });
      save(fileName, blob);
      status.textContent = `Saved ${fileName} (${(blob.size / 1024).toFixed(0)} KiB).`;
      options.status?.('exportStatus', 'done');
      options.status?.('exportFile', fileName);
      options.banner?.clear('export');
      return fileName;
    } catch (err) {
      const text = `Export failed: ${(err as Error).message ?? err}`;
      status.textContent = text;
      options.status?.('exportStatus', 'error');
      options.banner?.show(text, 'error', 'export');
      return null;
    }
  };

  buttons.forEach((b, i) => b.addEventListener('click', () => { void exportAs(FORMATS[i].id); }));
  refresh();
  const clearStatus = () => {
    status.textContent = '';
    options.status?.('exportStatus', undefined);
    options.status?.('exportFile', undefined);
  };

  return { root: container, refresh, exportAs, clearStatus };
}
