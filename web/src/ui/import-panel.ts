// "Your motion": drop or choose a BVH file, or an .asf + .amc pair (and optionally a joint map JSON),
// or a folder holding them; a good file becomes a Motion for the page, a bad one a message naming the
// problem (linked to the served guide, bring-your-own.html), and the page keeps what it had.
// What a drop holds is sorted by dropped-files.ts: a .json is a joint map only when it is one (a
// dataset's metadata beside a take is ignored and named), and a map applies to the files dropped with
// it; a map dropped on its own waits for the next drop only, and one click clears it. A take keeps its
// folder in its name ("walk/07_01.bvh" is walk_07_01). A body that is the mirror image of a person
// (left and right labels on the wrong sides) is offered the swap (motion/handedness.ts), and the readers'
// warnings on a take that did import (origin.warnings: a wrong up axis, another subject's ASF) are shown.
//
// Mount API (the lead wires it into app.ts):
//   const imports = mountImportPanel(addSection(panel, 'import', 'Your motion').body, {
//     skeleton: () => clips.index?.skeleton ?? null,   // the project skeleton with offsets
//     onMotion: (m) => { ...show m like a clip; any window of it can be the history... },
//     banner,                                          // errors go here (key 'import') and in the panel
//     dropTarget: parts.host,                          // optional: more places files may be dropped
//     minFrames: () => 10,                             // optional: shortest usable take at 30 Hz
//     status: o.status,                                // optional: importStatus busy|done|error, importMap, importHandedness, importWarnings
//   });
// and in onMotion the app's own hook: showMotion(m, { kind: 'dropped', name: m.origin.file }).
//   imports.importText(text, 'take.bvh')  // the same path without a file picker (tests, URLs)
import type { Skeleton } from '../contract/types';
import { importAsfAmc } from '../motion/asf-amc';
import { importBvh, MAX_BYTES, MotionImportError, type ImportedMotion } from '../motion/bvh';
import { handedness, HANDEDNESS_MESSAGE, swapLeftRight } from '../motion/handedness';
import { loadJointMap } from '../motion/joint-map';
import { MIN_FRAMES } from '../motion/retarget';
import { el, type StatusSink } from './dom';
import {
  clipName, droppedFile, filesOfEntries, ignoredText, MAX_DROPPED_FILES, planDrop, type DroppedFile, type DropPlan, type EntryLike,
} from './dropped-files';
import { linkified } from './guide-link';
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
  /** Reports importStatus (busy, done, error), importMap (the waiting map's file), importHandedness
   *  (ok, reflected, swapped) and importWarnings (how many the readers gave) for tests and styles. */
  status?: StatusSink;
}

export interface ImportPanel {
  root: HTMLElement;
  /** Import BVH text as if a file of that name had been dropped; null (and a message) when it fails. */
  importText(text: string, file: string): ImportedMotion | null;
  importFile(file: File): Promise<ImportedMotion | null>;
  /** Import what a drop holds (files with their folders), as a drop does. */
  importFiles(files: readonly DroppedFile[]): Promise<ImportedMotion | null>;
  /** The last motion imported successfully (after the swap, when it was taken). */
  current(): ImportedMotion | null;
}

const BANNER_KEY = 'import';
type HeldMap = { doc: unknown; path: string };
type Reader = (o: Parameters<typeof importBvh>[2]) => ImportedMotion;

/** The readers' warnings on an imported take (none when the reader gives none). */
export function warningsOf(m: ImportedMotion): readonly string[] {
  return (m.origin as { warnings?: readonly string[] }).warnings ?? [];
}

/** The imported motion with its left and right joints' tracks swapped, named as such in its origin. */
export function swappedMotion(m: ImportedMotion): ImportedMotion {
  return {
    ...m, positions: swapLeftRight(m.positions, m.frames, m.skeleton),
    origin: { ...m.origin, jointMap: `${m.origin.jointMap}, left and right swapped` },
  };
}

