// Figure: WAT's variance stopping (Eq. 8). Each sample's v_i (mean distance of the Q poses from
// frame i on to their mean) falls as the predicted motion settles; a sample stops at the first
// i >= T_min with v_i < delta. With WAT served, the curves are K real predictions over all T_max
// frames: the prior and decoder graphs run in the explainer's worker and the sampling around them
// is the predictor's own (toCanonical, sampleGaussian, varianceCurve, firstStop), so the delta
// slider can move a stop later as well as earlier (a Prediction keeps only frames up to its stop).
// Without WAT, the same rule runs on the committed test vectors' pose sequences, and the figure says so.
import type { ModelEntry } from '../contract/types';
import { window as clipWindow } from '../motion/clip';
import { rootRelative, toCanonical } from '../predictor/canonical';
import { priorTemperature, type WatParams } from '../predictor/wat';
import { streams } from '../rng/prng';
import { sampleGaussian } from '../sampling/gaussian';
import { firstStop, varianceCurve } from '../sampling/variance-stop';
import { motionTitle } from '../ui/clip-name';
import { el } from '../ui/dom';
import type { ExplainerData } from './data';
import { figureShell, num, pretty, readout, select, slider } from './figure';
import { chart, fitWidth, hRule, line, svg, vRule } from './plot';

interface Curves {
  names: string[];
  curves: Float64Array[];
  q: number;
  tMin: number;
  tMax: number;
  /** Frames each curve's sample has (T_max for predictions; the sequence's length for test vectors). */
  maxFrames: number[];
  delta: number;
  source: string;
  /** The history's clip, as a newcomer reads it (ui/clip-name.ts), with its name; model curves only. */
  clip?: string;
}

const K = 6;

