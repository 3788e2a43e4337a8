// Play/pause, frame steps, speed, scrubber and the time read-out, all bound to one Player. With a
// prediction on stage the scrubber shades the history, marks where it ends (t = 0, the first
// predicted frame), each sample's action changes and its stop (Eq. 8) or cut (out of bounds), or,
// with a sample selected, every action change and stop of that sample (timeline-marks.ts), and t
// counts from the first predicted frame.
import { el } from './dom';
import { icon } from './icons';
import type { Player, PlayerState } from './player';
import { formatTime, SPEEDS } from './timeline';
import { markFraction, marksFor } from './timeline-marks';

export interface TimelineMark {
  frame: number;
  /** stop: an action (or the sample) stopped at this frame; cut: out of bounds; action: the next action starts. */
  kind: 'stop' | 'cut' | 'action';
  /** The action that starts here (kind 'action'). */
  action?: string;
  /** Shown only while its sample is selected (a stop inside a sequence). */
  detail?: boolean;
  /** CSS colour: the sample's identity colour. */
  colour: string;
  /** What the mark is, in words (its tooltip and accessible text). */
  label: string;
  sample: number;
}

export interface TimelineMarks {
  /** The first predicted frame (the history's length); 0 when there is no history. */
  origin: number;
  marks: TimelineMark[];
}

export interface PlaybackBar {
  /** Marks for what is on stage; null for a clip alone. */
  setTimeline(marks: TimelineMarks | null): void;
  /** Show only this sample's marks (all of them), or every sample's action changes and ends (null). */
  select(sample: number | null): void;
  dispose(): void;
}

export function mountPlaybackBar(container: HTMLElement, player: Player): PlaybackBar {
  const back = el('button', { type: 'button', class: 'icon-button', 'aria-label': 'Previous frame', title: 'Previous frame (←)' }, icon('back'));
  const play = el('button', { type: 'button', class: 'icon-button play-button', 'data-testid': 'play' });
  const forward = el('button', { type: 'button', class: 'icon-button', 'aria-label': 'Next frame', title: 'Next frame (→)' }, icon('forward'));
  const scrubber = el('input', {
    type: 'range', class: 'scrubber', min: 0, max: 0, step: 1, value: 0, 'aria-label': 'Timeline position', 'data-testid': 'scrubber',
  });
  const base = el('span', { class: 'scrubber-base' });
  const track = el('div', { class: 'scrubber-track', 'aria-hidden': 'true', 'data-testid': 'scrubber-marks' }, base);
  const wrap = el('div', { class: 'scrubber-wrap' }, track, scrubber);
  const readout = el('output', { class: 'time-readout', 'data-testid': 'time', 'aria-live': 'off' });
  const speed = el('select', { class: 'speed', 'aria-label': 'Playback speed', title: 'Playback speed ([ and ])' },
    ...SPEEDS.map((s) => el('option', { value: s }, `${s}×`)));
  container.replaceChildren(el('div', { class: 'playback-bar', role: 'group', 'aria-label': 'Playback' },
    back, play, forward, wrap, readout, speed));

  back.addEventListener('click', () => player.step(-1));
  forward.addEventListener('click', () => player.step(1));
  play.addEventListener('click', () => player.toggle());
  scrubber.addEventListener('input', () => { player.pause(); player.seek(Number(scrubber.value)); });
  speed.addEventListener('change', () => player.setSpeed(Number(speed.value)));

  let timeline: TimelineMarks | null = null;
  let selected: number | null = null;
  let shown: Partial<PlayerState> = {};
  /** A frame's place along the scrubber, where the range input's thumb centre is at that frame. */
  const at = (frame: number, length: number) => `calc(var(--thumb-half) + (100% - 2 * var(--thumb-half)) * ${markFraction(frame, length)})`;
  const drawMarks = (length: number) => {
    if (!timeline || length <= 1) { track.replaceChildren(base); wrap.removeAttribute('data-origin'); return; }
    const { origin } = timeline;
    const marks = marksFor(timeline.marks, selected);
    wrap.dataset.origin = String(origin);
    if (selected !== null) track.dataset.sample = String(selected); else delete track.dataset.sample;
    track.replaceChildren(base,
      el('span', { class: 'scrubber-history', style: `left: var(--thumb-half); width: calc(${at(origin, length)} - var(--thumb-half))`, title: 'history' }),
      el('span', { class: 'scrubber-now', style: `left: ${at(origin, length)}`, title: 'history ends: t = 0, the first predicted frame', 'data-frame': origin }),
      ...marks.map((m) => el('span', {
        class: `scrubber-mark scrubber-${m.kind}`, style: `left: ${at(m.frame, length)}; --mark-colour: ${m.colour}`,
        title: m.label, 'data-frame': m.frame, 'data-sample': m.sample, 'data-action': m.action,
      })),
    );
  };
  const unsubscribe = player.subscribe((s) => {
    if (s.playing !== shown.playing) {
      play.replaceChildren(icon(s.playing ? 'pause' : 'play'));
      play.setAttribute('aria-label', s.playing ? 'Pause' : 'Play');
      play.title = s.playing ? 'Pause (Space)' : 'Play (Space)';
    }
    if (s.length !== shown.length) {
      scrubber.max = String(Math.max(0, s.length - 1));
      for (const b of [back, play, forward, scrubber]) b.disabled = s.length <= 1;
      drawMarks(s.length);
    }
    if (s.frame !== shown.frame || s.length !== shown.length || s.fps !== shown.fps) updateTime(s);
    if (s.speed !== shown.speed) speed.value = String(s.speed);
    shown = s;
  });
  function updateTime(s: PlayerState): void {
    const text = s.length ? formatTime(s.frame, s.length, s.fps, timeline?.origin ?? 0) : 'no clip';
    // The frame number in a span of its own, which a narrow bar leaves out (embed/widget.css).
    const cut = text.indexOf(' (frame');
    if (cut < 0) readout.textContent = text;
    else readout.replaceChildren(text.slice(0, cut), el('span', { class: 'time-frame' }, text.slice(cut)));
    scrubber.value = String(s.frame);
    scrubber.setAttribute('aria-valuetext', text);
  }
  return {
    setTimeline(marks) {
      timeline = marks;
      selected = null; // a new prediction starts with no sample selected
      drawMarks(player.state.length);
      updateTime(player.state);
    },
    select(sample) {
      if (sample === selected) return;
      selected = sample;
      drawMarks(player.state.length);
    },
    dispose: unsubscribe,
  };
}
