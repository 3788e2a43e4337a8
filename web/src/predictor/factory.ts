// The one place that knows which predictor runs which method; everything else sees Predictor.
// Every method's predictor is wrapped in the same guard (twin of export/sample/predictor.py's
// predict): the feet on the floor carry the root (foot-plant.ts) and every future is cut at its first
// out-of-bounds frame, so no method can draw an exploding
// figure. The history's warnings, its scale and the refusals' order are history.ts's.
import { DirectPredictor } from './direct';
import { plantFeet } from './foot-plant';
import { followRoots } from './ghosts';
import { cutOutOfBounds } from './guard';
import { KeyposesPredictor } from './keyposes';
import { LcpVaePredictor } from './lcp-vae';
import { checkHistory } from './request';
import {
  PredictError,
  type History,
  type Prediction,
  type PredictRequest,
  type Predictor,
  type PredictorContext,
} from './types';
import { WatPredictor } from './wat';

function methodPredictor(ctx: PredictorContext): Predictor {
  switch (ctx.entry.method) {
    case 'zero_velocity':
    case 'regression':
      return new DirectPredictor(ctx);
    case 'lcp_vae':
      return new LcpVaePredictor(ctx);
    case 'keyposes':
      return new KeyposesPredictor(ctx);
    case 'wat':
    case 'wat_transformer': // same graph signatures and params as the RNN; only the network differs
      return new WatPredictor(ctx);
    default:
      throw new PredictError(`this version of the site cannot run ${ctx.entry.method} models (${ctx.entry.id})`);
  }
}

class Guarded implements Predictor {
  constructor(private readonly inner: Predictor, private readonly ctx: PredictorContext) {}

  get entry() {
    return this.inner.entry;
  }

  async predict(history: History, req: PredictRequest, isCancelled?: () => boolean): Promise<Prediction> {
    const { entry, skeleton } = this.ctx;
    const n = entry.params.history_frames;
    const j = skeleton.joints.length;
    checkHistory(history, n, j);
    const pred = await this.inner.predict(history, req, isCancelled);
    const recent = history.positions.subarray((history.frames - n) * j * 3);
    // feet on the floor carry the root (foot-plant.ts), then the bounds are checked on what is drawn
    // (the ghosts move with their futures' roots: ghosts.ts)
    if (req.plantFeet !== false) {
      const before = pred.ghosts ? pred.futures.slice() : undefined;
      plantFeet(recent.subarray((n - 1) * j * 3), pred.futures, pred.k, pred.frames, skeleton);
      if (pred.ghosts && before) followRoots(pred.ghosts, before, pred.futures, pred.frames, pred.joints);
    }
    cutOutOfBounds(pred, recent, n, skeleton);
    pred.warnings = [];   // the history's warnings are history.ts's (createCheckedPredictor)
    return pred;
  }
}

export function createPredictor(ctx: PredictorContext): Predictor {
  return new Guarded(methodPredictor(ctx), ctx);
}
