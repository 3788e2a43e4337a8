// The closest-to-truth highlight in compare mode (issue 29 item 4): one closest sample per method's
// row, each against its own row's truth; one model is one row, as the single view.
import { describe, expect, it } from 'vitest';
import { bestPerRow, bestSample } from '../../web/src/viewer/best';
import type { Track } from '../../web/src/viewer/tracks';

const J = 2;
/** A track of poses: each frame's joints at (x, 1 + j, 0), in row `group`. */
const track = (id: string, role: Track['role'], xs: number[], sample?: number, group?: number, groupLabel?: string): Track => ({
  id, role, sample, startFrame: 10, frames: xs.length, joints: J, group, groupLabel,
  positions: Float32Array.from(xs.flatMap((x) => [x, 1, 0, x, 2, 0])),
});
const truthXs = [0, 0.3, 0.6, 0.9];

describe('closest sample per compared row', () => {
  it('marks the closest sample within each row, against that row\'s truth, in row order', () => {
    const tracks = [
      track('truth:0', 'truth', truthXs, undefined, 0, 'WAT (RNN)'),
      track('s:0:0', 'prediction', [0.1, 0.4, 0.7, 1.0], 0, 0, 'WAT (RNN)'),    // 10 cm
      track('s:0:1', 'prediction', [0.02, 0.32, 0.62, 0.92], 1, 0, 'WAT (RNN)'), // 2 cm: row 0's closest
      track('truth:1', 'truth', truthXs, undefined, 1, 'LCP-VAE'),
      track('s:1:0', 'prediction', [0.05, 0.35, 0.65, 0.95], 0, 1, 'LCP-VAE'),   // 5 cm: row 1's closest
      track('s:1:1', 'prediction', [0.3, 0.6, 0.9, 1.2], 1, 1, 'LCP-VAE'),      // 30 cm
    ];
    const rows = bestPerRow(tracks);
    expect(rows.map((r) => [r.group, r.groupLabel, r.sample])).toEqual([[0, 'WAT (RNN)', 1], [1, 'LCP-VAE', 0]]);
    expect(rows[0].cm).toBeCloseTo(2, 4);
    expect(rows[1].cm).toBeCloseTo(5, 4);
    // the whole stage at once would pick only row 0's #2 (2 cm) and leave row 1 unmarked
    expect(bestSample(tracks)!.sample).toBe(1);
  });

  it('one model (no groups) is one row, the same as bestSample', () => {
    const tracks = [track('truth', 'truth', truthXs), track('s0', 'prediction', [0.1, 0.4, 0.7, 1.0], 0), track('s1', 'prediction', [0, 0.3, 0.6, 0.95], 1)];
    const rows = bestPerRow(tracks);
    expect(rows).toHaveLength(1);
    expect(rows[0]).toMatchObject({ group: 0, sample: bestSample(tracks)!.sample, cm: bestSample(tracks)!.cm });
    expect(rows[0]).not.toHaveProperty('groupLabel');
  });

  it('a row without futures or truth, or whose tracks do not fit its truth, has none; the others keep theirs', () => {
    const odd: Track = { ...track('s:2:0', 'prediction', [0, 0], 0, 2), joints: 1, positions: new Float32Array(6) };
    const tracks = [
      track('truth:0', 'truth', truthXs, undefined, 0), track('s:0:0', 'prediction', truthXs, 0, 0),
      track('history:1', 'history', [0], undefined, 1),   // a refused row draws no futures
      track('truth:2', 'truth', truthXs, undefined, 2), odd,
    ];
    expect(bestPerRow(tracks).map((r) => [r.group, r.sample, r.cm])).toEqual([[0, 0, 0]]);
  });
});
