// The one place that knows which predictor runs which method; everything else sees Predictor.
import { DirectPredictor } from './direct';
import { KeyposesPredictor } from './keyposes';
import { LcpVaePredictor } from './lcp-vae';
import { PredictError, type Predictor, type PredictorContext } from './types';
import { WatPredictor } from './wat';

export function createPredictor(ctx: PredictorContext): Predictor {
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
