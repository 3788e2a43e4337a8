import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import { Player, type FrameClock } from '../../web/src/ui/player';
import { advance, formatTime, frameAt, MAX_TICK_SECONDS, nextSpeed, phaseLabel, SPEEDS, stepFrame } from '../../web/src/ui/timeline';

describe('timeline arithmetic', () => {
  it('advances by wall clock x speed x fps', () => {
    expect(advance(0, 0.1, 1, 30, 100, true).position).toBeCloseTo(3);
    expect(advance(0, 0.1, 0.5, 30, 100, true).position).toBeCloseTo(1.5);
    expect(advance(10, 0.1, 2, 30, 100, true).position).toBeCloseTo(16);
  });

  it('wraps when looping and stops on the last frame otherwise', () => {
    expect(advance(37.5, 0.05, 1, 30, 38, true).position).toBeCloseTo(1);
    expect(advance(36.5, 0.1, 1, 30, 38, false)).toEqual({ position: 37, ended: true });
  });

  it('caps a long pause between ticks', () => {
    expect(advance(0, 10, 1, 30, 1000, true).position).toBeCloseTo(MAX_TICK_SECONDS * 30);
  });

  it('always stays inside [0, length)', () => {
    fc.assert(fc.property(
      fc.double({ min: 0, max: 500, noNaN: true }), fc.double({ min: -1, max: 5, noNaN: true }),
      fc.constantFrom(...SPEEDS), fc.integer({ min: 0, max: 500 }), fc.boolean(),
      (pos, dt, speed, length, loop) => {
        const p = advance(Math.min(pos, Math.max(0, length - 1)), dt, speed, 30, length, loop).position;
        return p >= 0 && (length <= 1 ? p === 0 : p < length);
      }));
  });

  it('shows whole frames and steps with wrap or clamp', () => {
    expect(frameAt(36.99, 38)).toBe(36);
    expect(frameAt(40, 38)).toBe(37);
    expect(frameAt(-1, 38)).toBe(0);
    expect(stepFrame(37, 1, 38, true)).toBe(0);
    expect(stepFrame(0, -10, 38, true)).toBe(28);
    expect(stepFrame(37, 1, 38, false)).toBe(37);
    expect(stepFrame(3, -10, 38, false)).toBe(0);
  });

  it('formats the read-out', () => {
    expect(formatTime(37, 120, 30)).toBe('t = 1.23 s / 4.00 s (frame 37)');
    expect(formatTime(0, 38, 30)).toBe('t = 0.00 s / 1.27 s (frame 0)');
  });

  it('counts t from the first predicted frame when there is a history: 0 there, negative before', () => {
    expect(formatTime(10, 100, 30, 10)).toBe('t = 0.00 s / 3.00 s (frame 10)');
    expect(formatTime(1, 100, 30, 10)).toBe('t = \u22120.30 s / 3.00 s (frame 1)');
    expect(formatTime(34, 100, 30, 10)).toBe('t = +0.80 s / 3.00 s (frame 34)');
    expect(phaseLabel(3, 30, 10)).toBe('history');
    expect(phaseLabel(10, 30, 10)).toBe('0.0 s');
    expect(phaseLabel(34, 30, 10)).toBe('+0.8 s');
    expect(phaseLabel(45, 30, 0)).toBe('1.5 s'); // a clip alone: its own time
  });

  it('walks the speed ladder between 0.25x and 2x', () => {
    expect(nextSpeed(1, 1)).toBe(1.25);
    expect(nextSpeed(1, -1)).toBe(0.75);
    expect(nextSpeed(2, 1)).toBe(2);
    expect(nextSpeed(0.25, -1)).toBe(0.25);
    expect(nextSpeed(0.6, 1)).toBe(0.75);
  });
});

/** A clock the test advances by hand. */
function manualClock() {
  let queued: ((now: number) => void) | null = null;
  let now = 0;
  const clock: FrameClock = { request: (cb) => { queued = cb; return 1; }, cancel: () => { queued = null; } };
  return { clock, tick(ms: number) { now += ms; const cb = queued; queued = null; cb?.(now); } };
}

describe('Player', () => {
  it('plays by elapsed time, pauses on a whole frame, and steps while paused', () => {
    const { clock, tick } = manualClock();
    const player = new Player(30, clock);
    player.load(38);
    player.play();
    tick(0); // first tick only sets the reference time
    tick(100);
    expect(player.state.position).toBeCloseTo(3);
    player.setSpeed(2);
    tick(100);
    expect(player.state.position).toBeCloseTo(9);
    player.pause();
    expect(player.state).toMatchObject({ playing: false, frame: 9, position: 9 });
    tick(1000);
    expect(player.state.frame).toBe(9);
    player.step(1);
    expect(player.state.frame).toBe(10);
    player.step(-11);
    expect(player.state.frame).toBe(37);
  });

  it('notifies subscribers and stops at the end when not looping', () => {
    const { clock, tick } = manualClock();
    const player = new Player(30, clock);
    const seen: number[] = [];
    player.subscribe((s) => seen.push(s.frame));
    player.load(10);
    player.setLoop(false);
    player.play();
    tick(0);
    tick(200);
    tick(200);
    expect(player.state).toMatchObject({ playing: false, frame: 9 });
    expect(seen.at(-1)).toBe(9);
    player.play(); // from the end, play starts over
    expect(player.state.frame).toBe(0);
  });

  it('will not play a timeline of one frame or less', () => {
    const player = new Player(30, manualClock().clock);
    player.load(1);
    player.play();
    expect(player.state.playing).toBe(false);
  });
});
