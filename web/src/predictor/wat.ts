// Predictor for WAT, twin of export/sample/wat.py: K samples per action, each cut at its own stop
// frame, the actions one after another. For every action, with all K samples in one call:
//   1. each sample's last N frames (up to its previous stop frame) -> canonical history;
//   2. prior graph -> mu, log-variance; z = mu + (temperature * exp(logvar / 2)) * eps (float64, rounded to float32);
//   3. decoder graph -> T_max frames; Eq. 8 on the canonical frames gives the sample's stop frame
//      (T_max and stopped = false if no window falls below delta);
//   4. Eq. 4 over the last L history frames and the first L predicted ones, flagged above the threshold.
// Draw order: sample i draws from its own stream, streams(seed, K)[i] (rng/prng.ts); per action, D
// normals, two uniforms each. Nothing else draws, and nothing couples the samples (each stop, each
// smoothness is the sample's own), so the first k samples of K > k are those of K = k.
import { streams } from '../rng/prng';
import { smoothness } from '../sampling/dct-smoothness';
import { sampleGaussian } from '../sampling/gaussian';
import { firstStop, varianceCurve } from '../sampling/variance-stop';
import { fromCanonical, rootRelative, toCanonical, type Placement } from './canonical';
import type { ModelEntry } from '../contract/types';
import { checkHistory, checkRequest, controlValue } from './request';
import {
  PredictError, Superseded, type History, type Prediction, type PredictRequest, type Predictor,
  type PredictorContext, type SampleInfo, type Segment,
} from './types';

export interface WatParams {
  history_frames: number;
  future_frames: number;
  latent_size: number;
  actions: string[];
  stop: { q: number; delta: number; min_frames: number };
  smoothness: { l: number; m: number; flag_threshold: number };
}

function concat(a: Float32Array, b: Float32Array): Float32Array {
  const out = new Float32Array(a.length + b.length);
  out.set(a);
  out.set(b, a.length);
  return out;
}

/** The prior's temperature t, z = mu_p + t * sigma_p * eps (a labelled variant; t = 1 is the paper's draw,
 *  export/methods/wat.py says why more is served). */
export function priorTemperature(entry: ModelEntry, controls?: PredictRequest['controls']): number {
  return Number(controlValue({ controls }, entry, 'temperature', 1));
}

export class WatPredictor implements Predictor {
  constructor(private readonly ctx: PredictorContext) {}

  get entry() {
    return this.ctx.entry;
  }

