// What a drop holds, before anything is read as motion (issue 30): the files with the folders they
// were dropped in, which of them is the one motion to import (a BVH, or an .asf with its .amc), which
// .json is a joint map (only a JSON object with a joint map's fields; the metadata a dataset ships
// beside each take is not one), and every other file, named with why it is left out.
// Pure functions, so tests/web/import-files.test.ts checks them without a browser; import-panel.ts
// mounts them.

/** One dropped file: `path` keeps the folders it was dropped in ("walk/07_01.bvh"), else its name. */
export interface DroppedFile {
  path: string;
  size: number;
  text(): Promise<string>;
}

/** The fields a joint map has (web/src/motion/joint-map.ts checks a map against the same list). */
export const JOINT_MAP_FIELDS = ['format', 'version', 'name', 'about', 'extends', 'up', 'joints', 'orders'];
/** A map does something through at least one of these; an object with none is not a map. */
const MAP_ACTIONS = ['extends', 'up', 'joints', 'orders'];
export const JOINT_MAP_FORMAT = 'motion-futures/joint-map';

const isObject = (v: unknown): v is Record<string, unknown> => typeof v === 'object' && v !== null && !Array.isArray(v);

/**
 * Why a parsed .json is not a joint map, or null when it is one: a map is a JSON object that says it
 * is (`"format": "motion-futures/joint-map"`), or whose fields are all a map's with at least one that
 * does something (extends, up, joints, orders). Whether its values are right is the reader's check.
 */
export function notAJointMap(doc: unknown): string | null {
  if (!isObject(doc)) return `not a joint map (a joint map is a JSON object, this is ${Array.isArray(doc) ? 'a list' : doc === null ? 'null' : typeof doc})`;
  if (doc.format === JOINT_MAP_FORMAT) return null;
  const other = Object.keys(doc).filter((k) => !JOINT_MAP_FIELDS.includes(k)).sort();
  if (other.length) return `not a joint map (it has the field${other.length > 1 ? 's' : ''} ${other.slice(0, 3).map((k) => `'${k}'`).join(', ')}${other.length > 3 ? ', …' : ''})`;
  if (!MAP_ACTIONS.some((k) => k in doc)) return `not a joint map (it has none of ${MAP_ACTIONS.join(', ')})`;
  return null;
}

/** A contract clip name from a dropped path, folders kept: "Walk/01 01.bvh" -> "walk_01_01".
 *  Twin of clip_name in export/data/sources.py, so a take dropped in its folder is named as
 *  `python -m export data --data` names it from the folder above. */
