// <motion-futures>: the widget as a custom element, the one script a project page includes.
//   <script type="module" src="SITE/assets/motion-futures.js"></script>
//   <motion-futures model="regression-gru" clip="cmu_10_04" seed="3" autoplay></motion-futures>
// Attributes are read once, when the element connects. With the `page` attribute the element is
// the whole page (index.html, embed.html): the page URL overrides the attributes and is kept up
// to date as a permalink, keys act with nothing focused, and the page works offline.
import type { App } from '../ui/app';
import { registerServiceWorker } from './offline';
import { attributeParams, viewOptions, viewQuery } from './options';
import { mountWidget } from './widget';

export class MotionFuturesElement extends HTMLElement {
  /** The running instance, once connected. */
  app: App | null = null;

  connectedCallback(): void {
    if (this.app) return;
    const page = this.hasAttribute('page');
    const params = attributeParams(this);
    if (page) params.push(...new URLSearchParams(location.search));
    try {
      this.app = mountWidget(this, {
        view: viewOptions(params, page),
        link: params,
        onLink: page ? (search) => keepPageUrl(search) : undefined,
      });
      if (page) registerServiceWorker(this.app.ready, (s) => this.app?.offline(s), () => this.app?.onStage().source.kind === 'dropped');
    } catch (err) {
      const box = document.createElement('p');
      box.setAttribute('role', 'alert');
      box.textContent = `motion-futures failed to start: ${(err as Error)?.message ?? String(err)}`;
      (this.shadowRoot ?? this).append(box);
      console.error(err);
    }
  }

  disconnectedCallback(): void {
    this.app?.player.pause();
  }
}

/** The page URL: the state's query, then the view options the page was opened with. */
function keepPageUrl(search: string | null): void {
  const q = new URLSearchParams(search ?? '');
  for (const [k, v] of viewQuery(location.search)) q.set(k, v);
  const text = q.toString();
  const url = `${location.pathname}${text ? `?${text}` : ''}${location.hash}`;
  if (url !== `${location.pathname}${location.search}${location.hash}`) history.replaceState(history.state, '', url);
}

if (!customElements.get('motion-futures')) customElements.define('motion-futures', MotionFuturesElement);

declare global {
  interface HTMLElementTagNameMap {
    'motion-futures': MotionFuturesElement;
  }
}
