// The scrubber's marks of a prediction, from each sample's length, stop flags and segments: where the
// history ends (t = 0), where each sample's next action starts, where an action stopped (Eq. 8) and
// where a sample was cut (out of bounds). With no sample selected the bar shows every sample's action
// changes and its end (stop or cut); with one selected, every mark of that sample only, its stops
// inside the sequence too (playback-bar.ts shows what marksFor picks).
import type { Prediction } from '../predictor/types';
import { identityCss } from '../viewer/palette';
import type { TimelineMark, TimelineMarks } from './playback-bar';
import { seconds } from './prediction-panel';

const pretty = (a: string) => a.replace(/_/g, ' ');

/** Every mark of every sample; `n`: the history's length (the first predicted frame on the timeline). */
export function timelineMarks(n: number, p: Prediction, fps: number): TimelineMarks {
  const marks: TimelineMark[] = [];
  p.samples.forEach((s, i) => {
    const colour = identityCss('prediction', i);
    const name = `#${i + 1}`;
    const at = (frame: number) => `+${seconds(frame, fps)}`;
    // segments past a cut were dropped by the guard (predictor/guard.ts); the ones left are in order
    const segs = s.segments.filter((g) => g.start < s.length);
    for (let j = 1; j < segs.length; j++) {
      const before = segs[j - 1];
      const g = segs[j];
      if (before.stopped) {
        const end = before.start + before.length - 1;
        marks.push({
          frame: n + end, kind: 'stop', colour, sample: i, detail: true,
          label: `${name} ${before.action ? `${pretty(before.action)} ` : ''}stops at ${at(end + 1)} (Eq. 8)`,
        });
      }
      const ran = before.stopped === false ? ` (${before.action ? pretty(before.action) : 'the action before'} did not stop: it ran its maximum length)` : '';
      marks.push({
        frame: n + g.start, kind: 'action', colour, sample: i, action: g.action,
        label: `${name} ${before.action && g.action ? `${pretty(before.action)} → ${pretty(g.action)}` : 'next action'} at ${at(g.start)}${ran}`,
      });
    }
    const last = segs[segs.length - 1];
    const stopped = last?.stopped ?? s.stopped;
    if (!s.cut && !stopped) return;
    marks.push({
      frame: n + Math.max(0, s.length - 1), kind: s.cut ? 'cut' : 'stop', colour, sample: i,
      label: s.cut ? `${name} cut at ${at(s.length)} (out of bounds)`
        : `${name} ${last?.action && segs.length > 1 ? `${pretty(last.action)} ` : ''}stops at ${at(s.length)}`,
    });
  });
  return { origin: n, marks };
}

/** The marks the bar shows: with no sample selected every sample's action changes and end; with one
 *  selected, all of its own marks. In frame order. */
export function marksFor(all: readonly TimelineMark[], selected: number | null): TimelineMark[] {
  const shown = selected === null ? all.filter((m) => !m.detail) : all.filter((m) => m.sample === selected);
  return [...shown].sort((a, b) => a.frame - b.frame || a.sample - b.sample);
}

/** Where frame `frame` sits along a scrubber of `length` frames, 0 (first) to 1 (last). */
export function markFraction(frame: number, length: number): number {
  return length > 1 ? Math.min(1, Math.max(0, frame / (length - 1))) : 0;
}
