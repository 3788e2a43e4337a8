// Figure: keypose extraction on a real clip (Keyposes section 3.1, Fig. 2) with the predictor's
// own extractKeyposes; the clip rebuilt from its keyposes alone by linear interpolation (Eq. 3).
import type { Motion } from '../motion/clip';
import { extractKeyposes } from '../sampling/keyposes';
import { el } from '../ui/dom';
import type { ExplainerData } from './data';
import { figureShell, num, pretty, readout, select, slider } from './figure';
import { chart, fitWidth, extentOf, line, svg } from './plot';
import { mpjpe, rebuildFromKeyposes } from './keypose-fit';
import { coordinate } from './transition';

const AXES = ['x (left–right)', 'y (up)', 'z (forward)'];

export async function mountKeyposeFigure(host: HTMLElement, data: ExplainerData): Promise<void> {
  const kp = data.model('keyposes');
  const served = (kp?.params.keyposes as { threshold?: number } | undefined)?.threshold;
  // A held-out dance (a person no model saw), else any dance, else the first clip.
  const dances = data.index.clips.filter((c) => c.action.startsWith('dance'));
  const first = dances.find((c) => c.role === 'test') ?? dances[0] ?? data.index.clips[0];
  const state = { clip: first?.name ?? '', joint: 'right_wrist', axis: 1, threshold: served ?? 0.3 };
  const f = figureShell(host, 'fig-keyposes', '3. Keyposes: the poses a straight line cannot skip',
    ['Keyposes starts from the first and last frame and adds, in each segment, the frame that linear interpolation between its ends ',
      'misses most, until the segment\'s mean error (the length of the whole-pose difference) is below a threshold. A high threshold keeps a few poses; ',
      'a low one keeps many. Move the threshold and watch the keyposes (numbered dots) and the rebuilt motion (dashed) on one joint\'s trajectory.'],
    `Keyposes: Kiciroglu, Wang, Salzmann, Fua, 3DV 2022, section 3.1 and Fig. 2; interpolation Eq. 3.${served !== undefined ? ` The served model extracts at ${served} m.` : ''} `
    + 'Code: web/src/sampling/keyposes.ts (extractKeyposes) and keypose-interpolation.ts, the predictor\'s own.');
  const clips = data.index.clips.map((c) => ({ value: c.name, text: `${pretty(c.name)} (${c.frames} frames)` }));
  const joints = data.index.skeleton.joints.map((n) => ({ value: n, text: pretty(n) }));
  const clip = select({ id: 'kp-clip', label: 'Clip', options: clips, value: state.clip, onChange: (v) => { state.clip = v; void draw(); } });
  const joint = select({ id: 'kp-joint', label: 'Plotted joint', options: joints, value: state.joint, onChange: (v) => { state.joint = v; void draw(); } });
  const axis = select({ id: 'kp-axis', label: 'Coordinate', options: AXES.map((t, i) => ({ value: String(i), text: t })), value: String(state.axis),
    onChange: (v) => { state.axis = Number(v); void draw(); } });
  const thr = slider({ id: 'kp-threshold', label: 'Threshold', min: 0.05, max: 1.5, step: 0.05, value: state.threshold,
    format: (v) => `${v.toFixed(2)} m`, onInput: (v) => { state.threshold = v; void draw(); } });
  f.controls.append(clip.row, joint.row, axis.row, thr.row);
  const setCount = readout(f.readouts, 'kp-count', 'Keyposes');
  const setGap = readout(f.readouts, 'kp-gap', 'Mean frames between keyposes');
  const setError = readout(f.readouts, 'kp-error', 'Rebuilt motion, mean per-joint error');

  let ticket = 0;
  async function draw(): Promise<void> {
    const mine = ++ticket;
    let m: Motion;
    try {
      m = await data.clip(state.clip);
    } catch (err) {
      f.status.textContent = (err as Error).message;
      return;
    }
    if (mine !== ticket) return;
    f.status.textContent = '';
    const keys = extractKeyposes(m.positions, m.frames, m.joints, state.threshold);
    const rebuilt = rebuildFromKeyposes(m.positions, m.joints, keys);
    const err = mpjpe(rebuilt, m.positions, m.joints);
    setCount(`${keys.length} of ${m.frames} frames`);
    setGap(keys.length > 1 ? num((keys[keys.length - 1] - keys[0]) / (keys.length - 1), 3) : '—');
    setError(`${num(err * 1000)} mm`);

    const j = data.index.skeleton.joints.indexOf(state.joint);
    const raw = coordinate(m.positions, m.frames, m.joints, j, state.axis);
    const fit = coordinate(rebuilt, m.frames, m.joints, j, state.axis);
    const frames = Array.from({ length: m.frames }, (_, i) => i);
    const c = chart({
      width: fitWidth(f.chart), x: [0, m.frames - 1], y: extentOf([...raw, ...fit]), xLabel: 'frame', yLabel: `${pretty(state.joint)} ${'xyz'[state.axis]} (m)`,
      label: `${pretty(state.clip)}: ${pretty(state.joint)} ${'xyz'[state.axis]} over ${m.frames} frames with ${keys.length} keyposes at threshold `
        + `${state.threshold.toFixed(2)} m at frames ${keys.join(', ')}; rebuilt motion error ${num(err * 1000)} mm.`,
    });
    c.add(line(c, frames, raw, { class: 'series series-0' }));
    c.add(line(c, frames, fit, { class: 'series series-1 dash-1' }));
    keys.forEach((k, n) => {
      c.add(svg('circle', { cx: c.x(k), cy: c.y(raw[k]), r: 5, class: 'dot series-1 keypose-dot' }));
      if (keys.length <= 40) c.add(svg('text', { x: c.x(k), y: c.y(raw[k]) - 8, 'text-anchor': 'middle', class: 'chart-note' }, String(n + 1)));
    });
    f.chart.replaceChildren(c.root, el('p', { class: 'fig-key' },
      el('span', { class: 'key key-0' }, 'captured'),
      el('span', { class: 'key key-1 key-dashed' }, 'rebuilt from keyposes'),
      el('span', { class: 'key key-dot' }, 'keyposes, numbered in order')));
    f.root.dataset.ready = 'true';
  }
  await draw();
}
