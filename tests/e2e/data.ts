// What the browser tests know of the served data, read from the files rather than typed in, so the
// tests keep passing when the clips and models are replaced: the clip index, the manifest, the model
// the page opens on, the history it opens on, and clips chosen by role and length.
import { readFileSync } from 'node:fs';
import type { ClipDoc, ClipIndex, ClipIndexEntry, Manifest, ModelEntry } from '../../web/src/contract/types';
import { movingStart } from '../../web/src/motion/moving-start';

export const index: ClipIndex = JSON.parse(readFileSync(new URL('../../public/clips/index.json', import.meta.url), 'utf8'));
export const manifest: Manifest = JSON.parse(readFileSync(new URL('../../public/models/manifest.json', import.meta.url), 'utf8'));

/** The clip the page falls back to when the index names no default (web/src/ui/app.ts DEFAULT_CLIP). */
const FALLBACK_CLIP = 'deepmimic_walker_walk_forward';

/** The model the page opens on: WAT (method "wat"), else the first with a K control, else the first. */
export const stageModel: ModelEntry = manifest.models.find((m) => m.method === 'wat')
  ?? manifest.models.find((m) => m.controls.some((c) => c.id === 'k')) ?? manifest.models[0];

/** Frames a WAT model may predict for its default action sequence (T_max per action); a fixed horizon otherwise. */
export function horizonFrames(entry: ModelEntry): number {
  const seq = entry.controls.find((c) => c.type === 'actions');
  const horizon = entry.controls.find((c) => c.id === 'horizon');
  if (horizon) return Math.round((horizon.default as number) * manifest.fps);
  return entry.params.future_frames * Math.max(1, seq ? (seq.default as string[]).length : 1);
}

/** The history the page opens on: the index's default, else the fallback clip at its first test frame. */
export function defaultHistory(): { clip: ClipIndexEntry; start: number } {
  const byName = (n?: string) => index.clips.find((c) => c.name === n);
  const clip = byName(index.default?.clip) ?? byName(FALLBACK_CLIP) ?? index.clips.find((c) => c.role === 'test')!;
  const n = stageModel.params.history_frames;
  if (index.default?.clip !== clip.name) return { clip, start: openingStart(clip, n) };
  // the index's start moved past a standing start, as the page does (web/src/motion/moving-start.ts)
  const doc = readClip(clip);
  const start = movingStart(Float32Array.from(doc.positions.flat(2)), doc.positions.length, doc.positions[0].length, index.fps, index.default.start);
  return { clip, start };
}

function readClip(clip: ClipIndexEntry): ClipDoc {
  return JSON.parse(readFileSync(new URL(`../../public/clips/${clip.file}`, import.meta.url), 'utf8')) as ClipDoc;
}

/** Where the page opens a picked clip for an n-frame history (web/src/ui/history-picker.ts defaultStart). */
export function openingStart(clip: ClipIndexEntry, n: number): number {
  const [a, b] = clip.test.find(([s, e]) => e - s >= n) ?? [0, clip.frames];
  const doc = readClip(clip);
  const moving = movingStart(Float32Array.from(doc.positions.flat(2)), doc.positions.length, doc.positions[0].length, index.fps, a);
  return moving + n <= b ? moving : a;
}

/** Clips with a test range of at least `frames` frames, longest first (ties by name). */
export function testClips(frames: number): ClipIndexEntry[] {
  const longest = (c: ClipIndexEntry) => Math.max(0, ...c.test.map(([a, b]) => b - a));
  return index.clips.filter((c) => longest(c) >= frames).sort((a, b) => longest(b) - longest(a) || a.name.localeCompare(b.name));
}

/** Another clip the stage model can predict from (at least its history long), other than `not`. */
export function otherClip(not: string, frames = stageModel.params.history_frames): ClipIndexEntry {
  const c = index.clips.find((x) => x.name !== not && x.frames >= frames);
  if (!c) throw new Error(`the clip index has no clip besides ${not} with ${frames} frames`);
  return c;
}
