// The stage notice's one sentence (issue 30): a reflected or frozen history or a rescaled body leads with
// its own sentence (the fix), a range finding with "Out of range"; warnings arrive most likely cause first.
import { describe, expect, it } from 'vitest';
import { HANDEDNESS_MESSAGE } from '../../web/src/motion/handedness';
import { ordered } from '../../web/src/predictor/history';
import type { RangeWarning } from '../../web/src/predictor/types';
import { rangeHeadline } from '../../web/src/ui/stage-parts';

const height: RangeWarning = { quantity: 'root_height', value: 1.5, min: 0.8, max: 1.1, unit: 'm', message: 'The history\'s root height is 1.50 m, outside…' };
const swapped: RangeWarning = { quantity: 'handedness', value: -0.6, min: 0, max: 1, unit: '', message: HANDEDNESS_MESSAGE };

describe('the range notice headline', () => {
  it('leads with the reflected body\'s own sentence, whatever order the warnings came in', () => {
    const text = rangeHeadline(ordered([height, swapped]), 'WAT RNN');
    expect(text.startsWith('Left and right look swapped')).toBe(true);
    expect(text).toContain('(1 more under Details)');
    expect(text).not.toMatch(/^Out of range/);
  });
  it('keeps "Out of range" for a range finding alone', () => {
    expect(rangeHeadline([height], 'WAT RNN')).toMatch(/^Out of range: .*WAT RNN.*\(root_height\); the futures are shown anyway\.$/);
  });
});
