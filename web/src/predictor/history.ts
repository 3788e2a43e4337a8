// What the predictor says about a history before predicting from it (issue 30), twin of
// export/sample/history.py and of predictor.py's predict (contract/vectors/envelope.json ties them):
// the training envelope (envelope.ts) and three findings it cannot express as a range:
// - handedness: a body reflected without swapping its left and right labels (motion/handedness.ts);
// - motion: a history that does not move, said in one sentence with its speed (predicted anyway);
// - body_scale: a body at another size, brought to the model's size for predicting and scaled back
//   (canonical.ts).
// A refusal that comes with warnings leads with the one that most likely caused it.
import type { Skeleton } from '../contract/types';
import { HANDEDNESS_MESSAGE, HANDEDNESS_THRESHOLD, handedness } from '../motion/handedness';
import { SCALE_LIMITS, SCALE_TOLERANCE, bodyScale, rescale, scaleAnchor, toCanonical } from './canonical';
import { checkEnvelope, type Envelope } from './envelope';
import { createPredictor } from './factory';
import { checkHistory, checkRequest } from './request';
import {
  PredictError,
  type History,
  type Prediction,
  type PredictRequest,
  type Predictor,
  type PredictorContext,
  type RangeWarning,
} from './types';

/** m/s: a history whose fastest joint is slower than this does not move. */
export const STILL_SPEED = 0.05;
/** Findings that are not ranges come first when they occur: each alone explains odd futures. */
const CATEGORICAL = ['handedness', 'motion'];

/** The fastest joint speed between any two frames of a world history (m/s). */
export function stillSpeed(world: ArrayLike<number>, frames: number, joints: number, fps: number): number {
  let top = 0;
  const s = joints * 3;
  for (let f = 1; f < frames; f++) {
    for (let j = 0; j < joints; j++) {
      const a = (f - 1) * s + j * 3;
      const b = f * s + j * 3;
      top = Math.max(top, Math.hypot(world[b] - world[a], world[b + 1] - world[a + 1], world[b + 2] - world[a + 2]));
    }
  }
  return top * fps;
}

/** The warnings for a history: `recent` its last frames as given (world), `canonical` the same frames as
 * the model sees them (at the model's size), `scale` its body size against the model's. */
export function historyWarnings(recent: ArrayLike<number>, canonical: ArrayLike<number>, frames: number, fps: number,
  skeleton: Skeleton, env: Envelope | undefined, scale: number): RangeWarning[] {
  const out: RangeWarning[] = [];
  const J = skeleton.joints.length;
  const hand = handedness(recent, frames, skeleton);
  if (hand.reflected) {
    out.push({ quantity: 'handedness', value: round4(hand.score), min: HANDEDNESS_THRESHOLD, max: 1, unit: '', message: HANDEDNESS_MESSAGE });
  }
  const speed = stillSpeed(recent, frames, J, fps);
  if (speed < STILL_SPEED) {
    const top = (env?.joint_speed as [number, number] | undefined)?.[1] ?? 100;
    out.push({ quantity: 'motion', value: round4(speed), min: STILL_SPEED, max: top, unit: 'm/s',
      message: `The history does not move: its fastest joint moves at ${speed.toFixed(3)} m/s, so the futures start from rest.` });
  }
  if (Math.abs(scale - 1) > SCALE_TOLERANCE) {
    out.push({ quantity: 'body_scale', value: round4(scale), min: round4(1 - SCALE_TOLERANCE), max: round4(1 + SCALE_TOLERANCE), unit: 'x',
      message: `The body is ${scale.toFixed(2)} times the model's size (bone lengths): it was brought to the model's size for predicting, and the futures scaled back.` });
  }
  if (env) out.push(...checkEnvelope(canonical, frames, fps, skeleton, env));
  return ordered(out);
}

/** The warnings for the last frames of a world history, as the predictor gives them: the envelope
 * measured on the history brought to the model's size (twin of history.py warnings_for). */
