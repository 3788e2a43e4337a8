// The bring-your-own guide page (bring-your-own.html): docs/BRING_YOUR_OWN.md, bundled at build time so
// the page works offline like the others, shown through markdown.ts. Each joint map example can be
// saved as a file to drop beside a take. The import panel's messages link here (ui/guide-link.ts).
import '../explainer/page.css';
import './guide.css';
import GUIDE from '../../../docs/BRING_YOUR_OWN.md?raw';
import { el } from '../ui/dom';
import { parseInline, parseMarkdown, type Block, type Inline } from './markdown';

// Only links that stay on the page or the site, or go to the web; anything else is shown as text.
const SAFE_HREF = /^(#|\.\/|https?:\/\/)/;

function inline(runs: Inline[]): (Node | string)[] {
  return runs.map((r) => {
    switch (r.kind) {
      case 'text': return r.text;
      case 'code': return el('code', {}, r.text);
      case 'strong': return el('strong', {}, ...inline(r.children));
      case 'link': return SAFE_HREF.test(r.href) ? el('a', { href: r.href }, ...inline(r.children)) : el('span', {}, ...inline(r.children));
    }
  });
}

/** The file name an example map is saved under: its "name" field, else joint-map.json. */
function mapFileName(text: string): string {
  try {
    const name = (JSON.parse(text) as { name?: unknown }).name;
    if (typeof name === 'string' && /^[\w.-]+$/.test(name)) return `${name}.json`;
  } catch { /* a fragment: saved under the general name */ }
  return 'joint-map.json';
}

function save(fileName: string, text: string): void {
  const url = URL.createObjectURL(new Blob([`${text}\n`], { type: 'application/json' }));
  const a = el('a', { href: url, download: fileName, hidden: true });
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 10_000);
}

function block(b: Block): HTMLElement {
  switch (b.kind) {
    case 'heading': {
      const tag = `h${Math.min(b.level, 6)}` as 'h1';
      return el(tag, { id: b.id }, ...inline(parseInline(b.text)));
    }
    case 'paragraph': return el('p', {}, ...inline(parseInline(b.text)));
    case 'list': return el(b.ordered ? 'ol' : 'ul', {}, ...b.items.map((t) => el('li', {}, ...inline(parseInline(t)))));
    case 'code': {
      const pre = el('pre', { tabindex: 0 }, el('code', { class: b.lang ? `language-${b.lang}` : undefined }, b.text));
      if (b.lang !== 'json') return pre;
      const name = mapFileName(b.text);
      const button = el('button', { type: 'button', class: 'save-map', 'data-file': name }, `Save as ${name}`);
      button.addEventListener('click', () => save(name, b.text));
      return el('div', { class: 'example-map', 'data-testid': 'example-map' }, pre, button);
    }
  }
}

const blocks = parseMarkdown(GUIDE);
document.getElementById('guide')!.replaceChildren(...blocks.map(block));
document.body.dataset.guideStatus = 'done';
// the anchor a message linked to exists only now that the text is on the page
if (location.hash) document.getElementById(decodeURIComponent(location.hash.slice(1)))?.scrollIntoView();
