// Pure timeline arithmetic for the player: advancing, wrapping, stepping and the time read-out.

export const SPEEDS = [0.25, 0.5, 0.75, 1, 1.25, 1.5, 2] as const;
/** Longest wall-clock step taken in one tick, so a tab coming back from the background does not jump. */
export const MAX_TICK_SECONDS = 0.25;

/**
 * Advance a fractional frame position by `seconds` of wall-clock time.
 * Looping wraps into [0, length); otherwise it stops on the last frame and reports `ended`.
 */
export function advance(
  position: number, seconds: number, speed: number, fps: number, length: number, loop: boolean,
): { position: number; ended: boolean } {
  if (length <= 1) return { position: 0, ended: !loop };
  const dt = Math.min(Math.max(seconds, 0), MAX_TICK_SECONDS);
  const p = position + dt * speed * fps;
  if (loop) return { position: ((p % length) + length) % length, ended: false };
  if (p >= length - 1) return { position: length - 1, ended: true };
  return { position: p, ended: false };
}

/** The whole frame shown at a position, within [0, length - 1]. */
export function frameAt(position: number, length: number): number {
  if (length <= 0) return 0;
  return Math.min(length - 1, Math.max(0, Math.floor(position + 1e-9)));
}

/** Step whole frames from the shown frame; wraps when looping, clamps otherwise. */
export function stepFrame(frame: number, delta: number, length: number, loop: boolean): number {
  if (length <= 0) return 0;
  const f = frame + delta;
  if (loop) return ((f % length) + length) % length;
  return Math.min(length - 1, Math.max(0, f));
}

/**
 * "t = 1.23 s / 4.00 s (frame 37)": time of the frame / duration of the timeline. With an `origin`
 * (the first predicted frame, after a history of that many frames) t counts from it: the history
 * reads negative ("t = −0.30 s / 3.00 s (frame 1)") and the duration is the future's.
 */
export function formatTime(frame: number, length: number, fps: number, origin = 0): string {
  const t = (frame - origin) / fps;
  return `t = ${signed(t, 2, origin > 0)} s / ${((length - origin) / fps).toFixed(2)} s (frame ${frame})`;
}

/** The stage's phase label: "history" before the origin, "+0.8 s" after it; the clip's own time without one. */
export function phaseLabel(frame: number, fps: number, origin: number): string {
  if (origin <= 0) return `${(frame / fps).toFixed(1)} s`;
  if (frame < origin) return 'history';
  return `${signed((frame - origin) / fps, 1, true)} s`;
}

/** A number with a typographic minus, and a plus sign when asked; zero has no sign. */
function signed(v: number, digits: number, plus: boolean): string {
  const text = Math.abs(v).toFixed(digits);
  if (Number(text) === 0) return text;
  if (v < 0) return `\u2212${text}`;
  return plus ? `+${text}` : text;
}

/** The next speed up (+1) or down (-1) the ladder, from whatever the current speed is. */
export function nextSpeed(speed: number, direction: 1 | -1): number {
  if (direction > 0) return SPEEDS.find((s) => s > speed + 1e-9) ?? SPEEDS[SPEEDS.length - 1];
  return [...SPEEDS].reverse().find((s) => s < speed - 1e-9) ?? SPEEDS[0];
}

export function clampSpeed(speed: number): number {
  return Math.min(SPEEDS[SPEEDS.length - 1], Math.max(SPEEDS[0], speed));
}