export function clipName(path: string): string {
  const rel = path.replace(/\\/g, '/').replace(/^\/+/, '');
  const slash = rel.lastIndexOf('/');
  const dot = rel.lastIndexOf('.');
  const stem = dot > slash + 1 ? rel.slice(0, dot) : rel;
  return stem.toLowerCase().replace(/\//g, '_').replace(/[^a-z0-9_.-]+/g, '_').replace(/^[_.-]+/, '') || 'clip';
}

const ext = (path: string) => /\.([^./\\]+)$/.exec(path)?.[1].toLowerCase() ?? '';
const base = (path: string) => path.replace(/^.*[\\/]/, '');

export type DropMotion =
  | { kind: 'bvh'; file: DroppedFile }
  | { kind: 'asf-amc'; asf: DroppedFile; amc: DroppedFile };

export interface DropPlan {
  /** The one motion this drop imports, or null. */
  motion: DropMotion | null;
  /** Why nothing can be imported, when `motion` is null and the drop held motion files or nothing usable. */
  problem: string | null;
  /** The joint map dropped with the motion (its parsed JSON), or null. */
  map: { doc: unknown; path: string } | null;
  /** Files left out, each with why: sidecars that are not joint maps, other kinds, takes beyond the first. */
  ignored: { path: string; why: string }[];
}

const NPZ = 'the page reads BVH and ASF/AMC files; convert npz joint positions with "python -m export data --data FOLDER" (bring-your-own.html)';

/**
 * Sort a drop: .json files are read and kept as the joint map only when they are one; one motion is
 * chosen (the first BVH by path, else the first .amc with an .asf, the one whose subject it names when
 * there are several); every other file is named in `ignored`. Two joint maps in one drop are a problem
 * (which one was meant?), as is an .amc without an .asf or an .asf without an .amc.
 */
export async function planDrop(files: readonly DroppedFile[]): Promise<DropPlan> {
  const sorted = [...files].sort((a, b) => (a.path < b.path ? -1 : a.path > b.path ? 1 : 0));
  const ignored: DropPlan['ignored'] = [];
  const maps: { doc: unknown; path: string }[] = [];
  const bvh: DroppedFile[] = [];
  const asf: DroppedFile[] = [];
  const amc: DroppedFile[] = [];
  const npz: DroppedFile[] = [];
  for (const f of sorted) {
    const kind = ext(f.path);
    if (kind === 'bvh') bvh.push(f);
    else if (kind === 'asf') asf.push(f);
    else if (kind === 'amc') amc.push(f);
    else if (kind === 'npz') npz.push(f);
    else if (kind === 'json') {
      let doc: unknown;
      try {
        // a joint map is a few kB; a big .json beside a take is a dataset's metadata, not read whole
        if (f.size > 1024 * 1024) { ignored.push({ path: f.path, why: 'not a joint map (larger than 1 MB)' }); continue; }
        doc = JSON.parse(await f.text());
      } catch (err) {
        ignored.push({ path: f.path, why: `not a joint map (not readable JSON: ${(err as Error).message})` });
        continue;
      }
      const why = notAJointMap(doc);
      if (why) ignored.push({ path: f.path, why });
      else maps.push({ doc, path: f.path });
    } else ignored.push({ path: f.path, why: 'not a BVH, ASF/AMC or joint map file' });
  }
  const plan = (motion: DropMotion | null, problem: string | null): DropPlan => ({ motion, problem, map: maps[0] ?? null, ignored });
  if (maps.length > 1) {
    return { motion: null, problem: `${maps.map((m) => m.path).join(', ')}: ${maps.length} joint maps dropped together; drop the one meant for the file`, map: null, ignored };
  }
  const skip = (fs: DroppedFile[], why: string) => { for (const f of fs) ignored.push({ path: f.path, why }); };
  const ONE = 'not imported: the page imports one take per drop';
  if (bvh.length) {
    skip(bvh.slice(1), ONE);
    skip([...asf, ...amc, ...npz], ONE);
    return plan({ kind: 'bvh', file: bvh[0] }, null);
  }
  if (amc.length && asf.length) {
    // CMU names a take <subject>_<take>.amc and its skeleton <subject>.asf: pair them by that when it can
    const subject = (f: DroppedFile) => base(f.path).replace(/\.[^.]*$/, '').toLowerCase();
    const first = amc[0];
    const own = asf.find((a) => subject(first).startsWith(`${subject(a)}_`)) ?? asf[0];
    skip(asf.filter((a) => a !== own), 'not imported: an .amc is read with one .asf');
    skip(amc.slice(1), ONE);
    skip(npz, ONE);
    return plan({ kind: 'asf-amc', asf: own, amc: first }, null);
  }
  if (amc.length) {
    const names = amc.map((f) => f.path).join(', ');
    return plan(null, `${names}: an AMC motion needs its ASF skeleton: drop the .asf (e.g. ${base(amc[0].path).replace(/_.*$/, '').replace(/\.[^.]*$/, '')}.asf) together with ${amc.length > 1 ? 'one .amc' : 'it'}`);
  }
  if (asf.length) return plan(null, `${asf.map((f) => f.path).join(', ')}: an ASF skeleton and its AMC motion go together: drop both files at once`);
  if (npz.length) return plan(null, `${npz[0].path}: ${NPZ}`);
  if (maps.length) return plan(null, null); // a map on its own: kept for the next drop
  const names = ignored.map((i) => i.path).join(', ');
  return plan(null, names ? `${names}: nothing to import (the page reads .bvh files, an .asf with its .amc, and joint map .json files)` : 'nothing was dropped');
}

/** One line naming the files a drop left out, grouped by why (a few names each):
 *  "Ignored meta.json: not a joint map (it has the field 'content'); b.bvh, c.bvh and 3 more: not imported: …". */
export function ignoredText(ignored: DropPlan['ignored'], shown = 3): string {
  if (!ignored.length) return '';
  const byWhy = new Map<string, string[]>();
  for (const i of ignored) byWhy.set(i.why, [...(byWhy.get(i.why) ?? []), i.path]);
  const parts = [...byWhy].map(([why, paths]) => {
    const names = paths.length > shown + 1 ? `${paths.slice(0, shown).join(', ')} and ${paths.length - shown} more` : paths.join(', ');
    return `${names}: ${why}`;
  });
  return `Ignored ${parts.join('; ')}.`;
}

// ---- folders: what a drop event carries ----

/** The parts of the File and Directory Entries API a drop's items offer (webkitGetAsEntry). */
export interface EntryLike {
  isFile: boolean;
  isDirectory: boolean;
  name: string;
  fullPath: string;
  file?(ok: (f: File) => void, fail?: (e: unknown) => void): void;
  createReader?(): { readEntries(ok: (entries: EntryLike[]) => void, fail?: (e: unknown) => void): void };
}

/** The most files a dropped folder is walked for: a whole dataset is not imported take by take. */
export const MAX_DROPPED_FILES = 2000;
const MAX_FOLDER_DEPTH = 32;

const asDropped = (file: File, path: string): DroppedFile => ({ path, size: file.size, text: () => file.text() });

/** A picked or dropped File with the folder it came in when the browser says (webkitRelativePath). */
export function droppedFile(file: File): DroppedFile {
  return asDropped(file, file.webkitRelativePath || file.name);
}

/**
 * The files of a drop with their folders: a dropped folder is walked (its files keep the path from the
 * folder dropped, "walk/07_01.bvh"); a dropped file keeps its name. Entries the browser does not give
 * fall back to the plain file list. `truncated`: the folders held more than MAX_DROPPED_FILES files.
 */
export async function filesOfEntries(
  entries: readonly (EntryLike | null)[], plain: readonly File[],
): Promise<{ files: DroppedFile[]; truncated: boolean }> {
  if (!entries.length || entries.some((e) => e === null)) return { files: plain.map(droppedFile), truncated: false };
  const out: DroppedFile[] = [];
  let truncated = false;
  const fileOf = (e: EntryLike) => new Promise<File>((ok, fail) => e.file!(ok, fail));
  const children = async (e: EntryLike): Promise<EntryLike[]> => {
    const reader = e.createReader!();
    const all: EntryLike[] = [];
    // readEntries returns a batch at a time (100 in Chromium) until an empty one
    for (;;) {
      const batch = await new Promise<EntryLike[]>((ok, fail) => reader.readEntries(ok, fail));
      if (!batch.length || all.length + batch.length > MAX_DROPPED_FILES) { all.push(...batch); break; }
      all.push(...batch);
    }
    return all;
  };
  const walk = async (e: EntryLike, depth: number): Promise<void> => {
    if (out.length >= MAX_DROPPED_FILES) { truncated = true; return; }
    if (e.isFile && e.file) out.push(asDropped(await fileOf(e), e.fullPath.replace(/^\/+/, '') || e.name));
    else if (e.isDirectory && e.createReader && depth < MAX_FOLDER_DEPTH) for (const c of await children(e)) await walk(c, depth + 1);
  };
  for (const e of entries) await walk(e as EntryLike, 0);
  return { files: out, truncated };
}
