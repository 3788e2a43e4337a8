// "Your motion": drop or choose a BVH file, or an .asf + .amc pair (and optionally a joint map JSON);
// a good file becomes a Motion for the page, a bad one a message naming the problem, and the page keeps
// what it had.
//
// Mount API (the lead wires it into app.ts):
//   const imports = mountImportPanel(addSection(panel, 'import', 'Your motion').body, {
//     skeleton: () => clips.index?.skeleton ?? null,   // the project skeleton with offsets
//     onMotion: (m) => { ...show m like a clip; any window of it can be the history... },
//     banner,                                          // errors go here (key 'import') and in the panel
//     dropTarget: parts.host,                          // optional: more places files may be dropped
//     minFrames: () => 10,                             // optional: shortest usable take at 30 Hz
//     status: o.status,                                // optional: importStatus busy|done|error
//   });
// and in onMotion the app's own hook: showMotion(m, { kind: 'dropped', name: m.origin.file }).
//   imports.importText(text, 'take.bvh')  // the same path without a file picker (tests, URLs)
import type { Skeleton } from '../contract/types';
import { importAsfAmc } from '../motion/asf-amc';
import { importBvh, MAX_BYTES, MotionImportError, type ImportedMotion } from '../motion/bvh';
import { parseJointMap } from '../motion/joint-map';
import { MIN_FRAMES } from '../motion/retarget';
import { el, type StatusSink } from './dom';
import type { MessageBanner } from './messages';

export interface ImportPanelOptions {
  /** The project skeleton with offsets; null while the clip index is still loading. */
  skeleton(): Skeleton | null;
  /** A dropped file became a Motion (30 Hz, project skeleton, role "test", origin "dropped-file"). */
  onMotion(m: ImportedMotion): void;
  banner: MessageBanner;
  /** Element that accepts dropped files besides the panel's own drop zone (e.g. the widget host). */
  dropTarget?: HTMLElement;
  /** Shortest take, in frames at 30 Hz (e.g. the longest history_frames of the served models). */
  minFrames?: () => number;
  /** Reports importStatus (busy, done, error) for tests and styles. */
  status?: StatusSink;
}

export interface ImportPanel {
  root: HTMLElement;
  /** Import BVH text as if a file of that name had been dropped; null (and a message) when it fails. */
  importText(text: string, file: string): ImportedMotion | null;
  importFile(file: File): Promise<ImportedMotion | null>;
  /** The last motion imported successfully. */
  current(): ImportedMotion | null;
}

const BANNER_KEY = 'import';