  async predict(history: History, req: PredictRequest, isCancelled: () => boolean = () => false): Promise<Prediction> {
    const { entry, skeleton, runner } = this.ctx;
    const p = entry.params as unknown as WatParams;
    const j = skeleton.joints.length;
    const n = p.history_frames;
    const tMax = p.future_frames;
    const d = p.latent_size;
    const { q, delta, min_frames: tMin } = p.stop;
    const { l, m, flag_threshold: flag } = p.smoothness;
    checkHistory(history, n, j);
    checkRequest(req, entry, this.ctx.actions, this.ctx.fps);
    const actions = req.actions ?? [];
    const maxLength = entry.controls.find((c) => c.id === 'actions')?.max_length ?? Infinity;
    if (actions.length > maxLength) {
      throw new PredictError(`the action sequence has ${actions.length} actions; at most ${maxLength} are allowed`);
    }
    const k = req.k;
    const temperature = priorTemperature(entry, req.controls);
    const stride = j * 3;
    const histLen = n * stride;
    const draws = streams(req.seed, k);
    const first = history.positions.slice((history.frames - n) * stride);
    const seqs: Float32Array[] = Array.from({ length: k }, () => first);   // world frame, grows per segment
    const parts: Float32Array[][] = Array.from({ length: k }, () => []);
    const totals = new Array<number>(k).fill(0);
    const series: number[][] = Array.from({ length: k }, () => []);
    const segments: Segment[][] = Array.from({ length: k }, () => []);
    for (const action of actions) {
      if (isCancelled()) throw new Superseded();
      const canon = new Float32Array(k * histLen);
      const placements: Placement[] = [];
      seqs.forEach((s, i) => {
        const { canonical, placement } = toCanonical(s.slice(s.length - histLen), n, skeleton);
        canon.set(canonical, i * histLen);
        placements.push(placement);
      });
      const onehot = new Float32Array(k * p.actions.length);
      const a = p.actions.indexOf(action);
      for (let i = 0; i < k; i++) onehot[i * p.actions.length + a] = 1;
      const historyT = { data: canon, dims: [k, n, j, 3] };
      const actionT = { data: onehot, dims: [k, p.actions.length] };
      const prior = await runner.run('prior', { history: historyT, action: actionT });
      const z = sampleGaussian(draws, prior.prior_mean.data, prior.prior_logvar.data, k, d, temperature);
      if (isCancelled()) throw new Superseded();
      const out = await runner.run('decoder', { z: { data: z, dims: [k, d] }, history: historyT, action: actionT });
      const futLen = tMax * stride;
      for (let i = 0; i < k; i++) {
        const future = out.future.data.subarray(i * futLen, (i + 1) * futLen);
        // Eq. 8 and Eq. 4 act on root-relative poses: a walk that keeps walking is not static.
        const poses = rootRelative(future, j);
        const curve = varianceCurve(poses, tMax, stride, q);
        const stop = firstStop(curve, delta, tMin, tMax);
        const tail = rootRelative(canon.subarray((i + 1) * histLen - l * stride, (i + 1) * histLen), j);
        const s = smoothness(tail, poses.subarray(0, l * stride), l, stride, m);
        segments[i].push({ start: totals[i], length: stop.length, action, stopped: stop.stopped, smoothness: s, flagged: s > flag });
        // v at each kept frame; the last Q-1 frames of a sample that never stopped repeat the last value.
        for (let f = 0; f < stop.length; f++) series[i].push(curve[Math.min(f, curve.length - 1)]);
        const world = fromCanonical(future.slice(0, stop.length * stride), j, placements[i]);
        parts[i].push(world);
        totals[i] += stop.length;
        seqs[i] = concat(seqs[i], world);
      }
    }
    const frames = req.horizonFrames ?? Math.max(...totals);
    const futures = new Float32Array(k * frames * stride);
    const samples: SampleInfo[] = [];
    const curveSeries: Float32Array[] = [];
    for (let i = 0; i < k; i++) {
      let o = 0;
      const base = i * frames * stride;
      for (const part of parts[i]) {
        const take = Math.min(part.length, (frames - o) * stride);
        if (take <= 0) break;
        futures.set(part.subarray(0, take), base + o * stride);
        o += take / stride;
      }
      const last = futures.slice(base + (o - 1) * stride, base + o * stride);
      for (let f = o; f < frames; f++) futures.set(last, base + f * stride);   // past its length: its last pose
      const s = new Float32Array(frames);
      for (let f = 0; f < frames; f++) s[f] = series[i][Math.min(f, series[i].length - 1)];
      curveSeries.push(s);
      const segs = segments[i].filter((sg) => sg.start < frames).map((sg) => ({ ...sg, length: Math.min(sg.length, frames - sg.start) }));
      samples.push({
        length: Math.min(totals[i], frames), stopped: segments[i].every((sg) => sg.stopped),
        segments: segs, marks: segs.slice(1).map((sg) => sg.start),
      });
    }
    const never = samples.filter((s) => !s.stopped).length;
    const flagged = samples.reduce((c, s) => c + s.segments.filter((sg) => sg.flagged).length, 0);
    return {
      k, frames, joints: j, futures,
      lengths: Int32Array.from(samples.map((s) => s.length)),
      samples,
      notes: never ? [`${never} of ${k} samples did not meet the stop rule in every action and kept T_max = ${tMax} frames there`] : [],
      curves: [{
        id: 'variance', title: 'Variance of the last Q frames (Eq. 8)', series: curveSeries,
        levels: [{ label: 'delta', value: delta }], frames: [{ label: 'T_min', frame: tMin - 1 }], log: true,
      }],
      readouts: [
        { label: 'stopped', value: (100 * (k - never)) / k, unit: '%',
          about: 'Share of the K samples in which every action stopped by the variance rule (Eq. 8: the last Q frames vary less than δ) before its maximum length T_max.' },
        { label: 'mean length', value: samples.reduce((c, s) => c + s.length, 0) / k / this.ctx.fps, unit: 's',
          about: 'The samples\' mean length in seconds: each action runs until it stops (Eq. 8) or reaches T_max.' },
        { label: 'flagged transitions', value: flagged,
          about: 'Joins (history to first action, action to action) whose smoothness loss (Eq. 4) is above the model\'s threshold: a visible jerk there.' },
      ],
    };
  }
}
