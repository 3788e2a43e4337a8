// Ghost poses move with their future: a step that moves a future's root after the method (planted feet,
// foot-plant.ts) moves each ghost by its future's root shift at the ghost's frame, so a ghost stands
// where the drawn figure stands. Twin of export/sample/ghosts.py (same float64 sums, float32 out).
import type { Ghosts } from './types';

/** In place: the ghosts of futures [k, frames, joints, 3] that went from `before` to `after`. */
export function followRoots(ghosts: Ghosts, before: ArrayLike<number>, after: ArrayLike<number>, frames: number, joints: number): void {
  const s = joints * 3;
  ghosts.frames.forEach((marks, q) => {
    if (marks.some((m) => !(m >= 0 && m < frames))) {
      throw new Error(`future ${q} has a ghost outside its ${frames} frames: ${marks.join(', ')}`);
    }
    const poses = ghosts.poses[q];
    marks.forEach((m, i) => {
      const at = (q * frames + m) * s;
      for (let c = 0; c < 3; c++) {
        const d = after[at + c] - before[at + c];
        for (let j = 0; j < joints; j++) poses[i * s + j * 3 + c] += d;
      }
    });
  });
}
