// Keyposes predictor, twin of export/sample/keyposes.py: extract the history's keyposes, feed them
// to the KP-GRU step graph, sample K label and duration sequences with the shared PRNG, interpolate
// the centres from the present pose (Eq. 3) and optionally refine.
//
// Draw order (both languages): sample i draws from its own stream, streams(seed, K)[i] (rng/prng.ts):
// after the observed keyposes, at each step whose horizon it has not yet covered, one uniform for the
// label, then one for the duration class. A sample's logits come from its own row of the batched step
// graph, so the first k samples of K > k are those of K = k.
import { streams } from '../rng/prng';
import { rotateAboutY } from '../motion/facing';
import { interpolateKeyposes, keyposeTimes } from '../sampling/keypose-interpolation';
import { durationClass, extractKeyposes, faceForward, labelDistribution, nearestCentre, pace, prune, travel } from '../sampling/keyposes';
import { sampleIndex } from '../sampling/temperature';
import { continueHistory } from '../sampling/seam';
import { keepBones } from '../motion/bones';
import { canonicalise, place, rootRelative, splitRoot } from './canonical';
import { checkHistory, checkRequest, controlValue, horizonFrames } from './request';
import {
  PredictError, Superseded, type History, type Prediction, type PredictRequest, type Predictor, type PredictorContext, type SampleInfo, type Tensor,
} from './types';

interface KeyposesParams {
  history_frames: number;
  refine_frames: number;
  label_temperature: number;
  keyposes: { threshold: number; clusters: number; min_observed: number; max_observed: number; layers: number; hidden: number };
  duration_classes: { bounds: number[]; lengths: number[] };
  /** The seam with the history and fixed bone lengths (false only in the no-shape ablation). */
  finish?: boolean;
}

export interface Observed {
  frames: number[];
  labels: number[];
  labelDist: Float32Array;
  duration: Float32Array;
}

/** The centres file: centres [K][J][3] and the root channel's velocity per cluster [K][2], flat. */
export interface CentresFile {
  centres: Float64Array;
  rootVelocity: Float64Array;
}

export class KeyposesPredictor implements Predictor {
  private centres: Promise<CentresFile> | null = null;

  constructor(private readonly ctx: PredictorContext) {}

  get entry() {
    return this.ctx.entry;
  }

  private get params(): KeyposesParams {
    return this.ctx.entry.params as unknown as KeyposesParams;
  }

  /** The centres file, checked against the manifest's cluster count. */
  loadCentres(): Promise<CentresFile> {
    this.centres ??= (async () => {
      const { entry, skeleton } = this.ctx;
      const file = entry.files?.centres;
      if (!file) throw new Error(`model ${entry.id} names no keypose centres file in the manifest`);
      const text = new TextDecoder().decode(await this.ctx.loadFile(file));
      let doc: { centres?: unknown; root_velocity?: unknown };
      try {
        doc = JSON.parse(text);
      } catch (err) {
        throw new Error(`${file}: not valid JSON (${(err as Error).message})`);
      }
      const k = this.params.keyposes.clusters;
      const j = skeleton.joints.length;
      const c = doc.centres;
      const ok = Array.isArray(c) && c.length === k && c.every((p) => Array.isArray(p) && p.length === j
        && p.every((x) => Array.isArray(x) && x.length === 3 && x.every((v) => typeof v === 'number')));
      if (!ok) throw new Error(`${file}: centres must be [${k}][${j}][3] numbers`);
      const v = doc.root_velocity;
      const okV = Array.isArray(v) && v.length === k && v.every((r) => Array.isArray(r) && r.length === 2 && r.every((x) => typeof x === 'number'));
      if (!okV) throw new Error(`${file}: root_velocity must be [${k}][2] numbers`);
      return { centres: Float64Array.from((c as number[][][]).flat(2)), rootVelocity: Float64Array.from((v as number[][]).flat()) };
    })();
    this.centres.catch(() => { this.centres = null; }); // a failed load may be retried
    return this.centres;
  }

