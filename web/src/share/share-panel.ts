// The Share section: "Copy link" and "Copy embed snippet", the link itself to select by hand,
// and why there is no link when the history cannot be linked (a dropped file).
import { el } from '../ui/dom';

export type Shareable =
  | { link: string; snippet: string; iframe: string }
  | { unlinkable: string };

export interface SharePanel {
  update(s: Shareable): void;
}

async function copyText(text: string, field: HTMLInputElement | HTMLTextAreaElement): Promise<boolean> {
  try {
    if (!navigator.clipboard?.writeText) throw new Error('no clipboard API');
    await navigator.clipboard.writeText(text);
    return true;
  } catch {
    // Insecure origins and iframes without clipboard-write: select the text for Ctrl+C instead.
    field.hidden = false;
    field.focus();
    field.select();
    try { return document.execCommand('copy'); } catch { return false; }
  }
}

export function mountSharePanel(container: HTMLElement): SharePanel {
  const linkField = el('input', { type: 'text', readonly: true, class: 'share-link', 'aria-label': 'Link to this view', 'data-testid': 'share-link' });
  const snippetField = el('textarea', { readonly: true, rows: 4, class: 'share-snippet', 'aria-label': 'Embed snippet', 'data-testid': 'share-snippet' });
  const iframeField = el('textarea', { readonly: true, rows: 3, class: 'share-snippet', 'aria-label': 'Iframe snippet', 'data-testid': 'share-iframe' });
  const copyLink = el('button', { type: 'button', class: 'text-button', 'data-testid': 'copy-link' }, 'Copy link');
  const copySnippet = el('button', { type: 'button', class: 'text-button', 'data-testid': 'copy-snippet' }, 'Copy embed snippet');
  const status = el('p', { class: 'muted share-status', role: 'status', 'aria-live': 'polite', 'data-testid': 'share-status' });
  let current: Shareable = { unlinkable: 'Nothing to share yet.' };

  const say = (text: string) => { status.textContent = text; };
  copyLink.addEventListener('click', async () => {
    if ('unlinkable' in current) { say(current.unlinkable); return; }
    say(await copyText(current.link, linkField) ? 'Link copied.' : 'The link is selected above: copy it with Ctrl+C.');
  });
  copySnippet.addEventListener('click', async () => {
    if ('unlinkable' in current) { say(current.unlinkable); return; }
    say(await copyText(current.snippet, snippetField) ? 'Embed snippet copied: paste it into a project page.' : 'The snippet is selected below: copy it with Ctrl+C.');
  });

  container.replaceChildren(
    el('div', { class: 'share-row' }, copyLink, copySnippet),
    linkField, status,
    el('details', { class: 'share-details' }, el('summary', {}, 'Embed code'),
      el('p', { class: 'muted' }, 'A custom element (one script, one tag):'), snippetField,
      el('p', { class: 'muted' }, 'Or an iframe:'), iframeField),
  );
  return {
    update(s) {
      current = s;
      const off = 'unlinkable' in s;
      for (const b of [copyLink, copySnippet]) {
        b.dataset.unlinkable = String(off); // dimmed, but still clickable, so it can say why
        b.title = off ? s.unlinkable : '';
      }
      linkField.value = off ? '' : s.link;
      snippetField.value = off ? '' : s.snippet;
      iframeField.value = off ? '' : s.iframe;
      if (off) say(s.unlinkable);
      else if (linkField.dataset.shown !== s.link) say(''); // an earlier "copied" was for another link
      linkField.dataset.shown = off ? '' : s.link;
    },
  };
}
