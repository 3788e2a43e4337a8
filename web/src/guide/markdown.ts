// The little Markdown docs/BRING_YOUR_OWN.md is written in, read into blocks and inline runs for the
// served guide (bring-your-own.html): headings (with GitHub's anchors, so "#joint-maps" links work
// on both), paragraphs, fenced code, "-" and "1." lists with indented continuation lines, `code`,
// **bold** and [links](url). Pure, so tests/web/import-guide.test.ts reads the real document; the
// page builds DOM nodes from it (never innerHTML), so nothing in the text can run as markup.

export type Inline =
  | { kind: 'text'; text: string }
  | { kind: 'code'; text: string }
  | { kind: 'strong'; children: Inline[] }
  | { kind: 'link'; href: string; children: Inline[] };

export type Block =
  | { kind: 'heading'; level: number; text: string; id: string }
  | { kind: 'paragraph'; text: string }
  | { kind: 'code'; lang: string; text: string }
  | { kind: 'list'; ordered: boolean; items: string[] };

/** GitHub's heading anchor: lower case, punctuation dropped, spaces to hyphens. */
export function slug(text: string): string {
  return text.toLowerCase().replace(/[`*]/g, '').replace(/[^\p{L}\p{N}\s_-]/gu, '').trim().replace(/\s/g, '-');
}

const ITEM = /^(\s*)(-|\d+\.)\s+(.*)$/;
const FENCE = /^```\s*([\w-]*)\s*$/;
const HEADING = /^(#{1,6})\s+(.*?)\s*#*\s*$/;

export function parseMarkdown(source: string): Block[] {
  const lines = source.replace(/\r\n?/g, '\n').split('\n');
  const blocks: Block[] = [];
  const ids = new Map<string, number>();
  let i = 0;
  while (i < lines.length) {
    const line = lines[i];
    if (!line.trim()) { i++; continue; }
    const fence = FENCE.exec(line);
    if (fence) {
      const body: string[] = [];
      for (i++; i < lines.length && !/^```\s*$/.test(lines[i]); i++) body.push(lines[i]);
      i++; // the closing fence (or the end of the text)
      blocks.push({ kind: 'code', lang: fence[1], text: body.join('\n') });
      continue;
    }
    const heading = HEADING.exec(line);
    if (heading) {
      const base = slug(heading[2]);
      const n = ids.get(base) ?? 0;
      ids.set(base, n + 1);
      blocks.push({ kind: 'heading', level: heading[1].length, text: heading[2], id: n ? `${base}-${n}` : base });
      i++;
      continue;
    }
    const item = ITEM.exec(line);
    if (item) {
      const ordered = item[2] !== '-';
      const items: string[] = [];
      while (i < lines.length) {
        const m = ITEM.exec(lines[i]);
        if (m && (m[2] !== '-') === ordered && m[1].length <= item[1].length) {
          items.push(m[3]);
          i++;
        } else if (lines[i].trim() && /^\s/.test(lines[i]) && items.length) {
          items[items.length - 1] += ` ${lines[i].trim()}`; // an indented continuation line
          i++;
        } else if (!lines[i].trim() && i + 1 < lines.length && ITEM.exec(lines[i + 1])) {
          i++; // a blank line between two items of one list
        } else break;
      }
      blocks.push({ kind: 'list', ordered, items });
      continue;
    }
    const para: string[] = [];
    while (i < lines.length && lines[i].trim() && !FENCE.test(lines[i]) && !HEADING.test(lines[i]) && !ITEM.test(lines[i])) {
      para.push(lines[i].trim());
      i++;
    }
    blocks.push({ kind: 'paragraph', text: para.join(' ') });
  }
  return blocks;
}

/** Inline runs: `code` first (nothing inside it is markup), then **bold** and [text](href). */
export function parseInline(text: string): Inline[] {
  const out: Inline[] = [];
  let rest = text;
  const TOKEN = /`([^`]+)`|\*\*(.+?)\*\*|\[([^\]]+)\]\(([^)\s]+)\)/;
  while (rest) {
    const m = TOKEN.exec(rest);
    if (!m) { out.push({ kind: 'text', text: rest }); break; }
    if (m.index) out.push({ kind: 'text', text: rest.slice(0, m.index) });
    if (m[1] !== undefined) out.push({ kind: 'code', text: m[1] });
    else if (m[2] !== undefined) out.push({ kind: 'strong', children: parseInline(m[2]) });
    else out.push({ kind: 'link', href: m[4], children: parseInline(m[3]) });
    rest = rest.slice(m.index + m[0].length);
  }
  return out;
}

/** The text of every ```json block, in order (the guide's example joint maps). */
export function jsonBlocks(blocks: readonly Block[]): string[] {
  return blocks.filter((b): b is Extract<Block, { kind: 'code' }> => b.kind === 'code' && b.lang === 'json').map((b) => b.text);
}
