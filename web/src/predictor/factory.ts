// The one place that knows which predictor runs which method; everything else sees Predictor.
// Every method's predictor is wrapped in the same guards (twin of export/sample/predictor.py's
// predict): a history outside the training envelope gets named warnings, and every future is cut at
// its first out-of-bounds frame, so no method can draw an exploding figure.
import { toCanonical } from './canonical';
import { DirectPredictor } from './direct';
import { checkEnvelope } from './envelope';
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
  type RangeWarning,
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
    const { entry, skeleton, fps } = this.ctx;
    const n = entry.params.history_frames;
    const j = skeleton.joints.length;
    checkHistory(history, n, j);
    const recent = history.positions.subarray((history.frames - n) * j * 3);
    const env = (entry.params as { envelope?: Record<string, [number, number]> }).envelope;
    const warnings = env ? checkEnvelope(toCanonical(recent, n, skeleton).canonical, n, fps, skeleton, env) : [];
    let pred: Prediction;
    try {
      pred = await this.inner.predict(history, req, isCancelled);
    } catch (e) {
      // A refusal also names the envelope warnings, which may be its real cause.
      if (e instanceof PredictError) throw new PredictError(refusalWithWarnings(e.message, warnings));
      throw e;
    }
    cutOutOfBounds(pred, recent, n, skeleton);
    pred.warnings = warnings;
    return pred;
  }
}

/** A refusal followed by the history's envelope warnings (twin of predictor.py refusal_with_warnings). */
export function refusalWithWarnings(message: string, warnings: RangeWarning[]): string {
  if (warnings.length === 0) return message;
  return `${message}. The history is outside the training range: ${warnings.map((w) => w.message).join(' ')}`;
}

export function createPredictor(ctx: PredictorContext): Predictor {
  return new Guarded(methodPredictor(ctx), ctx);
}
