// A refusal is a way forward (issue 29 item 7): the history starts of a clip nearest the refused one,
// tried in order with the predictor the page runs, until one is accepted. Pure: the caller passes how
// a start is tried (web/src/ui/predict-controller.ts asks the worker, tests ask createCheckedPredictor).

/** Starts tried at most: a clip of any length is searched in about as many predictions. */
export const MAX_TRIES = 40;

/**
 * Every start of a clip (0..last) on a stride that keeps them within `maxTries`, nearest to `refused`
 * first (at equal distance, the later one first: its history is closer to where the futures were),
 * `refused` itself left out.
 */
export function candidateStarts(refused: number, last: number, maxTries = MAX_TRIES): number[] {
  if (last < 0) return [];
  const stride = Math.max(1, Math.ceil((last + 1) / maxTries));
  const out = new Set<number>();
  for (let s = refused % stride; s <= last; s += stride) if (s !== refused) out.add(s);
  // the clip's first and last start, whatever the stride
  for (const s of [0, last]) if (s !== refused) out.add(s);
  return [...out].sort((a, b) => Math.abs(a - refused) - Math.abs(b - refused) || b - a);
}

export type StartVerdict = 'accepted' | 'refused';

/**
 * The first of `starts` that `tryStart` accepts, or null when none is. `tryStart` throws to stop the
 * search (a newer request, a clip change): the error goes to the caller.
 */
export async function nearestAccepted(starts: readonly number[], tryStart: (start: number) => Promise<StartVerdict>,
  onTried?: (tried: number, of: number) => void): Promise<number | null> {
  for (let i = 0; i < starts.length; i++) {
    const verdict = await tryStart(starts[i]);
    onTried?.(i + 1, starts.length);
    if (verdict === 'accepted') return starts[i];
  }
  return null;
}