export function mountImportPanel(container: HTMLElement, options: ImportPanelOptions): ImportPanel {
  const fileInput = el('input', { type: 'file', id: 'import-file', accept: '.bvh,.asf,.amc,.json', multiple: true });
  const choose = el('button', { type: 'button', class: 'text-button', id: 'import-choose' }, 'Choose a BVH or ASF + AMC…');
  const zone = el('div', {
    class: 'import-drop', id: 'import-drop', 'aria-describedby': 'import-help',
    style: 'border: 1px dashed var(--border); border-radius: 6px; padding: 0.6rem; text-align: center;',
  }, 'Drop a BVH file (or an .asf and its .amc together, or their folder) here', el('br'), choose);
  const help = el('p', { class: 'muted', id: 'import-help' },
    'CMU-style and Daz-style skeletons are recognised (CMU ASF/AMC pairs at 120 Hz); for other joint names or a z-up file, '
    + 'drop a joint map .json together with it. ',
    'It is retargeted to this skeleton at 30 Hz; any window can then be the history. ',
    ...linkified('How, with an example map: bring-your-own.html.'));
  const clearMap = el('button', { type: 'button', class: 'text-button', id: 'import-map-clear' }, 'Clear joint map');
  const mapText = el('span', {});
  const mapNote = el('p', { class: 'muted import-map' }, mapText, ' ', clearMap);
  const status = el('p', { class: 'muted import-status', role: 'status', 'aria-live': 'polite' });
  const ignoredNote = el('p', { class: 'muted import-ignored' });
  const warningNote = el('ul', { class: 'import-warnings', role: 'alert' });
  const swapButton = el('button', { type: 'button', class: 'text-button', id: 'import-swap' }, 'Swap left and right');
  const swapText = el('span', {});
  const swapNote = el('p', { class: 'import-swap', role: 'alert' }, swapText, ' ', swapButton);
  fileInput.hidden = true;
  mapNote.hidden = true;
  ignoredNote.hidden = true;
  warningNote.hidden = true;
  swapNote.hidden = true;
  container.replaceChildren(zone, fileInput, help, mapNote, status, warningNote, swapNote, ignoredNote);

  // A joint map dropped on its own, for the next drop only.
  let waiting: HeldMap | null = null;
  let last: ImportedMotion | null = null;
  let reflected: ImportedMotion | null = null;
  const setStatus = (text: string, state: 'busy' | 'done' | 'error') => {
    status.replaceChildren(...linkified(text));
    options.status?.('importStatus', state);
  };
  const fail = (message: string) => {
    setStatus(message, 'error');
    options.banner.show(`Could not import: ${message}`, 'error', BANNER_KEY);
  };
  const setWaiting = (map: HeldMap | null) => {
    waiting = map;
    mapNote.hidden = !map;
    mapText.textContent = map ? `Joint map ${map.path} waits for the next file dropped (it applies to that drop only).` : '';
    options.status?.('importMap', map?.path);
  };
  const setIgnored = (plan: DropPlan | null, truncated = false) => {
    const text = [truncated ? `Only the first ${MAX_DROPPED_FILES} files of the folder were looked at.` : '', plan ? ignoredText(plan.ignored) : '']
      .filter(Boolean).join(' ');
    ignoredNote.textContent = text;
    ignoredNote.hidden = !text;
  };
  /** The readers' warnings on a take that imported (a wrong up axis, another subject's ASF: motion/retarget.ts). */
  const setWarnings = (warnings: readonly string[]) => {
    warningNote.replaceChildren(...warnings.map((w) => el('li', {}, ...linkified(w))));
    warningNote.hidden = !warnings.length;
    options.status?.('importWarnings', String(warnings.length));
  };
  /** After a take imported: its warnings, then what the drop left out, in the banner (never "Imported" when nothing was). */
  const announce = (m: ImportedMotion, plan: DropPlan | null) => {
    const warnings = warningsOf(m);
    setWarnings(warnings);
    const left = plan?.ignored ?? [];
    const skipped = left.some((i) => i.why.startsWith('not imported'));
    const text = [...warnings, left.length ? `Imported ${m.origin.file}. ${ignoredText(left)}` : ''].filter(Boolean).join(' ');
    if (text) options.banner.show(text, warnings.length || skipped ? 'warning' : 'info', BANNER_KEY);
  };
  const offerSwap = (m: ImportedMotion | null) => {
    reflected = null;
    let state = 'ok';
    try {
      if (m && handedness(m.positions, m.frames, m.skeleton).reflected) { reflected = m; state = 'reflected'; }
    } catch {
      state = 'unknown'; // a skeleton without hips or feet: no offer
    }
    swapText.textContent = reflected ? `${m!.name}: ${HANDEDNESS_MESSAGE}` : '';
    swapNote.hidden = !reflected;
    options.status?.('importHandedness', m ? state : undefined);
  };

  /** Hand a motion to the page; false (and a message) when the page could not show it. */
  const show = (m: ImportedMotion, file: string): boolean => {
    try {
      options.onMotion(m);
    } catch (err) {
      fail(`${file}: could not be shown (${(err as Error).message ?? err})`);
      return false;
    }
    last = m;
    return true;
  };
  const describe = (m: ImportedMotion) => `${m.name}: ${m.frames} frames at 30 Hz (${(m.frames / 30).toFixed(1)} s) from ${m.origin.sourceFrames} at `
    + `${Number(m.origin.sourceFps.toPrecision(4))} Hz, joint map ${m.origin.jointMap}.`;

  // One reader per format (BVH, or an ASF skeleton with its AMC motion), the same handling after it.
  const importWith = (file: string, map: HeldMap | null, read: Reader): ImportedMotion | null => {
    const skeleton = options.skeleton();
    if (!skeleton?.offsets) { fail(`${file}: the page is still loading its skeleton; try again in a moment`); return null; }
    let m: ImportedMotion;
    try {
      m = read({ skeleton, jointMap: map?.doc, jointMapName: map?.path, minFrames: options.minFrames?.() ?? MIN_FRAMES });
    } catch (err) {
      fail(err instanceof MotionImportError ? err.message : `${file}: could not be read (${(err as Error).message ?? err})`);
      return null;
    }
    m = { ...m, name: clipName(m.origin.file) }; // the folder it was dropped in stays in its name
    if (!show(m, file)) return null;
    options.banner.clear(BANNER_KEY);
    setStatus(describe(m), 'done');
    offerSwap(m);
    return m;
  };
  /** The map for a drop: the one dropped with it, else the one waiting; either way none is kept after. */
  const takeMap = (dropped: HeldMap | null): HeldMap | null => {
    const map = dropped ?? waiting;
    setWaiting(null);
    return map;
  };
  const importText = (text: string, file: string) => {
    setIgnored(null);
    setWarnings([]);
    const m = importWith(file, takeMap(null), (o) => importBvh(text, file, o));
    if (m) announce(m, null);
    return m;
  };

  const readText = async (file: DroppedFile): Promise<string | null> => {
    if (file.size > MAX_BYTES) {
      fail(`${file.path}: ${(file.size / 2 ** 20).toFixed(0)} MB is larger than this page reads (${MAX_BYTES / 2 ** 20} MB); cut the take shorter`);
      return null;
    }
    try {
      return await file.text();
    } catch (err) {
      fail(`${file.path}: could not be read (${(err as Error).message})`);
      return null;
    }
  };

  /** A joint map dropped without a take: checked now (against the built-in BVH map), kept for the next drop. */
  const keepMap = (map: HeldMap) => {
    const skeleton = options.skeleton();
    try {
      if (skeleton) loadJointMap('cmu-bvh', skeleton.joints, map.doc, map.path);
    } catch (err) {
      setWaiting(null);
      fail((err as Error).message);
      return;
    }
    setWaiting(map);
    options.banner.clear(BANNER_KEY);
    setStatus(`Joint map ${map.path} will be used for the next file dropped.`, 'done');
  };

  const importFiles = async (files: readonly DroppedFile[], truncated = false): Promise<ImportedMotion | null> => {
    setStatus(files.length === 1 ? `Reading ${files[0].path}…` : `Reading ${files.length} files…`, 'busy');
    await new Promise((r) => setTimeout(r, 0)); // let the status paint before a long parse
    const plan = await planDrop(files);
    setIgnored(plan, truncated);
    setWarnings([]);
    if (plan.problem) { fail(plan.problem); return null; }
    if (!plan.motion) { if (plan.map) keepMap(plan.map); return null; }
    offerSwap(null);
    const map = takeMap(plan.map);
    let m: ImportedMotion | null;
    if (plan.motion.kind === 'bvh') {
      const { path } = plan.motion.file;
      const text = await readText(plan.motion.file);
      m = text === null ? null : importWith(path, map, (o) => importBvh(text, path, o));
    } else {
      const { asf, amc } = plan.motion;
      setStatus(`Reading ${asf.path} and ${amc.path}…`, 'busy');
      const [a, b] = [await readText(asf), await readText(amc)];
      m = a === null || b === null ? null : importWith(amc.path, map, (o) => importAsfAmc(a, b, asf.path, amc.path, o));
    }
    if (m) announce(m, plan);
    return m;
  };
  const importFile = (file: File) => importFiles([droppedFile(file)]);

  const onDrop = (e: DragEvent) => {
    e.preventDefault();
    zone.classList.remove('drag-over');
    const dt = e.dataTransfer;
    if (!dt) return;
    // entries must be taken while the event runs: the list is emptied after it
    const items = Array.from(dt.items ?? []).filter((i) => i.kind === 'file');
    const entries = items.map((i) => (typeof i.webkitGetAsEntry === 'function' ? i.webkitGetAsEntry() as EntryLike | null : null));
    const plain = Array.from(dt.files ?? []);
    if (!plain.length && !entries.length) return;
    void filesOfEntries(entries, plain).then(({ files, truncated }) => importFiles(files, truncated))
      .catch((err) => fail(`the dropped files could not be read (${(err as Error).message ?? err})`));
  };
  const onDragOver = (e: DragEvent) => { e.preventDefault(); zone.classList.add('drag-over'); };
  for (const target of new Set([zone, options.dropTarget ?? zone])) {
    target.addEventListener('dragover', onDragOver);
    target.addEventListener('dragleave', () => zone.classList.remove('drag-over'));
    target.addEventListener('drop', onDrop);
  }
  choose.addEventListener('click', () => fileInput.click());
  fileInput.addEventListener('change', () => {
    const files = Array.from(fileInput.files ?? []).map(droppedFile);
    fileInput.value = '';
    if (files.length) void importFiles(files);
  });
  clearMap.addEventListener('click', () => {
    const map = waiting;
    setWaiting(null);
    if (map) setStatus(`Joint map ${map.path} cleared: the next file is read with the built-in maps.`, 'done');
  });
  swapButton.addEventListener('click', () => {
    const m = reflected;
    if (!m) return;
    const fixed = swappedMotion(m);
    if (!show(fixed, m.origin.file)) return;
    setStatus(describe(fixed), 'done');
    reflected = null;
    swapNote.hidden = true;
    options.status?.('importHandedness', 'swapped');
  });
  status.textContent = 'No file yet.';
  return { root: zone, importText, importFile, importFiles, current: () => last };
}