export async function mountVarianceFigure(host: HTMLElement, data: ExplainerData): Promise<void> {
  const wat = data.model('wat');
  const f = figureShell(host, 'fig-variance', '2. Where a future stops: the variance of the last Q frames',
    ['WAT predicts futures of different lengths. For each sample it computes v_i, the mean distance of Q consecutive predicted poses ',
      'from their mean, and stops at the first frame i (after T_min) where v_i falls below a threshold δ. Move δ: a higher threshold ',
      'stops samples earlier, a lower one lets them run on, and a sample whose motion never settles keeps the maximum length T_max.'],
    'WAT: Mao, Liu, Salzmann, CVPR 2022, Eq. 8 (variance-based stopping), Q = 5 in its supplement. Code: web/src/sampling/variance-stop.ts '
    + '(varianceCurve, firstStop), web/src/sampling/gaussian.ts and web/src/predictor/canonical.ts, the predictor\'s own.');
  const setStops = readout(f.readouts, 'var-stops', 'Stop frame per curve');
  const setMean = readout(f.readouts, 'var-mean', 'Mean length');
  const setStopped = readout(f.readouts, 'var-stopped', 'Curves that stop');
  let current: Curves | null = null;
  let delta = 0;
  const deltaSlider = slider({ id: 'var-delta', label: 'Threshold δ (log scale)', min: -3, max: 0, step: 0.02, value: -1.5,
    format: (v) => `δ = ${num(10 ** v)} m`, onInput: (v) => { delta = 10 ** v; draw(); } });

  function draw(): void {
    const c0 = current;
    if (!c0) return;
    const stops = c0.curves.map((cv, i) => firstStop(cv, delta, c0.tMin, c0.maxFrames[i]));
    setStops(stops.map((s, i) => `${i + 1}: ${s.stopped ? s.length : `${s.length} (never)`}`).join(', '));
    setMean(`${num(stops.reduce((a, s) => a + s.length, 0) / stops.length / data.index.fps)} s`);
    setStopped(`${stops.filter((s) => s.stopped).length} of ${stops.length}`);
    // A pose held exactly has v_i ~ 1e-16; the axis stops half a decade below the slider's lowest δ
    // and lower values sit on its bottom edge.
    const floor = 10 ** (Number(deltaSlider.input.min) - 0.5);
    const all = c0.curves.flatMap((cv) => Array.from(cv)).filter((v) => v > 0);
    const lo = Math.max(floor, Math.min(delta, ...all));
    const hi = Math.max(delta, ...all);
    const c = chart({
      width: fitWidth(f.chart), x: [1, c0.tMax], y: [lo, hi], logY: true, xLabel: 'frame i (start of the Q-frame window)', yLabel: 'v_i (m, log scale)',
      label: `Variance curves of ${c0.curves.length} ${c0.source}; threshold delta ${num(delta)} m; stop frames ${stops.map((s) => s.length).join(', ')}.`,
    });
    c.add(vRule(c, c0.tMin, 'T_min'));
    c.add(hRule(c, delta, 'δ'));
    c0.curves.forEach((cv, i) => {
      const xs = Array.from(cv, (_, n) => n + 1);
      c.add(line(c, xs, Array.from(cv, (v) => Math.max(v, lo)), { class: `series series-${i % 8} dash-${i % 4}` }));
      const s = stops[i];
      if (s.stopped) {
        const v = Math.max(cv[s.length - 1], lo);
        c.add(svg('circle', { cx: c.x(s.length), cy: c.y(v), r: 6, class: `stop-mark series-${i % 8}` }));
        c.add(svg('text', { x: c.x(s.length), y: c.y(v) + 3.5, 'text-anchor': 'middle', class: 'stop-label' }, String(i + 1)));
      }
    });
    f.chart.replaceChildren(c.root, el('ol', { class: 'fig-key fig-key-list' },
      ...c0.names.map((n, i) => el('li', { class: `key key-${i % 8} key-dash-${i % 4}` }, n))));
    f.root.dataset.ready = 'true';
  }

  const start = (c: Curves) => {
    current = c;
    delta = c.delta;
    const lg = Math.log10(c.delta);
    // The range is centred on the served δ, so the slider starts exactly on it (a whole number of steps from min).
    deltaSlider.input.min = String(lg - 1.5);
    deltaSlider.input.max = String(lg + 1.5);
    deltaSlider.input.value = String(lg);
    deltaSlider.input.dispatchEvent(new Event('input'));
  };

  const cite = f.root.querySelector('.fig-cite')!;
  const source = (text: string, kind: string) => { cite.append(` Curves: ${text}.`); f.root.dataset.source = kind; };
  if (wat) {
    source(`samples of the served WAT model '${wat.id}' (models/manifest.json)`, 'model');
    const p = wat.params as unknown as WatParams;
    const action = select({ id: 'var-action', label: 'Action', options: p.actions.map((a) => ({ value: a, text: pretty(a) })), value: p.actions.includes('walk') ? 'walk' : p.actions[0],
      onChange: () => { void run(); } });
    let seed = 1;
    const again = el('button', { type: 'button', class: 'fig-button', id: 'var-again' }, 'New samples');
    again.addEventListener('click', () => { seed += 1; void run(); });
    f.controls.append(action.row, deltaSlider.row, again);
    const run = async () => {
      f.status.textContent = `Predicting ${K} futures with ${wat.label}…`;
      try {
        start(await watCurves(data, wat, action.input.value, seed));
        delta = 10 ** deltaSlider.value();
        draw();
        // names the clip the curves really come from (watCurves): the site's default clip, from frame 0
        f.status.textContent = `${K} futures of ${wat.label} from the first ${p.history_frames} frames of ${current?.clip ?? 'the default clip'}, action ${pretty(action.input.value)}, seed ${seed}; the served δ is ${num(p.stop.delta)} m.`;
      } catch (err) {
        f.status.textContent = `The WAT model could not run here: ${(err as Error).message}`;
      }
    };
    await run();
  } else {
    f.controls.append(deltaSlider.row);
    source('the pose sequences of contract/vectors/variance_stop.json, as no WAT model is served yet', 'vectors');
    f.status.textContent = 'No WAT model is served on this site yet (models/manifest.json lists none), so these curves come from the committed '
      + 'test vectors, contract/vectors/variance_stop.json: short pose sequences on which both predictors\' stop rules are tested, run here '
      + 'through the same varianceCurve and firstStop. With a WAT model served, the curves are its own samples.';
    start(await vectorCurves());
    draw();
  }
}

