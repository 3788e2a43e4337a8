// Bootstrap: styles, then the app; if even that fails, say so on the page rather than leave it blank.
import './styles.css';
import { startApp, type App } from './ui/app';

declare global {
  interface Window {
    /** The running page, for the console and browser tests. */
    motionFutures?: App;
  }
}

try {
  window.motionFutures = startApp();
} catch (err) {
  const box = document.getElementById('messages') ?? document.body;
  const p = document.createElement('p');
  p.className = 'message message-error';
  p.setAttribute('role', 'alert');
  p.textContent = `The page failed to start: ${(err as Error)?.message ?? String(err)}`;
  box.append(p);
  console.error(err);
}
