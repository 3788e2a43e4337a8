// Checks a history and a request against the model's manifest entry, twin of request.py.
import type { ModelEntry } from '../contract/types';
import { MAX_SEED } from '../rng/prng';
import { PredictError, type History, type PredictRequest } from './types';

export const MAX_K = 50;

export function checkHistory(h: History, needed: number, joints: number): void {
  if (h.joints !== joints || h.positions.length !== h.frames * h.joints * 3) {
    throw new PredictError(`history must be [frames, ${joints}, 3], got ${h.frames} frames of ${h.joints} joints`);
  }
  if (h.frames < needed) throw new PredictError(`history has ${h.frames} frames; this model needs at least ${needed}`);
  for (let i = 0; i < h.positions.length; i++) {
    if (!Number.isFinite(h.positions[i])) {
      throw new PredictError(`history contains NaN or infinite values (first at frame ${Math.floor(i / (joints * 3))})`);
    }
  }
}

/** Controls that are fields of the request rather than entries of `controls`. */
export const REQUEST_FIELDS = ['k', 'actions', 'horizon'];

/** A control's value: the request's, else the manifest's default, else `absent` (a model without it). */
export function controlValue(req: Pick<PredictRequest, 'controls'>, entry: ModelEntry, id: string, absent?: unknown): unknown {
  const spec = entry.controls.find((c) => c.id === id);
  return spec ? (req.controls?.[id] ?? spec.default) : absent;
}

/** Frames to predict: the request's, else the `horizon` control's default (seconds), else one call. */
export function horizonFrames(req: PredictRequest, entry: ModelEntry, fps: number): number {
  if (req.horizonFrames !== undefined) return req.horizonFrames;
  const spec = entry.controls.find((c) => c.id === 'horizon');
  return spec ? Math.round((spec.default as number) * fps) : entry.params.future_frames;
}

export function checkRequest(req: PredictRequest, entry: ModelEntry, actions: string[], fps = 30): void {
  const controls = new Map(entry.controls.map((c) => [c.id, c]));
  if (controls.has('k')) {
    if (!Number.isInteger(req.k) || req.k < 1 || req.k > MAX_K) {
      throw new PredictError(`K must be an integer from 1 to ${MAX_K}, got ${req.k}`);
    }
  } else if (req.k !== 1) {
    throw new PredictError(`${entry.label} is deterministic: it predicts one future (K = 1), got K = ${req.k}`);
  }
  if (!Number.isInteger(req.seed) || req.seed < 0 || req.seed > MAX_SEED) {
    throw new PredictError(`seed must be an integer from 0 to ${MAX_SEED}, got ${req.seed}`);
  }
  for (const a of req.actions ?? []) {
    if (!actions.includes(a)) throw new PredictError(`unknown action '${a}'; this model knows ${actions.join(', ')}`);
  }
  if (controls.has('actions') && !(req.actions ?? []).length) {
    throw new PredictError('the action sequence is empty: add at least one action');
  }
  if (req.horizonFrames !== undefined) {
    const spec = controls.get('horizon');
    const lo = spec ? Math.round(spec.min! * fps) : 1;
    const hi = spec ? Math.round(spec.max! * fps) : entry.params.future_frames;
    if (!Number.isInteger(req.horizonFrames) || req.horizonFrames < lo || req.horizonFrames > hi) {
      throw new PredictError(`the horizon must be ${lo} to ${hi} frames, got ${req.horizonFrames}`);
    }
  }
  for (const [id, value] of Object.entries(req.controls ?? {})) {
    const spec = controls.get(id);
    if (REQUEST_FIELDS.includes(id)) throw new PredictError(`'${id}' is a field of the request, not a control value`);
    if (!spec) throw new PredictError(`${entry.label} has no control '${id}'`);
    if (spec.type === 'int' || spec.type === 'number') {
      if (typeof value !== 'number' || !Number.isFinite(value)) throw new PredictError(`${spec.label} must be a number, got ${value}`);
      if ((spec.min !== undefined && value < spec.min) || (spec.max !== undefined && value > spec.max)) {
        throw new PredictError(`${spec.label} must be between ${spec.min} and ${spec.max}, got ${value}`);
      }
    }
  }
}
