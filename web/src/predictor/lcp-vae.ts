// Predictor for LCP-VAE and its Table 4 baselines, twin of export/sample/lcp_vae.py: the condition
// graph, then z for K samples, then K futures in one decoder call. A horizon beyond future_frames
// recurses on each sample's own last history_frames frames, re-canonicalised.
//   full model (params.prior 'conditional'): z = mu_c + s*sigma_c*eps (Eq. 4 at inference, z = z_c);
//     s = 0 decodes the most likely future z = mu_c (appendix E);
//   row 2 ('standard_normal', c = h_t): z = s*eps, c = h_t;
//   row 3 ('standard_normal', c = z_c): c = mu_c + s*sigma_c*eps_c, z = s*eps.
// Draw order: sample i draws from its own stream, streams(seed, K)[i] (rng/prng.ts); per graph call,
// for row 3 first d_c normals (eps_c) then d (eps), otherwise d (eps); two uniforms per normal. Nothing
// couples the samples, so the first k samples of K > k are those of K = k. sampleLatents also takes
// one Prng, whose arrays fill row-major (sample, then latent dimension): the explainer's figures draw so.
// The Gaussian is sampling/gaussian.ts's shiftScale: float64 as mu + (s*sigma)*eps, rounded to float32.
import { rowNormals, streams, type Prng } from '../rng/prng';
import { diversity } from '../sampling/diversity';
import { shiftScale } from '../sampling/gaussian';
import { fromCanonical, toCanonical, type Placement } from './canonical';
import { checkHistory, checkRequest, controlValue, horizonFrames } from './request';
import {
  PredictError, Superseded, type History, type Prediction, type PredictRequest, type Predictor,
  type PredictorContext, type Tensor,
} from './types';

export interface LcpParams {
  history_frames: number;
  future_frames: number;
  latent_size: number;
  prior: 'conditional' | 'standard_normal';
  decoder_condition: { name: 'h_t' | 'z_c'; size: number } | null;
}

/** Condition-graph outputs (batch 1 or k) -> z [k, d] and c [k, .] (or null), float32; draws from one Prng
 *  row-major or from k streams, one per sample (twin of sample_latents in export/sample/lcp_vae.py). */
export function sampleLatents(
  prng: Prng | Prng[], cond: Record<string, Tensor>, k: number, scale: number, params: LcpParams,
): { z: Float32Array; c: Float32Array | null } {
  const d = params.latent_size;
  const cSpec = params.decoder_condition;
  if (params.prior === 'conditional') {
    return { z: shiftScale(cond.mu_c.data, cond.sigma_c.data, rowNormals(prng, k, d), k, d, scale), c: null };
  }
  if (params.prior !== 'standard_normal') throw new PredictError(`unknown LCP-VAE prior '${String(params.prior)}' in the manifest`);
  let c: Float32Array | null = null;
  if (cSpec?.name === 'z_c') {
    c = shiftScale(cond.mu_c.data, cond.sigma_c.data, rowNormals(prng, k, cSpec.size), k, cSpec.size, scale);
  } else if (cSpec?.name === 'h_t') {
    c = broadcast(cond.h_t.data, k, cSpec.size);
  }
  const eps = rowNormals(prng, k, d);
  const z = new Float32Array(k * d);
  for (let i = 0; i < z.length; i++) z[i] = scale * eps[i];
  return { z, c };
}

function broadcast(x: Float32Array, k: number, size: number): Float32Array {
  if (x.length === k * size) return Float32Array.from(x);
  const out = new Float32Array(k * size);
  for (let i = 0; i < k; i++) out.set(x.subarray(0, size), i * size);
  return out;
}

export class LcpVaePredictor implements Predictor {
  constructor(private readonly ctx: PredictorContext) {}

  get entry() {
    return this.ctx.entry;
  }

  async predict(history: History, req: PredictRequest, isCancelled: () => boolean = () => false): Promise<Prediction> {
    const { entry, skeleton, runner } = this.ctx;
    const params = entry.params as unknown as LcpParams;
    const j = skeleton.joints.length;
    const n = params.history_frames;
    const step = params.future_frames;
    checkHistory(history, n, j);
    checkRequest(req, entry, this.ctx.actions, this.ctx.fps);
    const horizon = horizonFrames(req, entry, this.ctx.fps);
    const k = req.k;
    const scale = Number(controlValue(req, entry, 'sigma_scale', 1));
    const draws = streams(req.seed, k);
    const stride = j * 3;
    const histLen = n * stride;
    const futLen = step * stride;
    // Every sample starts from the same history: the first condition call runs once (batch 1).
    let recent: Float32Array[] = [history.positions.slice((history.frames - n) * stride)];
    const calls = Math.ceil(horizon / step);
    const all = new Float32Array(k * calls * futLen);   // [k, calls * step, j, 3]
    for (let call = 0; call < calls; call++) {
      if (isCancelled()) throw new Superseded();
      const rows = recent.length;
      const canon = new Float32Array(rows * histLen);
      const placements: Placement[] = [];
      recent.forEach((h, r) => {
        const { canonical, placement } = toCanonical(h, n, skeleton);
        canon.set(canonical, r * histLen);
        placements.push(placement);
      });
      const cond = await runner.run('condition', { history: { data: canon, dims: [rows, n, j, 3] } });
      const { z, c } = sampleLatents(draws, cond, k, scale, params);
      const lastPoses = new Float32Array(k * 2 * stride);      // the history's last two poses (the seam needs both)
      for (let i = 0; i < k; i++) {
        const r = rows === 1 ? 0 : i;
        lastPoses.set(canon.subarray(r * histLen + (n - 2) * stride, (r + 1) * histLen), i * 2 * stride);
      }
      const feeds: Record<string, Tensor> = {
        z: { data: z, dims: [k, params.latent_size] },
        last_poses: { data: lastPoses, dims: [k, 2, j, 3] },
      };
      if (params.decoder_condition && c) feeds.c = { data: c, dims: [k, params.decoder_condition.size] };
      if (isCancelled()) throw new Superseded();
      const res = await runner.run('decoder', feeds);
      const next: Float32Array[] = [];
      for (let i = 0; i < k; i++) {
        const future = fromCanonical(res.future.data.slice(i * futLen, (i + 1) * futLen), j, placements[rows === 1 ? 0 : i]);
        all.set(future, (i * calls + call) * futLen);
        const joined = new Float32Array(histLen + futLen);
        joined.set(recent[rows === 1 ? 0 : i]);
        joined.set(future, histLen);
        next.push(joined.slice(joined.length - histLen));
      }
      recent = next;
    }
    const futures = new Float32Array(k * horizon * stride);
    for (let i = 0; i < k; i++) {
      futures.set(all.subarray(i * calls * futLen, i * calls * futLen + horizon * stride), i * horizon * stride);
    }
    return {
      k, frames: horizon, joints: j, futures,
      lengths: Int32Array.from({ length: k }, () => horizon),
      samples: Array.from({ length: k }, () => ({ length: horizon, stopped: false, segments: [{ start: 0, length: horizon }] })),
      notes: scale === 0 && k > 1 ? ['sigma scale 0: every sample is the most likely future'] : [],
      readouts: [{ label: 'diversity', value: diversity(futures, k, horizon, stride), unit: 'm',
        about: 'LCP-VAE\'s diversity (WAT Eq. 10): the whole-pose L2 distance between two samples at each frame, averaged over frames and pairs (root-relative). '
          + 'Unlike APD it does not grow with the futures\' length: at least √18 ≈ 4.2 × the pose spread.' }],
    };
  }
}
