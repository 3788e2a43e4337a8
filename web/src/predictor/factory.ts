// The one place that knows which predictor runs which method; everything else sees Predictor.
import { DirectPredictor } from './direct';
import { PredictError, type Predictor, type PredictorContext } from './types';

export function createPredictor(ctx: PredictorContext): Predictor {
  switch (ctx.entry.method) {
    case 'zero_velocity':
    case 'regression':
      return new DirectPredictor(ctx);
    default:
      throw new PredictError(`this version of the site cannot run ${ctx.entry.method} models (${ctx.entry.id})`);
  }
}
