// Figure: sampling at a temperature (Keyposes section 3.3, Table 3). After the history's keyposes
// the KP-GRU gives logits over the keypose clusters; labels are drawn from softmax(logits / T).
// The bars are that distribution for a real test history (the step graph in the explainer's
// worker, fed by KeyposesPredictor.observe); the sequences are K whole predictions by
// KeyposesPredictor itself at the same T, its graphs in the same worker.
import { window as clipWindow } from '../motion/clip';
import { KeyposesPredictor } from '../predictor/keyposes';
import type { History, Tensor } from '../predictor/types';
import { softmax } from '../sampling/temperature';
import { defaultStart } from '../ui/history-picker';
import { el } from '../ui/dom';
import type { ExplainerData } from './data';
import { figureShell, num, pretty, readout, select, slider } from './figure';
import { chart, fitWidth, svg } from './plot';
import { entropyBits, sequenceStats, topIndices } from './label-stats';

const K = 5;
const SEED = 3;

interface KpParams {
  history_frames: number;
  keyposes: { clusters: number; layers: number; hidden: number };
  duration_classes: { bounds: number[] };
}

export async function mountTemperatureFigure(host: HTMLElement, data: ExplainerData): Promise<void> {
  const entry = data.model('keyposes');
  const spec = entry?.controls.find((c) => c.id === 'temperature');
  const f = figureShell(host, 'fig-temperature', '4. Temperature: from the most likely keypose to many',
    ['Keyposes treats the next keypose as a class: one of the cluster centres of training keyposes. Its network gives a score (logit) per ',
      'class; the label is drawn from softmax(logits / T). A low temperature T puts nearly all probability on the top class, so every sample ',
      'follows the same keyposes; a high one spreads it, and the sampled sequences differ. Move T and watch the distribution and the sequences.'],
    'Keyposes: Kiciroglu, Wang, Salzmann, Fua, 3DV 2022, section 3.3 (sampling with temperature 0.3) and Table 3 (diversity against temperature). '
    + 'Code: web/src/sampling/temperature.ts (softmax, sampleIndex) and web/src/predictor/keyposes.ts, the predictor\'s own.');
  if (!entry) {
    f.status.textContent = 'The Keyposes model is not available on this site (models/manifest.json serves no keyposes model).';
    return;
  }
  const p = entry.params as unknown as KpParams;
  const n = p.history_frames;
  const tests = data.index.clips.filter((c) => c.test.some(([a, b]) => b - a >= n) || (c.role === 'test' && c.frames >= n));
  const clip = select({ id: 'temp-clip', label: 'History (a test clip)', options: tests.map((c) => ({ value: c.name, text: pretty(c.name) })),
    value: tests.some((c) => c.name === data.defaultClip()) ? data.defaultClip() : tests[0]?.name ?? '', onChange: () => { void observe(); } });
  let temperature = Number(spec?.default ?? 0.3);
  const t = slider({ id: 'temp-t', label: 'Temperature T', min: spec?.min ?? 0.05, max: spec?.max ?? 1.5, step: spec?.step ?? 0.05, value: temperature,
    format: (v) => `T = ${v.toFixed(2)}`, onInput: (v) => { temperature = v; drawBars(); schedule(); } });
  f.controls.append(clip.row, t.row);
  const setTop = readout(f.readouts, 'temp-top', 'Probability of the top label');
  const setPerplexity = readout(f.readouts, 'temp-perplexity', 'Effective number of labels (2^entropy)');
  const setDistinct = readout(f.readouts, 'temp-distinct', `Distinct labels in ${K} sampled sequences`);
  const barBox = el('div', { class: 'fig-bars' });
  const sequences = el('div', { class: 'fig-sequences', 'aria-live': 'polite' });
  f.chart.append(barBox, el('h3', { class: 'fig-subtitle' }, `${K} sampled label sequences (5 s each, seed ${SEED})`), sequences);

  let predictor: KeyposesPredictor;
  try {
    predictor = new KeyposesPredictor({ entry, skeleton: data.index.skeleton, actions: data.manifest!.actions, fps: data.index.fps,
      runner: data.graphs().runner(entry.id), loadFile: data.loadFile });
  } catch (err) {
    f.status.textContent = `The Keyposes model cannot run here: ${(err as Error).message}`;
    return;
  }
  let logits: Float32Array | null = null;
  let history: History | null = null;

  function drawBars(): void {
    if (!logits) return;
    const prob = softmax(logits, temperature);
    const bars = f.chart.clientWidth < 520 ? 12 : 24; // each bar keeps room for its label
    const order = topIndices(logits, bars);
    setTop(`${num(prob[order[0]] * 100)} % (label ${order[0]})`);
    setPerplexity(num(2 ** entropyBits(prob)));
    const c = chart({ width: fitWidth(f.chart), xTicks: false, x: [0, bars], y: [0, 1], height: 220, xLabel: `the ${bars} labels with the highest logits, best first (of ${logits.length})`, yLabel: 'probability',
      label: `Label distribution at temperature ${temperature.toFixed(2)}: top label ${order[0]} with probability ${num(prob[order[0]])}; `
        + `effective number of labels ${num(2 ** entropyBits(prob))}.` });
    const w = (c.box.r - c.box.l) / bars;
    order.forEach((label, i) => {
      const x = c.box.l + i * w;
      c.add(svg('rect', { x: x + 1, y: c.y(prob[label]), width: w - 2, height: c.box.b - c.y(prob[label]), class: 'bar' }));
      c.add(svg('text', { x: x + w / 2, y: c.box.b + 12, 'text-anchor': 'middle', class: 'chart-tick-label bar-label' }, String(label)));
    });
    barBox.replaceChildren(c.root);
  }

  let timer = 0;
  let ticket = 0;
  function schedule(): void {
    clearTimeout(timer);
    timer = window.setTimeout(() => { void sample(); }, 200);
  }

  async function sample(): Promise<void> {
    if (!history) return;
    const mine = ++ticket;
    sequences.setAttribute('aria-busy', 'true');
    try {
      const pred = await predictor.predict(history, { k: K, seed: SEED, horizonFrames: 150, controls: { temperature, refine: false } });
      if (mine !== ticket) return;
      const labels = pred.samples.map((s) => s.labels ?? []);
      const st = sequenceStats(labels);
      setDistinct(`${st.distinct} (${st.constant} of ${K} repeat one label throughout)`);
      sequences.replaceChildren(...labels.map((seq, i) => el('p', { class: 'sequence' },
        el('span', { class: `sequence-name key-${i % 8}` }, `#${i + 1}`),
        ...seq.map((l) => el('span', { class: 'label-chip', style: `--hue:${(l * 137.508) % 360}` }, String(l))))));
      f.root.dataset.ready = 'true';
    } catch (err) {
      if (mine === ticket) f.status.textContent = `Sampling failed: ${(err as Error).message}`;
    } finally {
      if (mine === ticket) sequences.removeAttribute('aria-busy');
    }
  }

  async function observe(): Promise<void> {
    f.status.textContent = 'Loading the Keyposes model…';
    logits = null;
    try {
      const m = await data.clip(clip.input.value);
      // past a standing start, as the stage opens a clip: Keyposes needs 3 keyposes
      const start = defaultStart(m, n);
      history = { positions: clipWindow(m, start, n), frames: n, joints: m.joints };
      const { centres } = await predictor.loadCentres();
      const obs = predictor.observe(history, centres);
      // Feed the observed keyposes one step each, as the predictor does before it samples.
      const { layers, hidden, clusters } = p.keyposes;
      const nd = p.duration_classes.bounds.length;
      let h: Float32Array = new Float32Array(layers * hidden);
      let out: Record<string, Tensor> = {};
      const runner = data.graphs().runner(entry!.id);
      for (let i = 0; i < obs.frames.length; i++) {
        out = await runner.run('step', {
          label_dist: { data: obs.labelDist.slice(i * clusters, (i + 1) * clusters), dims: [1, clusters] },
          duration: { data: obs.duration.slice(i * nd, (i + 1) * nd), dims: [1, nd] },
          hidden: { data: h, dims: [1, layers, hidden] },
        });
        h = out.next_hidden.data;
      }
      logits = out.label_logits.data;
      f.status.textContent = `History: frames ${start}–${start + n - 1} of ${pretty(m.name)}, ${obs.frames.length} observed keyposes (labels ${obs.labels.join(', ')}).`;
      drawBars();
      await sample();
    } catch (err) {
      f.status.textContent = `The Keyposes model could not run on this history: ${(err as Error).message}`;
    }
  }
  await observe();
}
