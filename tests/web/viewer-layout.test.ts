import { describe, expect, it } from 'vitest';
import { CELL_SPACING, chooseColumns, layoutTracks, ROW_SPACING } from '../../web/src/viewer/layout';
import { hslToRgb, identityColour, identityCss, identityHex, sideOf, tintColour, type Side } from '../../web/src/viewer/palette';
import { poseInto, timelineLength, trackPose, type TrackRole } from '../../web/src/viewer/tracks';

describe('track poses on the shared timeline', () => {
  const history = { frames: 25, startFrame: 0 };
  const prediction = { frames: 60, startFrame: 25 };

  it('spans every track', () => {
    expect(timelineLength([history, prediction])).toBe(85);
    expect(timelineLength([])).toBe(0);
  });

  it('hides a track before it starts, blends within it, holds its last pose after', () => {
    expect(trackPose(prediction, 10).state).toBe('pending');
    expect(trackPose(prediction, 25)).toEqual({ state: 'playing', a: 0, b: 1, w: 0 });
    expect(trackPose(prediction, 26.25)).toEqual({ state: 'playing', a: 1, b: 2, w: 0.25 });
    expect(trackPose(history, 24.5)).toEqual({ state: 'playing', a: 24, b: 24, w: 0 });
    expect(trackPose(history, 25)).toEqual({ state: 'ended', a: 24, b: 24, w: 0 });
    expect(trackPose(history, 80).state).toBe('ended');
  });

  it('blends joint positions linearly', () => {
    const track = { positions: Float32Array.from([0, 0, 0, 2, 4, 6]), joints: 1 };
    const out = new Float32Array(3);
    expect(Array.from(poseInto(track, { state: 'playing', a: 0, b: 1, w: 0.5 }, out))).toEqual([1, 2, 3]);
  });
});

describe('layout', () => {
  const tracks: { role: TrackRole; sample?: number }[] = [
    { role: 'history' }, { role: 'prediction', sample: 1 }, { role: 'prediction', sample: 0 }, { role: 'truth' },
  ];

  it('overlay puts every figure at the origin', () => {
    const l = layoutTracks(tracks, 'overlay');
    expect(l.placements.map((p) => [p.track, p.x, p.z])).toEqual([[0, 0, 0], [1, 0, 0], [2, 0, 0], [3, 0, 0]]);
  });

  it('side by side: truth first, samples in order, history shared by every cell', () => {
    const l = layoutTracks(tracks, 'side');
    expect(l.cells).toBe(3);
    const own = l.placements.filter((p) => !p.shared);
    expect(own.map((p) => p.track)).toEqual([3, 2, 1]);
    expect(own[1].x - own[0].x).toBeCloseTo(CELL_SPACING);
    expect(l.rows).toBe(1);
    const shared = l.placements.filter((p) => p.shared);
    expect(shared.map((p) => [p.track, p.cell])).toEqual([[0, 0], [0, 1], [0, 2]]);
  });

  it('grids many samples in rows receding in z, centred on the origin', () => {
    const many = Array.from({ length: 51 }, (_, i) => (i === 0 ? { role: 'truth' as const } : { role: 'prediction' as const, sample: i - 1 }));
    const l = layoutTracks(many, 'side');
    expect(l.cols * l.rows).toBeGreaterThanOrEqual(51);
    expect(l.cols).toBeGreaterThan(l.rows);
    const xs = l.placements.map((p) => p.x);
    const zs = l.placements.map((p) => p.z);
    expect(Math.min(...xs)).toBeCloseTo(-Math.max(...xs));
    expect(Math.min(...zs)).toBeCloseTo(-Math.max(...zs));
    expect(l.placements[0]).toMatchObject({ track: 0, cell: 0 });
    expect(l.placements[0].z).toBe(Math.min(...zs));
    expect(l.placements[l.cols].z - l.placements[0].z).toBeCloseTo(ROW_SPACING);
  });

  it('lays the grid out in the figures\' own frame: columns across their heading, rows along it', () => {
    const five = Array.from({ length: 6 }, (_, i) => (i === 0 ? { role: 'truth' as const } : { role: 'prediction' as const, sample: i - 1 }));
    const facingZ = layoutTracks(five, 'side', { heading: 0 });
    const facingX = layoutTracks(five, 'side', { heading: Math.PI / 2 });
    // turning the heading by 90 degrees turns every cell's offset with it
    facingZ.placements.forEach((p, i) => {
      const q = facingX.placements[i];
      expect(q.x).toBeCloseTo(p.z, 9);
      expect(q.z).toBeCloseTo(-p.x, 9);
    });
    // cells grow to the room the figures need
    const wide = layoutTracks(five, 'side', { cellWidth: 3, cellDepth: 4 });
    expect(wide.spacing).toBe(3);
    expect(wide.rowSpacing).toBe(4);
    const own = wide.placements.filter((p) => !p.shared);
    expect(Math.abs(own[1].x - own[0].x)).toBeCloseTo(3);
  });

  it('chooses the columns that let the grid fill a wide or a tall view', () => {
    expect(chooseColumns(11, 1.2, 2, 1.6)).toBeGreaterThan(chooseColumns(11, 1.2, 2, 0.6));
    expect(chooseColumns(1, 1, 1, 1)).toBe(1);
    for (let cells = 1; cells <= 51; cells += 5) {
      const cols = chooseColumns(cells, CELL_SPACING, ROW_SPACING, 1.6);
      expect(cols).toBeGreaterThanOrEqual(1);
      expect(cols).toBeLessThanOrEqual(cells);
    }
  });

  it('a lone history track gets a cell of its own', () => {
    expect(layoutTracks([{ role: 'history' }], 'side').placements).toEqual([{ track: 0, cell: 0, x: 0, z: 0, shared: false }]);
  });
});

