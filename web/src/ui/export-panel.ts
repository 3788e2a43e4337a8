// "Export": download what is on stage (the history with all K futures, or with the selected one, and
// the ground truth that follows the history as its own figure "ground_truth") as GLB (opens in
// Blender), as clip JSON (the contract's clip format) or as CSV.
//
// Mount API (the lead wires it into app.ts):
//   const exporter = mountExportPanel(addSection(panel, 'export', 'Export').body, {
//     shown: () => predictor.last ? shownFromPrediction(clips.current!, predictor.last.start,
//        historyFrames, predictor.last.prediction, { selected, model: predictor.last.model }) : null,
//     banner, status: o.status,
//   });
//   exporter.refresh();   // after each prediction or selection change (enables the buttons)
import { clipJson } from '../export/clip-json';
import { csvText } from '../export/csv';
import { glbBytes } from '../export/glb';
import type { Shown } from '../export/shown';
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
  { id: 'json', label: 'JSON', title: 'Clip files of the contract (history + one future each; the ground truth as "<clip>.ground_truth")', type: 'application/json' },
  { id: 'csv', label: 'CSV', title: 'figure, frame, time, joint, x, y, z (metres, y up); the ground truth\'s rows have figure "ground_truth"', type: 'text/csv' },
];

function download(fileName: string, data: Blob): void {
  const url = URL.createObjectURL(data);
  const a = el('a', { href: url, download: fileName, hidden: true });
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 10_000);
}

/** "walk.regression-gru.3-futures" or "walk.regression-gru.sample_2". */
export function exportBaseName(s: Shown): string {
  const what = s.futures.length === 1 ? `sample_${s.futures[0].sample + 1}` : `${s.futures.length}-futures`;
  return [s.name, s.model, what].filter(Boolean).join('.');
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
    const truth = s?.truth ? ' and the ground truth' : '';
    what.textContent = !s ? 'Predict first: the history and its futures can then be saved.'
      : s.futures.length === 1 ? `The history of ${s.name} with future #${s.futures[0].sample + 1}${truth}.`
        : `The history of ${s.name} with all ${s.futures.length} futures${truth} (select one to save only it).`;
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
