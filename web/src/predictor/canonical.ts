// Into and out of the canonical frame, twin of export/sample/canonical.py: each graph call
// sees a history that faces +z at its last frame.
import type { Skeleton } from '../contract/types';
import { canonicalise, rotateAboutY } from '../motion/facing';

export function toCanonical(history: Float32Array, frames: number, skeleton: Skeleton): { canonical: Float32Array; angle: number } {
  const { canonical, angle } = canonicalise(Float64Array.from(history), frames - 1, skeleton);
  return { canonical: Float32Array.from(canonical), angle };
}

export function fromCanonical(frames: Float32Array, angle: number): Float32Array {
  return Float32Array.from(rotateAboutY(Float64Array.from(frames), angle));
}