export function warningsFor(recent: Float32Array, frames: number, fps: number, skeleton: Skeleton, env: Envelope | undefined): RangeWarning[] {
  const J = skeleton.joints.length;
  const scale = bodyScale(recent, frames, skeleton);
  const work = Math.abs(scale - 1) > SCALE_TOLERANCE ? rescale(recent, 1 / scale, scaleAnchor(recent, frames, J)) : recent;
  return historyWarnings(recent, toCanonical(work, frames, skeleton).canonical, frames, fps, skeleton, env, scale);
}

function round4(v: number): number {
  return Math.round(v * 1e4) / 1e4;
}

/** How far a range warning lies outside its range, in widths of the range (categorical: infinite). */
export function excess(w: RangeWarning): number {
  if (CATEGORICAL.includes(w.quantity)) return Infinity;
  const span = Math.max(w.max - w.min, 1e-9);
  return Math.max(w.min - w.value, w.value - w.max, 0) / span;
}

/** Most likely cause first: categorical findings, then the range farthest outside (stable). */
export function ordered(warnings: RangeWarning[]): RangeWarning[] {
  const rank = (w: RangeWarning) => (CATEGORICAL.includes(w.quantity) ? CATEGORICAL.indexOf(w.quantity) : 0);
  return warnings.map((w, i) => ({ w, i })).sort((a, b) => {
    const ea = excess(a.w);
    const eb = excess(b.w);
    if (ea !== eb) return eb - ea;
    return rank(a.w) - rank(b.w) || a.i - b.i;
  }).map(({ w }) => w);
}

/** A refusal that has warnings leads with the most likely cause, says why, then gives the refusal. */
export function refusalWithWarnings(message: string, warnings: RangeWarning[]): string {
  if (warnings.length === 0) return message;
  const [first, ...rest] = ordered(warnings);
  const why = CATEGORICAL.includes(first.quantity) ? '' : ', the quantity farthest outside the training range';
  let out = `${first.message} That is the most likely cause of this refusal${why}: ${message}.`;
  if (rest.length) out += ` Also outside the training range: ${rest.map((w) => w.message).join(' ')}`;
  return out;
}

/** A method's predictor with the history checks of predictor.py's predict around it: the body brought to
 * the model's size, the warnings above, and refusals that lead with their likely cause. */
class Checked implements Predictor {
  constructor(private readonly inner: Predictor, private readonly ctx: PredictorContext) {}

  get entry() {
    return this.ctx.entry;
  }

  async predict(history: History, req: PredictRequest, isCancelled?: () => boolean): Promise<Prediction> {
    const { entry, skeleton, fps, actions } = this.ctx;
    const n = entry.params.history_frames;
    const J = skeleton.joints.length;
    checkHistory(history, n, J);
    checkRequest(req, entry, actions, fps);
    const recent = history.positions.subarray((history.frames - n) * J * 3);
    const scale = bodyScale(recent, n, skeleton);
    const [lo, hi] = SCALE_LIMITS;
    if (!(scale >= lo && scale <= hi)) {
      throw new PredictError(`the body is ${scale.toFixed(2)} times the model's size (bone lengths); this model predicts `
        + `bodies ${lo}-${hi} times its size: retarget the history to the skeleton first`);
    }
    const scaled = Math.abs(scale - 1) > SCALE_TOLERANCE;
    const anchor = scaleAnchor(history.positions, history.frames, J);
    const work = scaled ? { ...history, positions: rescale(history.positions, 1 / scale, anchor) } : history;
    const env = (entry.params as { envelope?: Envelope }).envelope;
    const warnings = warningsFor(recent, n, fps, skeleton, env);
    let pred: Prediction;
    try {
      pred = await this.inner.predict(work, req, isCancelled);
    } catch (e) {
      if (e instanceof PredictError) throw new PredictError(refusalWithWarnings(e.message, warnings));
      throw e;
    }
    if (scaled) {
      pred.futures = rescale(pred.futures, scale, anchor);
      if (pred.ghosts) pred.ghosts.poses = pred.ghosts.poses.map((p) => rescale(p, scale, anchor));
    }
    pred.warnings = warnings;
    return pred;
  }
}

/** The predictor the site runs: the method's, guarded (factory.ts), with the history checks around it. */
export function createCheckedPredictor(ctx: PredictorContext): Predictor {
  return new Checked(createPredictor(ctx), ctx);
}
