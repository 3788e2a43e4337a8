// From control values to a PredictRequest: k, actions and horizon are request fields; the rest
// are the model's own controls; plantFeet is the site's (predictor/foot-plant.ts), sent only when off.
import type { ModelEntry } from '../contract/types';
import type { PredictRequest } from '../predictor/types';
import type { ControlValue } from './controls';

export function buildRequest(entry: ModelEntry, values: Record<string, ControlValue>, seed: number, fps: number,
  plantFeet = true): PredictRequest {
  const req: PredictRequest = { k: 1, seed, controls: {} };
  if (!plantFeet) req.plantFeet = false;
  for (const spec of entry.controls) {
    const v = values[spec.id];
    if (v === undefined) continue;
    if (spec.id === 'k') req.k = v as number;
    else if (spec.id === 'actions') req.actions = v as string[];
    else if (spec.id === 'horizon') req.horizonFrames = Math.round((v as number) * fps);
    else req.controls![spec.id] = v as number | boolean;
  }
  return req;
}