export function mountImportPanel(container: HTMLElement, options: ImportPanelOptions): ImportPanel {
  const fileInput = el('input', { type: 'file', id: 'import-file', accept: '.bvh,.asf,.amc,.json', multiple: true });
  const choose = el('button', { type: 'button', class: 'text-button', id: 'import-choose' }, 'Choose a BVH or ASF + AMC…');
  const zone = el('div', {
    class: 'import-drop', id: 'import-drop', 'aria-describedby': 'import-help',
    style: 'border: 1px dashed var(--border); border-radius: 6px; padding: 0.6rem; text-align: center;',
  }, 'Drop a BVH file (or an .asf and its .amc together) here', el('br'), choose);
  const help = el('p', { class: 'muted', id: 'import-help' },
    'CMU-style and Daz-style skeletons are recognised (CMU ASF/AMC pairs at 120 Hz); drop a joint map .json with it for other names or a z-up file. ',
    'It is retargeted to this skeleton at 30 Hz; any window can then be the history.');
  const mapNote = el('p', { class: 'muted import-map' });
  const status = el('p', { class: 'muted import-status', role: 'status', 'aria-live': 'polite' });
  fileInput.hidden = true;
  container.replaceChildren(zone, fileInput, help, mapNote, status);

  let jointMap: { doc: unknown; name: string } | null = null;
  let last: ImportedMotion | null = null;
  const setStatus = (text: string, state: 'busy' | 'done' | 'error') => {
    status.textContent = text;
    options.status?.('importStatus', state);
  };
  const fail = (message: string) => {
    setStatus(message, 'error');
    options.banner.show(`Could not import: ${message}`, 'error', BANNER_KEY);
  };

  // One reader per format (BVH, or an ASF skeleton with its AMC motion), the same handling after it.
  const importWith = (file: string, read: (o: Parameters<typeof importBvh>[2]) => ImportedMotion): ImportedMotion | null => {
    const skeleton = options.skeleton();
    if (!skeleton?.offsets) { fail(`${file}: the page is still loading its skeleton; try again in a moment`); return null; }
    let m: ImportedMotion;
    try {
      m = read({ skeleton, jointMap: jointMap?.doc, jointMapName: jointMap?.name, minFrames: options.minFrames?.() ?? MIN_FRAMES });
    } catch (err) {
      fail(err instanceof MotionImportError ? err.message : `${file}: could not be read (${(err as Error).message ?? err})`);
      return null;
    }
    try {
      options.onMotion(m);
    } catch (err) {
      fail(`${file}: could not be shown (${(err as Error).message ?? err})`);
      return null;
    }
    last = m;
    options.banner.clear(BANNER_KEY);
    setStatus(`${m.name}: ${m.frames} frames at 30 Hz (${(m.frames / 30).toFixed(1)} s) from ${m.origin.sourceFrames} at `
      + `${Number(m.origin.sourceFps.toPrecision(4))} Hz, joint map ${m.origin.jointMap}.`, 'done');
    return m;
  };
  const importText = (text: string, file: string) => importWith(file, (o) => importBvh(text, file, o));

  const readJointMap = async (file: File): Promise<boolean> => {
    try {
      const doc = parseJointMap(await file.text(), file.name);
      jointMap = { doc, name: file.name };
      mapNote.textContent = `Joint map: ${file.name} (on top of the built-in map the file's joints match).`;
      return true;
    } catch (err) {
      fail((err as Error).message);
      return false;
    }
  };

  const readText = async (file: File): Promise<string | null> => {
    if (file.size > MAX_BYTES) {
      fail(`${file.name}: ${(file.size / 2 ** 20).toFixed(0)} MB is larger than this page reads (${MAX_BYTES / 2 ** 20} MB); cut the take shorter`);
      return null;
    }
    try {
      return await file.text();
    } catch (err) {
      fail(`${file.name}: could not be read (${(err as Error).message})`);
      return null;
    }
  };

  const importFile = async (file: File): Promise<ImportedMotion | null> => {
    const lower = file.name.toLowerCase();
    if (lower.endsWith('.npz')) {
      fail(`${file.name}: the page reads BVH and ASF/AMC files; convert npz joint positions with "python -m export data --data FOLDER" (docs/BRING_YOUR_OWN.md)`);
      return null;
    }
    if (lower.endsWith('.asf') || lower.endsWith('.amc')) {
      fail(`${file.name}: an ASF skeleton and its AMC motion go together: drop both files at once`);
      return null;
    }
    setStatus(`Reading ${file.name}…`, 'busy');
    await new Promise((r) => setTimeout(r, 0)); // let the status paint before a long parse
    const text = await readText(file);
    return text === null ? null : importText(text, file.name);
  };

  const importPair = async (asf: File, amc: File): Promise<ImportedMotion | null> => {
    setStatus(`Reading ${asf.name} and ${amc.name}…`, 'busy');
    await new Promise((r) => setTimeout(r, 0));
    const [a, b] = [await readText(asf), await readText(amc)];
    if (a === null || b === null) return null;
    return importWith(amc.name, (o) => importAsfAmc(a, b, asf.name, amc.name, o));
  };

  // A joint map among the files applies to the BVH files dropped with it (and later ones).
  const importFiles = async (files: File[]) => {
    const maps = files.filter((f) => f.name.toLowerCase().endsWith('.json'));
    for (const f of maps) if (!(await readJointMap(f))) return;
    const takes = files.filter((f) => !maps.includes(f));
    if (!takes.length && maps.length) { setStatus(`Joint map ${maps[maps.length - 1].name} will be used for the next BVH file.`, 'done'); return; }
    const asf = takes.find((f) => f.name.toLowerCase().endsWith('.asf'));
    const amc = takes.find((f) => f.name.toLowerCase().endsWith('.amc'));
    if (asf && amc) { await importPair(asf, amc); return; }
    for (const f of takes.slice(0, 1)) await importFile(f);
    if (takes.length > 1) options.banner.show(`Imported ${takes[0].name}; drop one BVH file at a time.`, 'warning', BANNER_KEY);
  };

  const onDrop = (e: DragEvent) => {
    e.preventDefault();
    zone.classList.remove('drag-over');
    const files = Array.from(e.dataTransfer?.files ?? []);
    if (files.length) void importFiles(files);
  };
  const onDragOver = (e: DragEvent) => { e.preventDefault(); zone.classList.add('drag-over'); };
  for (const target of new Set([zone, options.dropTarget ?? zone])) {
    target.addEventListener('dragover', onDragOver);
    target.addEventListener('dragleave', () => zone.classList.remove('drag-over'));
    target.addEventListener('drop', onDrop);
  }
  choose.addEventListener('click', () => fileInput.click());
  fileInput.addEventListener('change', () => {
    const files = Array.from(fileInput.files ?? []);
    fileInput.value = '';
    if (files.length) void importFiles(files);
  });
  status.textContent = 'No file yet.';
  return { root: zone, importText, importFile, current: () => last };
}
