// A clip's name as a newcomer reads it: "walk · person 10 (held out) · take 4" instead of cmu_10_04.
// The clip index (public/clips/index.json) gives the action, the person (subject), the take and the
// split role; a clip without an index entry (or an index without subject and take) falls back on its
// name's own pattern (cmu_<subject>_<take>, deepmimic_<motion>). A dropped file keeps its name.
import type { ClipIndexEntry, Role } from '../contract/types';
import type { Motion } from '../motion/clip';

/** What the title is made of: an index entry, or a Motion with what its name says. */
export interface ClipFacts {
  name: string;
  action: string;
  role: Role;
  subject?: number | string;
  take?: string;
}

const SPLIT: Record<Role, string> = { test: 'held out', train: 'trained on', 'train+test': 'tail held out' };
const pretty = (s: string) => s.replace(/_/g, ' ').trim();

/** "person 10", "DeepMimic", or null when the subject says nothing. */
function person(subject: number | string | undefined): string | null {
  if (subject === undefined || subject === '') return null;
  const s = String(subject);
  if (/^\d+$/.test(s)) return `person ${Number(s)}`;
  if (s.toLowerCase() === 'deepmimic') return 'DeepMimic';
  return pretty(s);
}

/** "take 4" from "10_04" (the subject's own prefix goes), or the take as written. */
function takeOf(take: string | undefined, subject: number | string | undefined): string | null {
  if (!take) return null;
  const m = /^(\d+)_(\d+)$/.exec(take);
  if (m && (subject === undefined || Number(m[1]) === Number(subject))) return `take ${Number(m[2])}`;
  return /^\d+$/.test(take) ? `take ${Number(take)}` : pretty(take);
}

/** What the name itself says when the index gives no subject or take. */
function fromName(name: string): { subject?: string; take?: string } {
  const cmu = /^cmu_(\d+)_(\d+)$/.exec(name);
  if (cmu) return { subject: cmu[1], take: `${cmu[1]}_${cmu[2]}` };
  const deep = /^deepmimic_(.+)$/.exec(name);
  if (deep) return { subject: 'deepmimic', take: deep[1] };
  return {};
}

/** The title's parts: the action, the person (null when unknown), the split, the take (null when it says nothing more). */
export function clipParts(c: ClipFacts): { action: string; who: string | null; split: string; take: string | null } {
  const guess = fromName(c.name);
  const subject = c.subject ?? guess.subject;
  let take = takeOf(c.take ?? guess.take, subject);
  // A DeepMimic take named after its action alone ("deepmimic_walk") says nothing more than the action.
  if (take && take === pretty(c.action)) take = null;
  const who = person(subject);
  return { action: pretty(c.action), who, split: SPLIT[c.role] ?? c.role, take: take ?? (who ? null : pretty(c.name)) };
}

/** "walk · person 10 (held out) · take 4"; "walk · DeepMimic (trained on) · walker walk forward". */
export function clipTitle(c: ClipFacts): string {
  const { action, who, split, take } = clipParts(c);
  return [action, who ? `${who} (${split})` : `(${split})`, take].filter(Boolean).join(' · ');
}

/** The title without what a clip list's headings already say (the action and the split): "person 10 · take 4". */
export function clipShortTitle(c: ClipFacts): string {
  const { who, take } = clipParts(c);
  return [who, take].filter(Boolean).join(' · ') || clipTitle(c);
}

/** The title of a motion on stage: a served clip by its index entry (when given), a dropped file by its name. */
export function motionTitle(m: Pick<Motion, 'name' | 'action' | 'role' | 'origin'>, entry?: ClipIndexEntry): string {
  if (m.origin?.kind === 'dropped-file') return m.name;
  const own = entry?.name === m.name ? entry : undefined;
  return clipTitle({ name: m.name, action: m.action, role: m.role, subject: own?.subject, take: own?.take });
}