async function watCurves(data: ExplainerData, wat: ModelEntry, action: string, seed: number): Promise<Curves> {
  const p = wat.params as unknown as WatParams;
  const skeleton = data.index.skeleton;
  const j = skeleton.joints.length;
  const n = p.history_frames;
  const stride = j * 3;
  const clip = await data.clip(data.defaultClip());
  const entry = data.index.clips.find((c) => c.name === clip.name);
  const { canonical } = toCanonical(clipWindow(clip, 0, n), n, skeleton);
  const history = new Float32Array(K * n * stride);
  const onehot = new Float32Array(K * p.actions.length);
  for (let i = 0; i < K; i++) {
    history.set(canonical, i * n * stride);
    onehot[i * p.actions.length + p.actions.indexOf(action)] = 1;
  }
  const runner = data.graphs().runner(wat.id);
  const feeds = { history: { data: history, dims: [K, n, j, 3] }, action: { data: onehot, dims: [K, p.actions.length] } };
  const prior = await runner.run('prior', feeds);
  const z = sampleGaussian(streams(seed, K), prior.prior_mean.data, prior.prior_logvar.data, K, p.latent_size, priorTemperature(wat));
  const out = await runner.run('decoder', { ...feeds, z: { data: z, dims: [K, p.latent_size] } });
  const len = p.future_frames * stride;
  // Eq. 8 on root-relative poses, as the predictor computes it
  const curves = Array.from({ length: K }, (_, i) => varianceCurve(rootRelative(out.future.data.subarray(i * len, (i + 1) * len), j), p.future_frames, stride, p.stop.q));
  return {
    names: curves.map((_, i) => `sample ${i + 1}`), curves, q: p.stop.q, tMin: p.stop.min_frames, tMax: p.future_frames,
    maxFrames: curves.map(() => p.future_frames),
    delta: p.stop.delta, source: `WAT samples for ${pretty(action)}`,
    clip: `${motionTitle(clip, entry)} (${clip.name})`,
  };
}

interface StopCase { name: string; q: number; delta: number; min_frames: number; frames: number[][][] }

/**
 * The shared test vectors of Eq. 8 (contract/vectors/variance_stop.json), one curve per distinct
 * pose sequence. The figure uses one Q and T_min for all (Q = 5 and T_min = 10, the served WAT
 * config's), so a case written for another Q or T_min shows its motion, not its expected stop.
 */
async function vectorCurves(): Promise<Curves> {
  const doc = (await import('../../../contract/vectors/variance_stop.json')).default as { cases: StopCase[] };
  const q = 5;
  const tMin = 10;
  const seen = new Set<string>();
  const cases = doc.cases.filter((c) => {
    const key = JSON.stringify(c.frames);
    if (seen.has(key)) return false;
    seen.add(key);
    return true;
  });
  if (!cases.length) throw new Error('contract/vectors/variance_stop.json has no cases');
  const curves = cases.map((c) => {
    const flat = Float64Array.from(c.frames.flat(2));
    return varianceCurve(flat, c.frames.length, flat.length / c.frames.length, q);
  });
  return {
    names: cases.map((c) => `${c.name.split(/[,(]/)[0].trim()} (test vector)`), curves, q, tMin,
    tMax: Math.max(...cases.map((c) => c.frames.length)), maxFrames: cases.map((c) => c.frames.length),
    delta: doc.cases[0].delta, source: 'test-vector pose sequences',
  };
}
