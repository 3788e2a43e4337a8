// Actions and stops on stage, the pure parts: the scrubber's marks from each sample's segments (where
// the next action starts, where an action stopped, where the sample ends), which marks show with and
// without a selected sample, what a figure's label says at a frame, and the sample closest to the
// ground truth.
import { describe, expect, it } from 'vitest';
import type { Prediction } from '../../web/src/predictor/types';
import { markFraction, marksFor, timelineMarks } from '../../web/src/ui/timeline-marks';
import { bestSample } from '../../web/src/viewer/best';
import { figureStatus, sampleTrackInfo, type Track } from '../../web/src/viewer/tracks';

const fps = 30;
const N = 10;
/** Two samples of walk -> jump -> kick: #1 stops in walk and kick, not in jump; #2 stops only in jump. */
const p = {
  k: 2, frames: 40, joints: 1, futures: new Float32Array(2 * 40 * 3), lengths: Int32Array.from([30, 40]), notes: [],
  samples: [
    { length: 30, stopped: false, segments: [
      { start: 0, length: 10, action: 'walk', stopped: true }, { start: 10, length: 12, action: 'jump', stopped: false },
      { start: 22, length: 8, action: 'kick', stopped: true }] },
    { length: 40, stopped: false, segments: [
      { start: 0, length: 15, action: 'walk', stopped: false }, { start: 15, length: 15, action: 'jump', stopped: true },
      { start: 30, length: 10, action: 'kick', stopped: false }] },
  ],
} satisfies Prediction;

describe('scrubber marks of a 3-action run', () => {
  const t = timelineMarks(N, p, fps);
  const rows = (marks: typeof t.marks) => marks.map((m) => [m.sample, m.kind, m.frame, m.action ?? null]);

  it('marks each action change at its segment\'s start, each stop at its segment\'s last frame, after the history', () => {
    expect(t.origin).toBe(N);
    expect(rows(t.marks)).toEqual([
      [0, 'stop', N + 9, null], [0, 'action', N + 10, 'jump'], [0, 'action', N + 22, 'kick'], [0, 'stop', N + 29, null],
      [1, 'action', N + 15, 'jump'], [1, 'stop', N + 29, null], [1, 'action', N + 30, 'kick'],
    ]);
    const labels = t.marks.map((m) => m.label);
    expect(labels[0]).toBe('#1 walk stops at +0.33 s (Eq. 8)');
    expect(labels[1]).toBe('#1 walk → jump at +0.33 s');
    expect(labels[2]).toBe('#1 jump → kick at +0.73 s (jump did not stop: it ran its maximum length)');
    expect(labels[3]).toBe('#1 kick stops at +1.00 s');
    expect(t.marks.map((m) => m.colour)).toEqual(['rgb(214 39 40)', 'rgb(214 39 40)', 'rgb(214 39 40)', 'rgb(214 39 40)',
      'rgb(31 96 196)', 'rgb(31 96 196)', 'rgb(31 96 196)']);
  });

  it('with no sample selected shows every action change and each sample\'s end; with one, all of its marks only', () => {
    expect(rows(marksFor(t.marks, null))).toEqual([
      [0, 'action', N + 10, 'jump'], [1, 'action', N + 15, 'jump'], [0, 'action', N + 22, 'kick'], [0, 'stop', N + 29, null],
      [1, 'action', N + 30, 'kick'],
    ]);
    expect(rows(marksFor(t.marks, 1))).toEqual([[1, 'action', N + 15, 'jump'], [1, 'stop', N + 29, null], [1, 'action', N + 30, 'kick']]);
    expect(marksFor(t.marks, 0)).toHaveLength(4);
    expect(marksFor(t.marks, 5)).toEqual([]);
  });

  it('places a frame along the scrubber from 0 (first) to 1 (last)', () => {
    expect([0, 25, 49, 60].map((f) => markFraction(f, 50))).toEqual([0, 25 / 49, 1, 1]);
    expect(markFraction(3, 1)).toBe(0);
  });
});

describe('what a figure\'s label says', () => {
  const track = { startFrame: N, frames: 30, ...sampleTrackInfo(p.samples[0]) };

  it('names the action begun at each frame, and "stopped" from the last frame of a sample whose last action stopped', () => {
    const at = (t: number) => { const s = figureStatus(track, t); return [s.action, s.stopped]; };
    expect(at(5)).toEqual([null, false]);          // still the history
    expect(at(N)).toEqual(['walk', false]);
    expect(at(N + 9.5)).toEqual(['walk', false]);
    expect(at(N + 10)).toEqual(['jump', false]);
    expect(at(N + 22)).toEqual(['kick', false]);
    expect(at(N + 28)).toEqual(['kick', false]);
    expect(at(N + 29)).toEqual(['kick', true]);
    expect(at(N + 80)).toEqual(['kick', true]);
  });

  it('takes "stopped" from the last action; a cut sample or a single action is not labelled with either', () => {
    expect(sampleTrackInfo(p.samples[0]).stopped).toBe(true);
    expect(sampleTrackInfo(p.samples[1]).stopped).toBe(false);
    const cut = { ...p.samples[0], cut: { frame: 20, reason: 'cut: out of bounds' as const, detail: 'test' } };
    expect(sampleTrackInfo(cut).stopped).toBe(false);
    const single = { startFrame: 0, frames: 8, ...sampleTrackInfo({ length: 8, stopped: true, segments: [{ start: 0, length: 8, action: 'walk', stopped: true }] }) };
    expect(figureStatus(single, 3)).toEqual({ action: null, stopped: false });
    expect(figureStatus(single, 7)).toEqual({ action: null, stopped: true });
    expect(sampleTrackInfo(undefined)).toEqual({});
  });
});

describe('the sample closest to the ground truth', () => {
  const J = 2;
  /** A track of poses: each frame's joints at (x, 1 + j, 0). */
  const track = (id: string, role: Track['role'], xs: number[], sample?: number): Track => ({
    id, role, sample, startFrame: N, frames: xs.length, joints: J,
    positions: Float32Array.from(xs.flatMap((x) => [x, 1, 0, x, 2, 0])),
  });
  const truth = track('truth', 'truth', [0, 0.3, 0.6, 0.9]);

  it('is the smallest mean per-joint error over the truth\'s frames (cm); a short sample holds its last pose', () => {
    const tracks = [
      track('history', 'history', [0]), truth,
      track('s0', 'prediction', [0.1, 0.4, 0.7, 1.0], 0),     // 10 cm off at every frame
      track('s1', 'prediction', [0.02, 0.32, 0.62, 0.92], 1), // 2 cm
      track('s2', 'prediction', [0, 0.3], 2),                 // then holds x = 0.3: (0 + 0 + 30 + 60) / 4 cm
    ];
    const b = bestSample(tracks)!;
    expect(b.sample).toBe(1);
    expect(b.cm).toBeCloseTo(2, 4);
    expect(b.errors.map((e) => e.sample)).toEqual([0, 1, 2]);
    expect(b.errors[0].cm).toBeCloseTo(10, 4);
    expect(b.errors[2].cm).toBeCloseTo(22.5, 4);
    expect(b.frames).toBe(4);
  });

  it('gives a tie to the lower sample, and nothing without a ground truth or a sample', () => {
    const same = [truth, track('a', 'prediction', [0, 0.3, 0.6, 1.0], 3), track('b', 'prediction', [0, 0.3, 0.6, 1.0], 2)];
    expect(bestSample(same)!.sample).toBe(2);
    expect(bestSample([track('s0', 'prediction', [0], 0)])).toBeNull();
    expect(bestSample([truth])).toBeNull();
  });
});
