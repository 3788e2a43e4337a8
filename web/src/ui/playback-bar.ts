// Play/pause, frame steps, speed, scrubber and the time read-out, all bound to one Player.
import { el } from './dom';
import { icon } from './icons';
import type { Player, PlayerState } from './player';
import { formatTime, SPEEDS } from './timeline';

export function mountPlaybackBar(container: HTMLElement, player: Player): () => void {
  const back = el('button', { type: 'button', class: 'icon-button', 'aria-label': 'Previous frame', title: 'Previous frame (←)' }, icon('back'));
  const play = el('button', { type: 'button', class: 'icon-button play-button', 'data-testid': 'play' });
  const forward = el('button', { type: 'button', class: 'icon-button', 'aria-label': 'Next frame', title: 'Next frame (→)' }, icon('forward'));
  const scrubber = el('input', {
    type: 'range', class: 'scrubber', min: 0, max: 0, step: 1, value: 0, 'aria-label': 'Timeline position', 'data-testid': 'scrubber',
  });
  const readout = el('output', { class: 'time-readout', 'data-testid': 'time', 'aria-live': 'off' });
  const speed = el('select', { class: 'speed', 'aria-label': 'Playback speed', title: 'Playback speed ([ and ])' },
    ...SPEEDS.map((s) => el('option', { value: s }, `${s}×`)));
  container.replaceChildren(el('div', { class: 'playback-bar', role: 'group', 'aria-label': 'Playback' },
    back, play, forward, scrubber, readout, speed));

  back.addEventListener('click', () => player.step(-1));
  forward.addEventListener('click', () => player.step(1));
  play.addEventListener('click', () => player.toggle());
  scrubber.addEventListener('input', () => { player.pause(); player.seek(Number(scrubber.value)); });
  speed.addEventListener('change', () => player.setSpeed(Number(speed.value)));

  let shown: Partial<PlayerState> = {};
  return player.subscribe((s) => {
    if (s.playing !== shown.playing) {
      play.replaceChildren(icon(s.playing ? 'pause' : 'play'));
      play.setAttribute('aria-label', s.playing ? 'Pause' : 'Play');
      play.title = s.playing ? 'Pause (Space)' : 'Play (Space)';
    }
    if (s.length !== shown.length) {
      scrubber.max = String(Math.max(0, s.length - 1));
      for (const b of [back, play, forward, scrubber]) b.disabled = s.length <= 1;
    }
    if (s.frame !== shown.frame || s.length !== shown.length || s.fps !== shown.fps) {
      const text = s.length ? formatTime(s.frame, s.length, s.fps) : 'no clip';
      readout.textContent = text;
      scrubber.value = String(s.frame);
      scrubber.setAttribute('aria-valuetext', text);
    }
    if (s.speed !== shown.speed) speed.value = String(s.speed);
    shown = s;
  });
}
