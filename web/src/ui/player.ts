// The shared timeline: play/pause, speed, seeking; time advances by wall clock on animation frames.
import { advance, clampSpeed, frameAt, nextSpeed, stepFrame } from './timeline';

export interface PlayerState {
  /** Fractional position in frames (what the viewer draws). */
  position: number;
  /** Whole frame shown in the read-out and scrubber. */
  frame: number;
  length: number;
  fps: number;
  playing: boolean;
  speed: number;
  loop: boolean;
}

type Listener = (state: PlayerState) => void;

export interface FrameClock {
  request(cb: (now: number) => void): number;
  cancel(handle: number): void;
}

const browserClock: FrameClock = {
  request: (cb) => requestAnimationFrame(cb),
  cancel: (h) => cancelAnimationFrame(h),
};

export class Player {
  private position = 0;
  private length = 0;
  private playing = false;
  private speed = 1;
  private loop = true;
  private handle = 0;
  private last: number | null = null;
  private readonly listeners = new Set<Listener>();

  constructor(private fps = 30, private readonly clock: FrameClock = browserClock) {}

  get state(): PlayerState {
    return {
      position: this.position, frame: frameAt(this.position, this.length), length: this.length, fps: this.fps,
      playing: this.playing, speed: this.speed, loop: this.loop,
    };
  }

  /** Listen to every change; called at once with the current state. Returns an unsubscribe. */
  subscribe(listener: Listener): () => void {
    this.listeners.add(listener);
    listener(this.state);
    return () => this.listeners.delete(listener);
  }

  /** A new timeline: `length` frames at `fps`, starting at `start`. */
  load(length: number, fps = this.fps, start = 0): void {
    this.length = Math.max(0, Math.floor(length));
    this.fps = fps;
    this.position = frameAt(start, this.length);
    if (this.length <= 1) this.pause();
    this.emit();
  }

  play(): void {
    if (this.playing || this.length <= 1) return;
    if (!this.loop && frameAt(this.position, this.length) >= this.length - 1) this.position = 0;
    this.playing = true;
    this.last = null;
    this.handle = this.clock.request(this.tick);
    this.emit();
  }

  pause(): void {
    if (!this.playing) return;
    this.playing = false;
    this.clock.cancel(this.handle);
    this.position = frameAt(this.position, this.length); // rest on a whole frame
    this.emit();
  }

  toggle(): void { if (this.playing) this.pause(); else this.play(); }

  seek(frame: number): void {
    this.position = frameAt(frame, this.length);
    this.last = null;
    this.emit();
  }

  /** Step whole frames; stepping pauses. */
  step(delta: number): void {
    this.pause();
    this.seek(stepFrame(frameAt(this.position, this.length), delta, this.length, this.loop));
  }

  setSpeed(speed: number): void { this.speed = clampSpeed(speed); this.emit(); }
  faster(): void { this.setSpeed(nextSpeed(this.speed, 1)); }
  slower(): void { this.setSpeed(nextSpeed(this.speed, -1)); }
  setLoop(loop: boolean): void { this.loop = loop; this.emit(); }

  dispose(): void { this.pause(); this.listeners.clear(); }

  private readonly tick = (now: number): void => {
    if (!this.playing) return;
    if (this.last !== null) {
      const next = advance(this.position, (now - this.last) / 1000, this.speed, this.fps, this.length, this.loop);
      this.position = next.position;
      if (next.ended) { this.last = null; this.pause(); return; }
    }
    this.last = now;
    this.emit();
    this.handle = this.clock.request(this.tick);
  };

  private emit(): void {
    const s = this.state;
    for (const l of this.listeners) l(s);
  }
}
