// Figure colours. Every figure has an identity colour, worn on its torso and head and repeated in its
// label, its root path, the legend, the samples list and the curves: grey for the history, green for
// the ground truth, one distinct colour per sample. Limbs keep a colour-blind-safe warm (left) /
// cool (right) pair within every family, so a figure's sides can still be read.
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

const LIMBS: Record<Exclude<TrackRole, 'prediction'>, Record<'left' | 'right', Hsl>> = {
  clip: { left: { h: 32, s: 0.95, l: 0.52 }, right: { h: 211, s: 0.78, l: 0.5 } },
  history: { left: { h: 30, s: 0.35, l: 0.6 }, right: { h: 212, s: 0.3, l: 0.56 } },
  truth: { left: { h: 75, s: 0.7, l: 0.5 }, right: { h: 168, s: 0.8, l: 0.34 } },
};

/** sRGB bytes of each role's identity colour (the torso and head). */
const ROLE_IDENTITY: Record<Exclude<TrackRole, 'prediction'>, Rgb> = {
  clip: [96, 110, 128],
  history: [128, 128, 128],
  truth: [36, 140, 64],
};

/**
 * The first ten samples' identity colours (sRGB bytes): distinct in hue and in lightness, with no
 * green (the ground truth's) and no grey (the history's). Later samples continue by golden-angle
 * hues outside the green band.
 */
const SAMPLE_IDENTITY: Rgb[] = [
  [214, 39, 40], [31, 96, 196], [148, 103, 189], [230, 145, 20], [23, 170, 190],
  [227, 90, 180], [140, 86, 75], [110, 110, 20], [20, 40, 120], [200, 60, 110],
];

const bytes = ([r, g, b]: Rgb): Rgb => [Math.round(r * 255), Math.round(g * 255), Math.round(b * 255)];
const unit = ([r, g, b]: Rgb): Rgb => [r / 255, g / 255, b / 255];

function sampleIdentityBytes(sample: number): Rgb {
  if (sample < SAMPLE_IDENTITY.length) return SAMPLE_IDENTITY[sample];
  let h = (15 + sample * 137.508) % 360;
  if (h > 80 && h < 170) h += 90;   // skip the truth's green
  return bytes(hslToRgb({ h: h % 360, s: 0.62, l: [0.45, 0.36, 0.56][sample % 3] }));
}

/** The identity colour of a figure (0..1 sRGB, quantised to bytes so CSS and WebGL show the same colour). */
export function identityColour(role: TrackRole, sample = 0): Rgb {
  return unit(role === 'prediction' ? sampleIdentityBytes(sample) : ROLE_IDENTITY[role]);
}

/** The identity colour as CSS ("rgb(214 39 40)"), for swatches, labels and plots. */
export function identityCss(role: TrackRole, sample = 0): string {
  const [r, g, b] = bytes(identityColour(role, sample));
  return `rgb(${r} ${g} ${b})`;
}

/** The identity colour as "#rrggbb". */
export function identityHex(role: TrackRole, sample = 0): string {
  return `#${bytes(identityColour(role, sample)).map((v) => v.toString(16).padStart(2, '0')).join('')}`;
}

/**
 * Limbs of a sample: the warm/cool pair, spread across the family by the golden ratio and stepped in
 * lightness, so neighbouring samples differ even where hue steps are hard to see.
 */
function sampleLimbHsl(side: 'left' | 'right', sample: number): Hsl {
  const u = (sample * 0.6180339887) % 1;
  const dl = [0, -0.12, 0.12][sample % 3];
  if (side === 'left') return { h: 12 + 42 * u, s: 0.85, l: 0.55 + dl };
  return { h: 188 + 62 * u, s: 0.7, l: 0.52 + dl };
}

function rgbToHsl([r, g, b]: Rgb): Hsl {
  const max = Math.max(r, g, b);
  const min = Math.min(r, g, b);
  const l = (max + min) / 2;
  if (max === min) return { h: 0, s: 0, l };
  const d = max - min;
  const s = d / (1 - Math.abs(2 * l - 1));
  const h = max === r ? ((g - b) / d + 6) % 6 : max === g ? (b - r) / d + 2 : (r - g) / d + 4;
  return { h: h * 60, s, l };
}

function baseHsl(side: Side, tint: Tint): Hsl {
  if (side === 'mid') return rgbToHsl(identityColour(tint.role, tint.sample ?? 0));
  if (tint.role === 'prediction') return sampleLimbHsl(side, tint.sample ?? 0);
  return LIMBS[tint.role][side];
}

function tintHsl(side: Side, tint: Tint): Hsl | null {
  // The identity colour comes back as its exact bytes (see tintColour), also once the track has ended
  // (its limbs dim) and when it is selected (it is drawn thicker); only stepping back for another
  // selected sample mutes it.
  if (side === 'mid' && !(tint.muted && !tint.selected)) return null;
  let c = baseHsl(side, tint);
  if (tint.selected && side !== 'mid') c = { h: c.h, s: Math.min(1, c.s * 1.1 + 0.05), l: Math.min(0.62, c.l + 0.04) };
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
  const c = tintHsl(side, tint);
  return c === null ? identityColour(tint.role, tint.sample ?? 0) : hslToRgb(c);
}

/** Thickness factor: the selected sample stands out. */
export function tintScale(tint: Tint): number {
  return tint.selected ? 1.35 : 1;
}
