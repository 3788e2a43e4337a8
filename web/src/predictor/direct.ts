// Predictor for the deterministic baselines (zero-velocity, regression GRU), twin of
// export/sample/direct.py: one fixed-horizon graph call, repeated on its own output.
import { fromCanonical, toCanonical } from './canonical';
import { checkHistory, checkRequest, horizonFrames } from './request';
import { Superseded, type History, type Prediction, type PredictRequest, type Predictor, type PredictorContext } from './types';

export class DirectPredictor implements Predictor {
  constructor(private readonly ctx: PredictorContext) {}

  get entry() {
    return this.ctx.entry;
  }

  async predict(history: History, req: PredictRequest, isCancelled: () => boolean = () => false): Promise<Prediction> {
    const { entry, skeleton, runner } = this.ctx;
    const j = skeleton.joints.length;
    const n = entry.params.history_frames;
    const step = entry.params.future_frames;
    checkHistory(history, n, j);
    checkRequest(req, entry, this.ctx.actions, this.ctx.fps);
    const horizon = horizonFrames(req, entry, this.ctx.fps);
    const stride = j * 3;
    let frames = history.positions.slice((history.frames - n) * stride);
    const out = new Float32Array(Math.ceil(horizon / step) * step * stride);
    let done = 0;
    while (done < horizon) {
      if (isCancelled()) throw new Superseded();
      const { canonical, placement } = toCanonical(frames.slice(frames.length - n * stride), n, skeleton);
      const res = await runner.run('predict', { history: { data: canonical, dims: [1, n, j, 3] } });
      const future = fromCanonical(res.future.data, j, placement);
      out.set(future, done * stride);
      done += step;
      const joined = new Float32Array(frames.length + future.length);
      joined.set(frames);
      joined.set(future, frames.length);
      frames = joined.slice(joined.length - n * stride);
    }
    return {
      k: 1, frames: horizon, joints: j, futures: out.slice(0, horizon * stride),
      lengths: Int32Array.from([horizon]),
      samples: [{ length: horizon, stopped: false, segments: [{ start: 0, length: horizon }] }],
      notes: [],
    };
  }
}