describe('palette', () => {
  const hue = ([r, g, b]: number[]) => {
    const max = Math.max(r, g, b), min = Math.min(r, g, b);
    if (max === min) return 0;
    const h = max === r ? (g - b) / (max - min) : max === g ? 2 + (b - r) / (max - min) : 4 + (r - g) / (max - min);
    return ((h * 60) + 360) % 360;
  };

  it('names sides from joint names', () => {
    expect(['left_knee', 'right_wrist', 'head', 'root'].map(sideOf)).toEqual(['left', 'right', 'mid', 'mid']);
  });

  it('converts HSL', () => {
    expect(hslToRgb({ h: 0, s: 1, l: 0.5 })).toEqual([1, 0, 0]);
    expect(hslToRgb({ h: 240, s: 1, l: 0.5 })).toEqual([0, 0, 1]);
  });

  it('keeps left warm and right cool for every role and sample', () => {
    const tints = [
      { role: 'clip' as const }, { role: 'history' as const }, { role: 'truth' as const },
      ...Array.from({ length: 50 }, (_, sample) => ({ role: 'prediction' as const, sample })),
      { role: 'prediction' as const, sample: 3, selected: true },
    ];
    for (const t of tints) {
      const left = hue(tintColour('left', t));
      const right = hue(tintColour('right', t));
      expect(Math.abs(left - right), JSON.stringify(t)).toBeGreaterThan(60);
    }
  });

  it('gives every figure one identity colour, on its torso and head, that CSS and WebGL show alike', () => {
    const roles: { role: TrackRole; sample?: number }[] = [{ role: 'history' }, { role: 'truth' }, ...Array.from({ length: 50 }, (_, sample) => ({ role: 'prediction' as const, sample }))];
    const hexes = roles.map((t) => identityHex(t.role, t.sample));
    expect(new Set(hexes.slice(0, 12)).size).toBe(12); // history, truth and the first ten samples all differ
    for (const t of roles) {
      // the torso keeps the identity colour whether the track plays, ended or is selected
      for (const tint of [t, { ...t, ended: true }, { ...t, selected: true }]) expect(tintColour('mid', tint)).toEqual(identityColour(t.role, t.sample));
      const [r, g, b] = identityColour(t.role, t.sample).map((v) => Math.round(v * 255));
      expect(identityCss(t.role, t.sample)).toBe(`rgb(${r} ${g} ${b})`);
      // whole sRGB bytes, so a swatch and the GPU's instance colour read back the same '#rrggbb'
      expect(identityColour(t.role, t.sample).every((v) => Math.abs(v * 255 - Math.round(v * 255)) < 1e-9)).toBe(true);
    }
    // a sample stepping back for a selected one is muted
    expect(tintColour('mid', { role: 'prediction', sample: 1, muted: true })).not.toEqual(identityColour('prediction', 1));
  });

  it('dims an ended track and mutes unselected samples', () => {
    const lum = (side: Side, t: Parameters<typeof tintColour>[1]) => tintColour(side, t).reduce((a, b) => a + b, 0);
    expect(lum('left', { role: 'clip', ended: true })).toBeLessThan(lum('left', { role: 'clip' }));
    const sat = (c: number[]) => Math.max(...c) - Math.min(...c);
    expect(sat(tintColour('right', { role: 'prediction', sample: 2, muted: true })))
      .toBeLessThan(sat(tintColour('right', { role: 'prediction', sample: 2 })));
  });
});
