// Figure: WAT's smoothness prior (Eq. 4) on a real transition. The last L frames of one clip are
// joined to the first L of another; one joint coordinate is plotted with its approximation by the
// first M DCT bases, and L_smooth (over all joints, the predictor's smoothness()) is read out,
// beside the same loss for L + L captured frames of the first clip, which need no join.
import type { Motion } from '../motion/clip';
import { window as clipWindow } from '../motion/clip';
import { canonicalise, rootRelative } from '../predictor/canonical';
import { smoothness } from '../sampling/dct-smoothness';
import { el } from '../ui/dom';
import type { ExplainerData } from './data';
import { figureShell, num, pretty, readout, select, slider } from './figure';
import { chart, fitWidth, extentOf, line, svg, vRule } from './plot';
import { coordinate, dctApproximation, joinWindows } from './transition';

const AXES = ['x (left–right)', 'y (up)', 'z (forward)'];

export async function mountDctFigure(host: HTMLElement, data: ExplainerData): Promise<void> {
  const wat = data.model('wat');
  const smooth = wat?.params.smoothness;
  // WAT's supplement: L = 10, M = 5; the served model's own values when it is there.
  const l = smooth?.l ?? 10;
  const state = { a: data.firstOf('walk'), b: data.firstOf('punch'), joint: 'right_wrist', axis: 1, m: smooth?.m ?? 5 };
  const f = figureShell(host, 'fig-dct', '1. A smooth transition is one the first DCT bases can draw',
    [`WAT trains transitions between actions it never saw joined. It joins the last L = ${l} frames of one action to the `,
      `first ${l} of another and asks the predicted frames in between to be smooth: the ${2 * l} poses Z should be close to `,
      'their projection on the first M cosine (DCT) bases, Z D Dᵀ. The loss L_smooth = 1/(2L) Σ‖z_i − z̃_i‖² is large where the join jumps. ',
      'Move M: few bases draw only slow motion, so a jump shows as a large residual; with more bases the approximation follows the jump too.'],
    'WAT: Mao, Liu, Salzmann, CVPR 2022, Eq. 4 (smoothness prior), L = 10 and M = 5 in its supplement. Code: web/src/sampling/dct-smoothness.ts (smoothness, dctBasis), the predictor\'s own.');
  const clipNames = data.index.clips.filter((c) => c.frames >= 2 * l).map((c) => c.name);
  const joints = data.index.skeleton.joints;
  const opts = (names: string[]) => names.map((n) => ({ value: n, text: pretty(n) }));
  const a = select({ id: 'dct-from', label: 'History clip (last frames)', options: opts(clipNames), value: state.a, onChange: (v) => { state.a = v; void draw(); } });
  const b = select({ id: 'dct-to', label: 'Joined to clip (first frames)', options: opts(clipNames), value: state.b, onChange: (v) => { state.b = v; void draw(); } });
  const joint = select({ id: 'dct-joint', label: 'Plotted joint', options: opts(joints), value: state.joint, onChange: (v) => { state.joint = v; void draw(); } });
  const axis = select({ id: 'dct-axis', label: 'Coordinate', options: AXES.map((t, i) => ({ value: String(i), text: t })), value: String(state.axis),
    onChange: (v) => { state.axis = Number(v); void draw(); } });
  const m = slider({ id: 'dct-m', label: 'DCT bases M', min: 1, max: 2 * l - 1, step: 1, value: state.m,
    format: (v) => `M = ${v} of ${2 * l}`, onInput: (v) => { state.m = v; void draw(); } });
  f.controls.append(a.row, b.row, joint.row, axis.row, m.row);
  const setLoss = readout(f.readouts, 'dct-loss', 'L_smooth of the joined transition');
  const setCaptured = readout(f.readouts, 'dct-loss-captured', 'L_smooth of captured frames (no join)');
  const setRatio = readout(f.readouts, 'dct-ratio', 'Joined / captured');

  let ticket = 0;
  async function draw(): Promise<void> {
    const mine = ++ticket;
    let ma: Motion;
    let mb: Motion;
    try {
      [ma, mb] = await Promise.all([data.clip(state.a), data.clip(state.b)]);
    } catch (err) {
      f.status.textContent = (err as Error).message;
      return;
    }
    if (mine !== ticket) return;
    f.status.textContent = '';
    const skeleton = data.index.skeleton;
    const s = ma.joints * 3;
    const z = joinWindows(clipWindow(ma, ma.frames - l, l), clipWindow(mb, 0, l), l, skeleton);
    // Captured: the first clip's own last 2L frames, canonical at the same join frame.
    const captured = rootRelative(canonicalise(Float64Array.from(clipWindow(ma, ma.frames - 2 * l, 2 * l)), l - 1, skeleton).canonical,
      ma.joints);
    const loss = smoothness(z.subarray(0, l * s), z.subarray(l * s), l, s, state.m);
    const lossC = smoothness(captured.subarray(0, l * s), captured.subarray(l * s), l, s, state.m);
    setLoss(`${num(loss * 1e6)} mm²`);
    setCaptured(`${num(lossC * 1e6)} mm²`);
    setRatio(lossC > 0 ? `${num(loss / lossC, 2)} ×` : '—');

    const j = joints.indexOf(state.joint);
    const raw = coordinate(z, 2 * l, ma.joints, j, state.axis);
    const approx = dctApproximation(raw, state.m);
    const frames = Array.from({ length: 2 * l }, (_, i) => i - l + 1);
    const c = chart({
      width: fitWidth(f.chart), x: [frames[0], frames[frames.length - 1]], y: extentOf([...raw, ...approx]),
      xLabel: 'frame (0 = last history frame)', yLabel: `${pretty(state.joint)} ${'xyz'[state.axis]} (m)`,
      label: `${pretty(state.joint)} ${'xyz'[state.axis]} coordinate over ${2 * l} frames: ${pretty(state.a)} joined to ${pretty(state.b)}, `
        + `and its approximation by ${state.m} DCT bases. L_smooth ${num(loss * 1e6)} square millimetres.`,
    });
    c.add(vRule(c, 0.5, 'join'));
    for (let i = 0; i < raw.length; i++) {
      c.add(svg('line', { x1: c.x(frames[i]), x2: c.x(frames[i]), y1: c.y(raw[i]), y2: c.y(approx[i]), class: 'chart-residual' }));
    }
    c.add(line(c, frames, raw, { class: 'series series-0' }));
    for (let i = 0; i < raw.length; i++) c.add(svg('circle', { cx: c.x(frames[i]), cy: c.y(raw[i]), r: 3, class: 'dot series-0' }));
    c.add(line(c, frames, approx, { class: 'series series-1 dash-1' }));
    f.chart.replaceChildren(c.root, el('p', { class: 'fig-key' },
      el('span', { class: 'key key-0' }, `captured poses (${pretty(state.a)} → ${pretty(state.b)})`),
      el('span', { class: 'key key-1 key-dashed' }, `first ${state.m} DCT bases`),
      el('span', { class: 'key key-residual' }, 'residual')));
    f.root.dataset.ready = 'true';
  }
  await draw();
}
