// The main page: the header's styles, then the full widget (<motion-futures page> in index.html),
// the same code path as every embed.
import './styles.css';
import type { MotionFuturesElement } from './embed/element';
import './embed/element';
import type { App } from './ui/app';

declare global {
  interface Window {
    /** The running page, for the console and browser tests. */
    motionFutures?: App;
  }
}

window.motionFutures = document.querySelector<MotionFuturesElement>('motion-futures[page]')?.app ?? undefined;