  /** The history's keyposes: frames, labels after pruning, and the KP-GRU's inputs. */
  observe(history: History, centres: Float64Array): Observed {
    const p = this.params;
    const { skeleton } = this.ctx;
    const j = skeleton.joints.length;
    const s = j * 3;
    const n = p.history_frames;
    const k = p.keyposes;
    // keyposes act on root-relative poses (canonical.ts)
    const hist = rootRelative(splitRoot(Float64Array.from(history.positions.subarray((history.frames - n) * s)), j), j);
    const all = extractKeyposes(hist, n, j, k.threshold);
    const values = new Float64Array(all.length * s);
    all.forEach((f, i) => values.set(hist.subarray(f * s, (f + 1) * s), i * s));
    const faced = faceForward(values, all.length, skeleton);
    const { labels } = nearestCentre(faced, all.length, centres, k.clusters, j);
    let keep = prune(labels);
    if (keep.length < k.min_observed) {
      throw new PredictError(`the history yields ${keep.length} keypose${keep.length === 1 ? '' : 's'} at the ${k.threshold} m threshold; Keyposes needs at `
        + `least ${k.min_observed}: choose a history with more motion`);
    }
    keep = keep.slice(-k.max_observed);
    const frames = keep.map((i) => all[i]);
    const kept = new Float64Array(keep.length * s);
    keep.forEach((i, r) => kept.set(faced.subarray(i * s, (i + 1) * s), r * s));
    const bounds = p.duration_classes.bounds;
    const duration = new Float32Array(frames.length * bounds.length);
    for (let i = 1; i < frames.length; i++) duration[i * bounds.length + durationClass(frames[i] - frames[i - 1], bounds)] = 1;
    const labelDist = Float32Array.from(labelDistribution(kept, keep.length, centres, k.clusters, j, p.label_temperature));
    return { frames, labels: keep.map((i) => labels[i]), labelDist, duration };
  }

