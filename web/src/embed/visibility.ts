// Nobody watches a widget scrolled out of view or in a hidden tab: playing on would draw every frame
// for no one (software WebGL on a 2-core laptop spends most of a core on it). Playback pauses then,
// and picks up where it was once the widget is seen again. Play asked for while unseen (autoplay of a
// widget further down the page) waits the same way.
import type { Player } from '../ui/player';

/** Pause `player` while `target` is off screen or the tab is hidden; returns the undo. */
export function pauseWhileUnseen(target: Element, player: Player): () => void {
  let onScreen = true;
  let resume = false;
  const seen = () => onScreen && document.visibilityState === 'visible';
  const update = () => {
    if (!seen() && player.state.playing) { resume = true; player.pause(); }
    else if (seen() && resume) { resume = false; player.play(); }
  };
  const unsubscribe = player.subscribe((s) => { if (s.playing && !seen()) queueMicrotask(update); });
  const observer = new IntersectionObserver((entries) => {
    onScreen = entries[entries.length - 1].isIntersecting;
    update();
  });
  observer.observe(target);
  document.addEventListener('visibilitychange', update);
  return () => { observer.disconnect(); document.removeEventListener('visibilitychange', update); unsubscribe(); };
}
