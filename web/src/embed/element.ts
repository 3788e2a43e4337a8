// <motion-futures>: the widget as a custom element, the one script a project page includes.
//   <script type="module" src="SITE/assets/motion-futures.js"></script>
//   <motion-futures model="wat-rnn" clip="cmu_10_04" seed="3" k="5" autoplay></motion-futures>
// Attributes are read once, when the element connects. With the `page` attribute the element is
// the whole page (index.html, embed.html): the page URL overrides the attributes and is kept up
// to date as a permalink, and keys act with nothing focused. index.html (`page`) is the site itself
// and works offline; embed.html (`page="embed"`, for iframes) and a widget on a host page are
// embeds: they register no service worker (nothing is precached on the host's behalf) unless the
// host asks with `offline` (embed.html?offline=1), keep the page's scrolling, and pause unseen.
import type { App } from '../ui/app';
import { registerServiceWorker } from './offline';
import { attributeParams, linkParams, offlineAsked, theme, viewOptions, viewQuery } from './options';
import { mountWidget } from './widget';

export class MotionFuturesElement extends HTMLElement {
  /** The running instance, once connected. */
  app: App | null = null;

  connectedCallback(): void {
    if (this.app) return;
    const page = this.hasAttribute('page');
    const embedded = !page || this.getAttribute('page') === 'embed';
    const params = attributeParams(this);
    if (page) params.push(...new URLSearchParams(location.search));
    try {
      this.app = mountWidget(this, {
        view: viewOptions(params, page),
        link: linkParams(params),
        onLink: page ? (search) => keepPageUrl(search) : undefined,
        theme: theme(params),
        embedded,
      });
      // A widget on a host page never registers: the host page is outside the worker's scope, so
      // it would precache the site for nothing (see offline.ts).
      if (page && (!embedded || offlineAsked(params))) registerServiceWorker(this.app.ready, (s) => this.app?.offline(s), () => this.app?.onStage().source.kind === 'dropped');
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