  async predict(history: History, req: PredictRequest, isCancelled: () => boolean = () => false): Promise<Prediction> {
    const { entry, skeleton, runner } = this.ctx;
    const p = this.params;
    const j = skeleton.joints.length;
    const s = j * 3;
    checkHistory(history, p.history_frames, j);
    checkRequest(req, entry, this.ctx.actions, this.ctx.fps);
    const temperature = Number(controlValue(req, entry, 'temperature'));
    if (!(temperature > 0)) throw new PredictError(`the temperature must be above 0, got ${temperature}`);
    const refine = controlValue(req, entry, 'refine');
    if (typeof refine !== 'boolean') throw new PredictError(`Refine must be true or false, got ${refine}`);
    const horizon = horizonFrames(req, entry, this.ctx.fps);
    const r = p.refine_frames;
    if (horizon > r) throw new PredictError(`the horizon must be at most ${r} frames, got ${horizon}`);
    const need = refine ? r : horizon;
    const { centres, rootVelocity } = await this.loadCentres();
    const kk = p.keyposes.clusters;
    const lengths = p.duration_classes.lengths;
    const nd = lengths.length;
    const { layers, hidden } = p.keyposes;
    const hs = layers * hidden;

    const obs = this.observe(history, centres);
    let h: Float32Array = new Float32Array(hs);
    let out: Record<string, Tensor> = {};
    for (let i = 0; i < obs.frames.length; i++) {
      if (isCancelled()) throw new Superseded();
      out = await runner.run('step', {
        label_dist: { data: obs.labelDist.slice(i * kk, (i + 1) * kk), dims: [1, kk] },
        duration: { data: obs.duration.slice(i * nd, (i + 1) * nd), dims: [1, nd] },
        hidden: { data: h, dims: [1, layers, hidden] },
      });
      h = out.next_hidden.data;
    }
    const k = req.k;
    let logits: Float32Array = tile(out.label_logits.data, k);
    let dlogits: Float32Array = tile(out.duration_logits.data, k);
    let hk: Float32Array = tile(h, k);

    // A fed-back label's distribution: its centre's proximity to every centre (3.2.1, case 2).
    const centreDist = Float32Array.from(labelDistribution(centres, kk, centres, kk, j, p.label_temperature));
    const draws = streams(req.seed, k);
    const labels: number[][] = Array.from({ length: k }, () => []);
    const classes: number[][] = Array.from({ length: k }, () => []);
    const covered = new Array<number>(k).fill(0);
    const margins: number[] = [];
    for (;;) {
      for (let q = 0; q < k; q++) {
        if (covered[q] >= need) continue;
        const lab = sampleIndex(logits.subarray(q * kk, (q + 1) * kk), temperature, draws[q].uniform());
        const dur = sampleIndex(dlogits.subarray(q * nd, (q + 1) * nd), temperature, draws[q].uniform());
        labels[q].push(lab.index);
        classes[q].push(dur.index);
        covered[q] += lengths[dur.index];
        for (const m of [lab.margin, dur.margin]) if (Number.isFinite(m)) margins.push(m);
      }
      if (Math.min(...covered) >= need) break;
      if (isCancelled()) throw new Superseded();
      const dist = new Float32Array(k * kk);
      const dur = new Float32Array(k * nd);
      for (let q = 0; q < k; q++) {
        const l = labels[q][labels[q].length - 1];
        dist.set(centreDist.subarray(l * kk, (l + 1) * kk), q * kk);
        dur[q * nd + classes[q][classes[q].length - 1]] = 1;
      }
      out = await runner.run('step', {
        label_dist: { data: dist, dims: [k, kk] }, duration: { data: dur, dims: [k, nd] }, hidden: { data: hk, dims: [k, layers, hidden] },
      });
      logits = out.label_logits.data;
      dlogits = out.duration_logits.data;
      hk = out.next_hidden.data;
    }

    const n = p.history_frames;
    const { canonical, placement } = canonicalise(Float64Array.from(history.positions.subarray((history.frames - n) * s)), n - 1, skeleton);
    const present = rootRelative(canonical.subarray((n - 1) * s), j);
    const durations = classes.map((cs) => cs.map((c) => lengths[c]));
    let futures = new Float64Array(k * need * s);
    for (let q = 0; q < k; q++) {
      const poses = new Float64Array(labels[q].length * s);
      labels[q].forEach((l, i) => poses.set(centres.subarray(l * s, (l + 1) * s), i * s));
      futures.set(interpolateKeyposes(present, poses, durations[q], need), q * need * s);
    }
    let frames = need;
    if (refine) {
      if (isCancelled()) throw new Superseded();
      const seq = new Float32Array(k * (r + 1) * s);
      for (let q = 0; q < k; q++) {
        seq.set(present, q * (r + 1) * s);
        seq.set(futures.subarray(q * need * s, q * need * s + r * s), (q * (r + 1) + 1) * s);
      }
      const res = await runner.run('refine', { sequence: { data: seq, dims: [k, r + 1, j, 3] } });
      futures = Float64Array.from(res.refined.data);
      frames = r;
    }
    const cut = new Float64Array(k * horizon * s);
    // the history's own pace on the table's velocities (export/ops/keypose_travel.py `pace`)
    const historyRoot = new Float64Array(n * 2);
    for (let f = 0; f < n; f++) {
      historyRoot[f * 2] = canonical[f * s];
      historyRoot[f * 2 + 1] = canonical[f * s + 2];
    }
    const scale = pace(historyRoot, obs.labels, rootVelocity);
    for (let q = 0; q < k; q++) {
      cut.set(futures.subarray(q * frames * s, (q * frames + horizon) * s), q * horizon * s);
      // the root channel, per segment (export/ops/keypose_travel.py), in the root joint's x and z
      const path = travel(labels[q], durations[q], rootVelocity, horizon, scale);
      for (let f = 0; f < horizon; f++) {
        cut[(q * horizon + f) * s] = path[f * 2];
        cut[(q * horizon + f) * s + 2] = path[f * 2 + 1];
      }
    }
    // then the seam with the history and the skeleton's bone lengths, as the other methods' graphs end
    const finished = p.finish === false ? cut : keepBones(continueHistory(cut, k, horizon, s, canonical.subarray((n - 2) * s, n * s)), k * horizon, skeleton);
    const world = Float32Array.from(place(finished, j, placement));

    const samples: SampleInfo[] = [];
    const ghostFrames: number[][] = [];
    const ghostPoses: Float32Array[] = [];
    let shownTotal = 0;
    for (let q = 0; q < k; q++) {
      const times = keyposeTimes(durations[q]);
      const shown = times.filter((t) => t <= horizon).length;
      const marks = times.slice(0, shown).map((t) => t - 1);
      samples.push({ length: horizon, stopped: false, segments: [{ start: 0, length: horizon }], marks, labels: labels[q].slice(0, shown) });
      ghostFrames.push(marks);
      const poses = new Float64Array(shown * s);
      labels[q].slice(0, shown).forEach((l, i) => poses.set(centres.subarray(l * s, (l + 1) * s), i * s));
      rotateAboutY(poses, placement.angle);
      marks.forEach((m, i) => {   // each ghost stands where the root is at its frame
        const at = (q * horizon + m) * s;
        for (let jj = 0; jj < j; jj++) {
          poses[(i * j + jj) * 3] += world[at];
          poses[(i * j + jj) * 3 + 2] += world[at + 2];
        }
      });
      ghostPoses.push(Float32Array.from(poses));
      shownTotal += shown;
    }
    return {
      k, frames: horizon, joints: j, futures: world, lengths: Int32Array.from({ length: k }, () => horizon), samples, notes: [],
      ghosts: { frames: ghostFrames, poses: ghostPoses },
      readouts: [
        { label: 'observed keyposes', value: obs.frames.length,
          about: 'Keyposes found in the history (the frames linear interpolation cannot skip), each labelled by its nearest cluster centre: what the GRU reads.' },
        { label: 'keyposes per future', value: shownTotal / k,
          about: 'Keyposes each future samples on average (a label and a duration each) until the horizon is covered.' },
        { label: 'travel pace (history / training)', value: Math.round(scale * 1e4) / 1e4,
          about: 'How fast the history\'s root travels against the training futures of its keyposes (1: as fast); the futures\' root paths are scaled by it.' }],
      margins,
    };
  }

}

/** A batch-1 row repeated k times. */
function tile(row: Float32Array, k: number): Float32Array {
  const out = new Float32Array(row.length * k);
  for (let q = 0; q < k; q++) out.set(row, q * row.length);
  return out;
}
