// Figure: a standard CVAE prior against LCP-VAE's conditional prior (LCP-VAE section 3, Fig. 2).
// For two real histories the condition graph gives mu_c and sigma_c; the conditional samples are
// drawn by the predictor's own sampleLatents (z = mu_c + s * sigma_c * eps), the standard ones are
// s * eps from the same PRNG (what the predictor draws for Table 4's row 2). Both panels share one
// 2-D projection: the principal components of the s = 1 samples of both priors and histories.
import type { ModelEntry } from '../contract/types';
import { window as clipWindow } from '../motion/clip';
import { toCanonical } from '../predictor/canonical';
import { sampleLatents, type LcpParams } from '../predictor/lcp-vae';
import { Prng } from '../rng/prng';
import { defaultStart } from '../ui/history-picker';
import { el } from '../ui/dom';
import type { ExplainerData } from './data';
import { figureShell, num, pretty, readout, select, slider } from './figure';
import { chart, extentOf, svg, type Chart } from './plot';
import { pca2, separation, type Projection } from './pca';

const K = 150;
const SEED = 7;

interface Latents { mu: Float32Array[]; sigma: Float32Array[] }

export async function mountPriorFigure(host: HTMLElement, data: ExplainerData): Promise<void> {
  const entry = data.model('lcp_vae');
  const f = figureShell(host, 'fig-prior', '5. Where the randomness comes from: a prior that knows the history',
    ['A standard conditional VAE draws its latent z from N(0, I) whatever the history; the decoder sees the history separately and may learn to ',
      'ignore z, which costs diversity. LCP-VAE draws z from a conditional prior N(μ_c, σ_c) computed from the history itself, so the samples ',
      'of two different histories fall in different places. Each dot is one latent sample, drawn in the first two principal components of all samples. ',
      'Move the scale s (the predictor\'s sigma scale): s = 0 keeps only the most likely future, μ_c.'],
    'LCP-VAE: Aliakbarian, Saleh, Petersson, Gould, Salzmann, ICCV 2021, section 3 (Eq. 4, the conditional prior at inference) and Fig. 2. '
    + 'Code: web/src/predictor/lcp-vae.ts (sampleLatents) and web/src/rng/prng.ts, the predictor\'s own.');
  if (!entry) {
    f.status.textContent = 'The LCP-VAE model is not available on this site (models/manifest.json serves no lcp_vae model).';
    return;
  }
  const params = entry.params as unknown as LcpParams;
  const n = params.history_frames;
  const tests = data.index.clips.filter((c) => c.frames >= n && (c.role === 'test' || c.test.some(([a, b]) => b - a >= n)));
  const opts = tests.map((c) => ({ value: c.name, text: pretty(c.name) }));
  const pick = (name: string, fallback: number) => (tests.some((c) => c.name === name) ? name : tests[fallback]?.name ?? '');
  const histA = select({ id: 'prior-a', label: 'History A', options: opts, value: pick(data.defaultClip(), 0), onChange: () => { void load(); } });
  const histB = select({ id: 'prior-b', label: 'History B', options: opts, value: pick(tests.find((c) => c.action !== tests.find((t) => t.name === data.defaultClip())?.action)?.name ?? '', 1), onChange: () => { void load(); } });
  let scale = 1;
  // the predictor's own range (the manifest's control); the figure opens at the paper's s = 1
  const control = entry.controls.find((c) => c.id === 'sigma_scale');
  const s = slider({ id: 'prior-s', label: 'Sigma scale s', min: 0, max: control?.max ?? 2, step: 0.05, value: 1, format: (v) => `s = ${v.toFixed(2)}`,
    onInput: (v) => { scale = v; draw(); } });
  f.controls.append(histA.row, histB.row, s.row);
  const setStandard = readout(f.readouts, 'prior-sep-standard', 'Standard prior: distance between A and B, in spreads');
  const setConditional = readout(f.readouts, 'prior-sep-conditional', 'Conditional prior: distance between A and B, in spreads');
  const setSpread = readout(f.readouts, 'prior-spread', 'Conditional prior: RMS spread of z (A, B)');

  let latents: Latents | null = null;
  let projection: Projection | null = null;
  let limit = 1; // the axes' half-width, fixed at s = 1 so the slider visibly shrinks and grows the clouds
  const d = params.latent_size;

  /** [standard A, standard B, conditional A, conditional B], each [K, d], from one PRNG in that order. */
  function samples(sc: number): Float32Array[] {
    const prng = new Prng(SEED);
    const std = [0, 1].map(() => Float32Array.from(prng.normals(K * d), (e) => sc * e));
    const cond = [0, 1].map((h) => sampleLatents(prng, { mu_c: { data: latents!.mu[h], dims: [1, d] }, sigma_c: { data: latents!.sigma[h], dims: [1, d] } },
      K, sc, { ...params, prior: 'conditional' }).z);
    return [...std, ...cond];
  }

  function panel(title: string, pts: Float64Array[], extent: [number, number], ids: string[]): Chart {
    const c = chart({ width: 300, height: 300, x: extent, y: extent, xLabel: 'PC 1', yLabel: 'PC 2',
      label: `${title}: ${K} latent samples per history, history A as circles, history B as triangles.` });
    pts.forEach((p, h) => {
      for (let i = 0; i < K; i++) {
        const x = c.x(p[i * 2]);
        const y = c.y(p[i * 2 + 1]);
        c.add(h === 0 ? svg('circle', { cx: x, cy: y, r: 2.6, class: 'pt series-0' })
          : svg('path', { d: `M${x.toFixed(1)},${(y - 3.2).toFixed(1)}l3,5.4h-6z`, class: 'pt series-4' }));
      }
    });
    c.root.dataset.panel = ids.join(' ');
    const t = svg('text', { x: c.box.l + 4, y: c.box.t + 13, class: 'chart-note panel-title' }, title);
    c.add(t);
    return c;
  }

  function draw(): void {
    if (!latents || !projection) return;
    const z = samples(scale);
    const sepStd = separation(z[0], z[1], K, d);
    const sepCond = separation(z[2], z[3], K, d);
    setStandard(num(sepStd, 2));
    setConditional(num(sepCond, 2));
    const rms = (x: Float32Array) => {
      const mean = new Float64Array(d);
      for (let i = 0; i < K; i++) for (let j = 0; j < d; j++) mean[j] += x[i * d + j] / K;
      let t = 0;
      for (let i = 0; i < K; i++) for (let j = 0; j < d; j++) t += (x[i * d + j] - mean[j]) ** 2 / K;
      return Math.sqrt(t);
    };
    setSpread(`${num(rms(z[2]), 3)}, ${num(rms(z[3]), 3)}`);
    const proj = z.map((x) => projection!.project(x, K));
    const ext: [number, number] = [-limit, limit];
    const left = panel('Standard prior N(0, I)', [proj[0], proj[1]], ext, ['standard']);
    const right = panel('LCP-VAE conditional prior', [proj[2], proj[3]], ext, ['conditional']);
    f.chart.replaceChildren(el('div', { class: 'fig-panels' }, left.root, right.root), el('p', { class: 'fig-key' },
      el('span', { class: 'key key-dot key-0' }, `A: ${pretty(histA.input.value)} (circles)`),
      el('span', { class: 'key key-tri key-4' }, `B: ${pretty(histB.input.value)} (triangles)`),
      el('span', {}, `PC 1 and 2 hold ${num(projection.explained[0] * 100, 2)} % and ${num(projection.explained[1] * 100, 2)} % of the variance at s = 1.`)));
    f.root.dataset.ready = 'true';
  }

  async function load(): Promise<void> {
    f.status.textContent = `Running ${entry!.label}'s condition graph on both histories…`;
    try {
      latents = await condition(data, entry!, [histA.input.value, histB.input.value]);
      const all = samples(1);
      const joined = new Float32Array(4 * K * d);
      all.forEach((x, i) => joined.set(x, i * K * d));
      projection = pca2(joined, 4 * K, d);
      const e = extentOf(projection.project(joined, 4 * K), 0.1);
      limit = Math.max(Math.abs(e[0]), Math.abs(e[1]));
      f.status.textContent = `${K} samples of z (${d} dimensions) per history and prior, seed ${SEED}.`;
      draw();
    } catch (err) {
      f.status.textContent = `The LCP-VAE model could not run here: ${(err as Error).message}`;
    }
  }
  await load();
}

async function condition(data: ExplainerData, entry: ModelEntry, clips: string[]): Promise<Latents> {
  const params = entry.params as unknown as LcpParams;
  const n = params.history_frames;
  const skeleton = data.index.skeleton;
  const j = skeleton.joints.length;
  const batch = new Float32Array(clips.length * n * j * 3);
  for (const [i, name] of clips.entries()) {
    const m = await data.clip(name);
    const start = defaultStart(m, n);
    batch.set(toCanonical(clipWindow(m, start, n), n, skeleton).canonical, i * n * j * 3);
  }
  const out = await data.graphs().run(entry.id, 'condition', { history: { data: batch, dims: [clips.length, n, j, 3] } });
  const d = params.latent_size;
  return {
    mu: clips.map((_, i) => out.mu_c.data.slice(i * d, (i + 1) * d)),
    sigma: clips.map((_, i) => out.sigma_c.data.slice(i * d, (i + 1) * d)),
  };
}
