// A widget: the shadow root, its styles and markup, and one app instance inside. Styles stay in
// the shadow root, so the host page's CSS and the widget's never meet.
import baseCss from '../styles.css?inline';
import { startApp, type App, type ViewOptions } from '../ui/app';
import { el } from '../ui/dom';
import { cooperativeGestures } from './gestures';
import { mountMiniLegend } from './legend';
import { SITE_ROOT } from './site';
import { pauseWhileUnseen } from './visibility';
import widgetCss from './widget.css?inline';

export type Theme = 'auto' | 'light' | 'dark';
const sheets = new Map<Theme, CSSStyleSheet[]>();

/** The root font size styles.css gives the page (its :root rule), in px. */
const ROOT_PX = Number(/:root\s*\{[^}]*?font-size:\s*([\d.]+)px/.exec(baseCss)?.[1] ?? 15);

/**
 * styles.css is written for a document; in a shadow root the document's :root is the host. Its rem
 * would still follow the host page's root font size (8.5 px under html { font-size: 62.5% }), so
 * they become px here. The theme picks the dark rules always (dark), never (light) or with the
 * reader's system (auto).
 */
export function shadowCss(css: string, theme: Theme): string {
  let out = css.replace(/:root\b/g, ':host')
    .replace(/(\d*\.?\d+)rem\b/g, (_, n: string) => `${Number((Number(n) * ROOT_PX).toFixed(2))}px`);
  if (theme !== 'auto') {
    out = out.replace(/@media\s*\(prefers-color-scheme:\s*dark\)/g, theme === 'dark' ? '@media all' : '@media not all')
      + `\n:host { color-scheme: ${theme}; }`;
  }
  return out;
}

/** Constructed once per page and theme, and adopted by every instance. */
function styleSheets(theme: Theme): CSSStyleSheet[] {
  let found = sheets.get(theme);
  if (!found) {
    found = [shadowCss(baseCss, theme), shadowCss(widgetCss, theme)].map((text) => {
      const sheet = new CSSStyleSheet();
      sheet.replaceSync(text);
      return sheet;
    });
    sheets.set(theme, found);
  }
  return found;
}

const converted = new Map<Theme, WeakMap<CSSStyleSheet, CSSStyleSheet>>();

/** Sheets a feature adopted into the root itself (ui/stage-view.ts), in rem: the same px copy. */
function ownSizes(root: ShadowRoot, theme: Theme): void {
  const mine = styleSheets(theme);
  let copies = converted.get(theme);
  if (!copies) { copies = new WeakMap(); converted.set(theme, copies); }
  const done = copies;
  root.adoptedStyleSheets = root.adoptedStyleSheets.map((sheet) => {
    if (mine.includes(sheet)) return sheet;
    let copy = done.get(sheet);
    if (!copy) {
      const text = [...sheet.cssRules].map((r) => r.cssText).join('\n');
      if (!/\d\s*rem\b/.test(text)) return sheet;
      copy = new CSSStyleSheet();
      copy.replaceSync(shadowCss(text, theme));
      done.set(sheet, copy);
    }
    return copy;
  });
}

export interface WidgetOptions {
  view: ViewOptions;
  link: [string, string][];
  /** Page mode: the page URL's query to keep up to date (view options that came with it stay). */
  onLink?(search: string | null): void;
  /** light, dark, or auto (the reader's system). */
  theme: Theme;
  /** On someone else's page (not the site's own index.html): the page scrolls over the stage, the
   *  full controls fit the element, and playback pauses while unseen. */
  embedded: boolean;
}

export function mountWidget(host: HTMLElement, options: WidgetOptions): App {
  const root = host.shadowRoot ?? host.attachShadow({ mode: 'open' });
  root.adoptedStyleSheets = styleSheets(options.theme);
  const messages = el('div', { id: 'messages', class: 'messages', role: 'region', 'aria-label': 'Messages' });
  const viewer = el('div', { id: 'viewer', class: 'viewer' }, el('p', { class: 'viewer-notice' }, 'Loading the viewer…'));
  const notice = el('div', { class: 'stage-notice' });
  const gestureHint = el('p', { class: 'gesture-hint', 'aria-hidden': 'true', hidden: true });
  const toolbar = el('div', { class: 'stage-toolbar-slot' });
  const playback = el('div', { id: 'playback', class: 'playback' });
  // the minimal widget's key to the figures (the full controls have the toolbar's legend)
  const legend = options.view.controls === 'minimal' ? el('div', { class: 'mini-legend-slot' }) : null;
  const shownLine = el('div', { class: 'stage-status-slot' });
  const bar = el('div', { class: 'mini-bar' });
  const panel = el('aside', { id: 'panel', class: 'panel', 'aria-label': 'Controls' });
  // A narrow embed with the full controls keeps the panel behind this button (widget.css).
  const panelToggle = el('button', { type: 'button', class: 'text-button panel-toggle', 'aria-controls': 'panel', 'aria-expanded': 'false' }, 'Controls');
  const toggleRow = el('div', { class: 'panel-toggle-row' }, panelToggle);
  const hint = el('p', { class: 'hint muted' }, 'Space play/pause · ←/→ frame · [ ] speed · L layout · P predict · 1–9 sample · click a figure to select it · S picture · R record');
  // The stage frame holds the viewer and what lies over it (messages, the out-of-range notice), so
  // neither ever moves or resizes the stage.
  root.replaceChildren(el('div', { class: 'mf-widget', 'data-controls': options.view.controls, 'data-embedded': String(options.embedded) },
    el('div', { class: 'app' },
      el('section', { class: 'stage-area', 'aria-label': '3D viewer' },
        toolbar, el('div', { class: 'stage-frame' }, viewer, messages, notice, gestureHint), legend, playback, shownLine, bar, hint, toggleRow),
      panel)));
  const widget = root.firstElementChild as HTMLElement;
  panelToggle.addEventListener('click', () => {
    const open = widget.dataset.panel !== 'open';
    widget.dataset.panel = open ? 'open' : 'closed';
    panelToggle.setAttribute('aria-expanded', String(open));
    panelToggle.textContent = open ? 'Close controls' : 'Controls';
  });

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
  const app = startApp({ host, messages, viewer, playback, panel, bar, toolbar, notice, status: shownLine }, {
    siteRoot: SITE_ROOT, view: options.view, link: options.link, status, onLink: options.onLink,
  });
  ownSizes(root, options.theme);
  if (legend) mountMiniLegend(legend, app.view);
  // The minimal widget and a narrow embed keep the view's summary for screen readers only
  // (aria-describedby of the canvas, widget.css): no tab stop on a 1 px box.
  if (options.view.controls === 'minimal' || options.embedded) root.querySelector('.view-summary')?.setAttribute('tabindex', '-1');
  if (options.embedded) {
    cooperativeGestures(host, viewer, gestureHint);
    pauseWhileUnseen(host, app.player);
  }
  return app;
}
