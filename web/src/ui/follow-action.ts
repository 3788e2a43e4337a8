// Which action sequence a newly picked clip (or newly picked model) should get. The page predicts
// the action the history shows, as the first view does, until the user composes a sequence: a
// salsa history then gets "salsa" futures instead of the last clip's "walk". A composed sequence
// is the user's and stays.

const same = (a: readonly string[], b: readonly string[]) => a.length === b.length && a.every((x, i) => x === b[i]);

/**
 * The sequence to set, or null to leave it. `current`: the sequence on screen; `pageSet`: the one
 * the page set last (null if none); `modelDefault`: the model's default; `known`: the actions the
 * model can be asked for.
 */
export function followedSequence(current: readonly string[], pageSet: readonly string[] | null,
  modelDefault: readonly string[], clipAction: string | undefined, known: readonly string[]): string[] | null {
  if (!clipAction || !known.includes(clipAction)) return null;
  const pages = same(current, modelDefault) || (pageSet !== null && same(current, pageSet));
  if (!pages || same(current, [clipAction])) return null;
  return [clipAction];
}
