// A widget: the shadow root, its styles and markup, and one app instance inside. Styles stay in
// the shadow root, so the host page's CSS and the widget's never meet.
import baseCss from '../styles.css?inline';
import { startApp, type App, type ViewOptions } from '../ui/app';
import { el } from '../ui/dom';
import { SITE_ROOT } from './site';
import widgetCss from './widget.css?inline';

let sheets: CSSStyleSheet[] | null = null;

/** Constructed once per page and adopted by every instance. */
function styleSheets(): CSSStyleSheet[] {
  if (!sheets) {
    // styles.css is written for a document; in a shadow root the document's :root is the host.
    const base = new CSSStyleSheet();
    base.replaceSync(baseCss.replace(/:root\b/g, ':host'));
    const own = new CSSStyleSheet();
    own.replaceSync(widgetCss);
    sheets = [base, own];
  }
  return sheets;
}

export interface WidgetOptions {
  view: ViewOptions;
  link: [string, string][];
  /** Page mode: the page URL's query to keep up to date (view options that came with it stay). */
  onLink?(search: string | null): void;
}

export function mountWidget(host: HTMLElement, options: WidgetOptions): App {
  const root = host.shadowRoot ?? host.attachShadow({ mode: 'open' });
  root.adoptedStyleSheets = styleSheets();
  const messages = el('div', { id: 'messages', class: 'messages', role: 'region', 'aria-label': 'Messages' });
  const viewer = el('div', { id: 'viewer', class: 'viewer' }, el('p', { class: 'viewer-notice' }, 'Loading the viewer…'));
  const notice = el('div', { class: 'stage-notice' });
  const toolbar = el('div', { class: 'stage-toolbar-slot' });
  const playback = el('div', { id: 'playback', class: 'playback' });
  const shownLine = el('div', { class: 'stage-status-slot' });
  const bar = el('div', { class: 'mini-bar' });
  const panel = el('aside', { id: 'panel', class: 'panel', 'aria-label': 'Controls' });
  const hint = el('p', { class: 'hint muted' }, 'Space play/pause · ←/→ frame · [ ] speed · L layout · P predict · 1–9 sample · click a figure to select it · S picture · R record');
  // The stage frame holds the viewer and what lies over it (messages, the out-of-range notice), so
  // neither ever moves or resizes the stage.
  root.replaceChildren(el('div', { class: 'mf-widget', 'data-controls': options.view.controls },
    el('div', { class: 'app' },
      el('section', { class: 'stage-area', 'aria-label': '3D viewer' },
        toolbar, el('div', { class: 'stage-frame' }, viewer, messages, notice), playback, shownLine, bar, hint),
      panel)));

  // Keys act on the focused instance: make the host focusable, and focus it on a click anywhere
  // inside (the canvas itself takes no focus).
  if (!host.hasAttribute('tabindex')) host.tabIndex = 0;
  if (!host.hasAttribute('role')) host.setAttribute('role', 'group');
  if (!host.hasAttribute('aria-label')) host.setAttribute('aria-label', 'motion-futures: human motion and its predicted futures');
  host.addEventListener('pointerdown', () => {
    if (!host.matches(':focus-within')) host.focus({ preventScroll: true });
  });

  const status = (key: string, value: string | undefined) => {
    for (const target of options.view.page ? [host, document.body] : [host]) {
      if (value === undefined) delete target.dataset[key]; else target.dataset[key] = value;
    }
  };
  return startApp({ host, messages, viewer, playback, panel, bar, toolbar, notice, status: shownLine }, {
    siteRoot: SITE_ROOT, view: options.view, link: options.link, status, onLink: options.onLink,
  });
}
