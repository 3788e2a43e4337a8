// Host pages for the embed tests: what a widget meets on someone else's site, each long enough that
// the page scrolls and with html { font-size: 62.5% } as many sites set for 1rem = 10px. A project
// page as the template most vision papers use builds it (a CSS reset, a Bulma-like stylesheet), and a
// minimal blog (one narrow serif column of long paragraphs, no reset, no framework).

/** A CSS reset of the usual kind (everything zeroed, box-sizing for all). */
const RESET = `
html, body, div, span, h1, h2, h3, p, a, img, section, figure, figcaption, button, input, select, ul, li {
  margin: 0; padding: 0; border: 0; font-size: 100%; font: inherit; vertical-align: baseline; }
*, *::before, *::after { box-sizing: inherit; }
html { box-sizing: border-box; -webkit-text-size-adjust: 100%; }
ul { list-style: none; }
button { background: none; cursor: pointer; }`;

/** The parts of Bulma a project page uses: sections, containers, columns, titles, buttons. */
const BULMA_LIKE = `
html { font-size: 62.5%; background: #fff; overflow-y: scroll; }
body { font-family: 'Noto Sans', sans-serif; font-size: 1.6rem; line-height: 1.5; color: #4a4a4a; }
.section { padding: 4.8rem 2.4rem; }
.container { margin: 0 auto; max-width: 96rem; position: relative; }
.columns { display: flex; gap: 2.4rem; }
.column { flex: 1 1 0; min-width: 0; }
.column.is-narrow { flex: none; width: 320px; }
.title { font-size: 3.2rem; font-weight: 600; color: #363636; margin-bottom: 1.6rem; }
.subtitle { font-size: 2rem; color: #4a4a4a; margin-bottom: 2.4rem; }
.content p { margin-bottom: 1.6rem; }
.button { display: inline-flex; padding: 0.8rem 1.6rem; border: 1px solid #dbdbdb; border-radius: 0.4rem; background: hotpink; color: #363636; }
.has-text-centered { text-align: center; }
@media (max-width: 768px) { .columns { display: block; } .column.is-narrow { width: auto; } .section { padding: 2.4rem 1.6rem; } }`;

const LOREM = 'We predict many plausible futures of a human motion from a short history, and show them as skeletons. '
  + 'Each sample is drawn from the model; the ground truth is what the person did. ';

/** Paragraphs of filler, so the page scrolls past the widgets. */
const filler = (n: number, long = 3) => Array.from({ length: n }, () => `<p>${LOREM.repeat(long)}</p>`).join('\n');

/** What a host page holds, wherever it puts it. */
export interface HostPageParts {
  /** The script include and widgets in the teaser section (the blog: a figure in the text). */
  teaser: string;
  /** Widgets further down, in a 320 px column beside text. */
  results: string;
}

export function projectPage(parts: HostPageParts): string {
  return `<!doctype html>
<html lang="en"><head><meta charset="utf-8"><meta name="viewport" content="width=device-width, initial-scale=1">
<title>Motion Futures: a project page</title><style>${RESET}${BULMA_LIKE}</style></head>
<body>
<section class="section"><div class="container has-text-centered">
  <h1 class="title">Stochastic Futures of Human Motion</h1>
  <p class="subtitle">A. Author, B. Author · Some Conference 2026</p>
  <p><a class="button" href="#paper">Paper</a> <a class="button" href="#code">Code</a></p>
</div></section>
<section class="section"><div class="container">
  ${parts.teaser}
  <div class="content">${filler(3)}</div>
</div></section>
<section class="section"><div class="container"><h2 class="title">Results</h2>
  <div class="columns"><div class="column content">${filler(2)}</div>
  <div class="column is-narrow">${parts.results}</div></div>
  <div class="content">${filler(6)}</div>
</div></section>
</body></html>`;
}

/** A minimal blog's stylesheet: a narrow column, a serif body font, a 320 px figure floated beside the text. */
const BLOG = `
html { font-size: 62.5%; }
body { margin: 0; background: #fdfdf8; color: #222; font: 1.9rem/1.65 Georgia, 'DejaVu Serif', serif; }
main { max-width: 64rem; margin: 0 auto; padding: 3.2rem 1.6rem; }
h1 { font-size: 3.4rem; line-height: 1.2; margin: 0 0 0.8rem; }
.byline { color: #777; font-style: italic; }
p { margin: 0 0 1.6rem; }
a { color: #8a2be2; }
figure { margin: 2.4rem 0; }
figcaption { font-size: 1.5rem; color: #666; margin-top: 0.6rem; }
.aside { float: right; width: 320px; margin: 0 0 1.6rem 2.4rem; }
@media (max-width: 600px) { .aside { float: none; margin: 0 auto 1.6rem; } }`;

export function blogPage(parts: HostPageParts): string {
  return `<!doctype html>
<html lang="en"><head><meta charset="utf-8"><meta name="viewport" content="width=device-width, initial-scale=1">
<title>Notes: predicting human motion</title><style>${BLOG}</style></head>
<body><main>
  <h1>What a motion model thinks happens next</h1>
  <p class="byline">Posted by someone who read the paper · <a href="#comments">3 comments</a></p>
  ${filler(3, 5)}
  <figure>${parts.teaser}<figcaption>Five futures from the same history; green is what the person did.</figcaption></figure>
  ${filler(2, 5)}
  <div class="aside">${parts.results}</div>
  ${filler(8, 5)}
</main></body></html>`;
}
