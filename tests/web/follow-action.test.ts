// The action sequence a new clip or model gets (web/src/ui/follow-action.ts).
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import { followedSequence } from '../../web/src/ui/follow-action';

const KNOWN = ['walk', 'run_jog', 'dance_salsa', 'kick'];

describe('followedSequence', () => {
  it("asks for the clip's action while the sequence is the model's default or the page's", () => {
    expect(followedSequence(['walk'], null, ['walk'], 'dance_salsa', KNOWN)).toEqual(['dance_salsa']);
    expect(followedSequence(['dance_salsa'], ['dance_salsa'], ['walk'], 'kick', KNOWN)).toEqual(['kick']);
  });

  it('leaves a composed sequence, an action the model does not know and a sequence that already matches', () => {
    expect(followedSequence(['walk', 'kick'], ['walk'], ['walk'], 'dance_salsa', KNOWN)).toBeNull();
    expect(followedSequence(['walk'], null, ['walk'], 'backflip', KNOWN)).toBeNull();
    expect(followedSequence(['walk'], null, ['walk'], undefined, KNOWN)).toBeNull();
    expect(followedSequence(['kick'], ['kick'], ['walk'], 'kick', KNOWN)).toBeNull();
  });

  it("never returns anything but the clip's known action alone", () => {
    const seq = fc.array(fc.constantFrom(...KNOWN), { maxLength: 4 });
    fc.assert(fc.property(seq, fc.option(seq, { nil: null }), seq, fc.constantFrom(...KNOWN, 'backflip'), (cur, page, def, action) => {
      const next = followedSequence(cur, page, def, action, KNOWN);
      if (next === null) return;
      expect(next).toEqual([action]);
      expect(KNOWN).toContain(action);
      // only the page's own sequences are replaced
      expect(JSON.stringify(cur) === JSON.stringify(def) || JSON.stringify(cur) === JSON.stringify(page)).toBe(true);
    }));
  });
});
