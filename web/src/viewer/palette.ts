// Figure colours: left/right limbs in a colour-blind-safe warm/cool pair within every tint family.
import type { TrackRole } from './tracks';

export type Side = 'left' | 'right' | 'mid';
export type Rgb = [number, number, number];
interface Hsl { h: number; s: number; l: number }

export function sideOf(jointName: string): Side {
  if (jointName.startsWith('left_')) return 'left';
  if (jointName.startsWith('right_')) return 'right';
  return 'mid';
}

export interface Tint {
  role: TrackRole;
  sample?: number;
  /** This figure is the selected sample. */
  selected?: boolean;
  /** Another sample is selected, so this one steps back. */
  muted?: boolean;
  /** The track has ended and holds its last pose. */
  ended?: boolean;
}

const FAMILIES: Record<Exclude<TrackRole, 'prediction'>, Record<Side, Hsl>> = {
  clip: { left: { h: 32, s: 0.95, l: 0.52 }, right: { h: 211, s: 0.78, l: 0.5 }, mid: { h: 210, s: 0.06, l: 0.6 } },
  history: { left: { h: 30, s: 0.35, l: 0.6 }, right: { h: 212, s: 0.3, l: 0.56 }, mid: { h: 0, s: 0, l: 0.6 } },
  truth: { left: { h: 75, s: 0.7, l: 0.5 }, right: { h: 168, s: 0.8, l: 0.34 }, mid: { h: 125, s: 0.45, l: 0.45 } },
};

const SELECTED: Record<Side, Hsl> = {
  left: { h: 28, s: 1, l: 0.55 }, right: { h: 205, s: 1, l: 0.52 }, mid: { h: 320, s: 0.75, l: 0.55 },
};

/**
 * Spread neighbouring samples across the family by the golden ratio, and step their lightness in
 * threes: hue steps inside one family are hard to tell apart with a colour-vision deficiency,
 * lightness steps are not (the list, the side-by-side cells and keys 1–9 number the samples too).
 */
function sampleHsl(side: Side, sample: number): Hsl {
  const u = (sample * 0.6180339887) % 1;
  const dl = [0, -0.14, 0.14][sample % 3];
  if (side === 'left') return { h: 12 + 42 * u, s: 0.85, l: 0.55 + dl };
  if (side === 'right') return { h: 188 + 62 * u, s: 0.7, l: 0.52 + dl };
  return { h: 270 + 60 * u, s: 0.18, l: 0.6 + dl };
}

function tintHsl(side: Side, tint: Tint): Hsl {
  let c: Hsl;
  if (tint.selected) c = SELECTED[side];
  else if (tint.role === 'prediction') c = sampleHsl(side, tint.sample ?? 0);
  else c = FAMILIES[tint.role][side];
  if (tint.muted && !tint.selected) c = { h: c.h, s: c.s * 0.35, l: c.l + (0.62 - c.l) * 0.5 };
  if (tint.ended) c = { h: c.h, s: c.s * 0.5, l: c.l * 0.7 };
  return c;
}

export function hslToRgb({ h, s, l }: Hsl): Rgb {
  const k = (n: number) => (n + h / 30) % 12;
  const a = s * Math.min(l, 1 - l);
  const f = (n: number) => l - a * Math.max(-1, Math.min(k(n) - 3, 9 - k(n), 1));
  return [f(0), f(8), f(4)];
}

/** sRGB colour (0..1) of one side of a figure. */
export function tintColour(side: Side, tint: Tint): Rgb {
  return hslToRgb(tintHsl(side, tint));
}

/** Thickness factor: the selected sample stands out. */
export function tintScale(tint: Tint): number {
  return tint.selected ? 1.35 : 1;
}
