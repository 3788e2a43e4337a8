// "Seeing what matters", over the stage's bottom-right corner: the camera presets (front, side, top,
// follow one figure), a toggle that highlights the sample closest to the ground truth (with its
// per-joint error; in compare mode one in each model's row), and one that hides the ground truth. It
// also carries the styles of what the viewer adds to each figure's label (the current action, the
// "stopped" and "closest" badges), so the parts of this feature live together. Placed absolutely: nothing here moves or resizes the stage.
import { CAMERA_PRESETS, type CameraPreset, type SkeletonView } from '../viewer/viewer';
import { el } from './dom';

/** What the bar has chosen, as a permalink keeps it (share/url-state.ts). */
export interface StageChoices {
  camera: CameraPreset;
  closest: boolean;
  truth: boolean;
}

export interface StageView {
  root: HTMLElement;
  /** Re-read the view (best sample, whether there is a truth); the view calls it after new tracks. */
  refresh(): void;
  choices(): StageChoices;
  /** Set what a link asks for (each part optional). */
  set(c: Partial<StageChoices>): void;
}

const PRESET_LABELS: Record<CameraPreset, string> = {
  auto: 'Camera: fit all', front: 'Camera: front', side: 'Camera: side', top: 'Camera: top', follow: 'Camera: follow one',
};

/** Stage width (CSS px) below which the bar uses its short labels. */
const COMPACT_BELOW = 560;

// px, not rem: in an embed the host's root font size must not resize the bar (html { font-size: 62.5% }).
const CSS = `
.stage-view { position: absolute; right: 8px; bottom: 8px; z-index: 2; display: flex; gap: 5px; align-items: center;
  flex-wrap: wrap; justify-content: flex-end; max-width: calc(100% - 16px); font: 500 13px/1.2 system-ui, sans-serif; }
.stage-view select, .stage-view button { font: inherit; color: var(--fg); background: color-mix(in srgb, var(--panel-bg) 88%, transparent);
  border: 1px solid var(--border); border-radius: 6px; padding: 4px 7px; cursor: pointer; min-height: 30px; }
.stage-view button[aria-pressed='true'] { border-color: var(--accent); box-shadow: inset 0 0 0 1px var(--accent); font-weight: 650; }
.stage-view button:disabled { cursor: default; }
.figure-action { font-weight: 500; }
.figure-badge b { font-weight: 700; padding: 0 5px; border-radius: 3px; }
.figure-stopped b { background: var(--fg); color: var(--panel-bg); }
.figure-best b { box-shadow: inset 0 0 0 2px var(--figure-colour); }
/* on the scrubber: where the next action starts, above the track; stops and cuts stay below it */
.scrubber-action { top: 0; bottom: auto; height: 40%; width: 2px; margin-left: -1px; }
.figure-label-best { box-shadow: 0 0 0 2px var(--figure-colour), 0 0 0 4px color-mix(in srgb, var(--figure-colour) 35%, transparent); }
`;

let sheet: CSSStyleSheet | null = null;

/** Adopt this feature's styles into the document or shadow root that holds `node` (once per root). */
function adoptStyles(node: Node): void {
  const root = node.getRootNode() as Document | ShadowRoot;
  if (!('adoptedStyleSheets' in root) || typeof CSSStyleSheet === 'undefined') return;
  try {
    if (!sheet) { sheet = new CSSStyleSheet(); sheet.replaceSync(CSS); }
    if (!root.adoptedStyleSheets.includes(sheet)) root.adoptedStyleSheets = [...root.adoptedStyleSheets, sheet];
  } catch {
    // a browser without constructable sheets still works, unstyled
  }
}

export function mountStageView(viewer: HTMLElement, view: SkeletonView, onChange: () => void = () => {}): StageView {
  const camera = el('select', { class: 'camera-preset', 'aria-label': 'Camera', 'data-testid': 'camera-preset',
    title: 'Where the camera looks from; "follow one" travels with the selected sample (else the closest, else #1)' },
  ...CAMERA_PRESETS.map((p) => el('option', { value: p }, PRESET_LABELS[p])));
  camera.value = view.camera;
  const best = el('button', { type: 'button', class: 'best-toggle', 'aria-pressed': 'false', 'data-testid': 'best-toggle' });
  const truth = el('button', { type: 'button', class: 'truth-toggle', 'aria-pressed': 'true', 'data-testid': 'truth-toggle',
    title: 'Show or hide the ground truth (what the clip really does next)' }, 'Ground truth');
  const root = el('div', { class: 'stage-view', role: 'group', 'aria-label': 'What to see', 'data-testid': 'stage-view' }, camera, best, truth);
  viewer.append(root);
  adoptStyles(root);

  let bestOn = false;
  let truthOn = true;
  /** A narrow stage (a phone, a small embed) gets the short labels, so the bar keeps to one line. */
  let compact = false;
  const refresh = () => {
    // one per row: the page's model alone, or each compared model (its row's own truth)
    const rows = view.bestRows();
    const b = rows[0] ?? null;
    const named = rows.length > 1;
    const each = rows.map((r) => `${named ? `${r.groupLabel ?? `row ${(r.group ?? 0) + 1}`} ` : ''}#${r.sample + 1} · ${r.cm.toFixed(1)} cm`);
    const name = compact ? 'Closest' : 'Closest to truth';
    best.disabled = !b;
    best.setAttribute('aria-pressed', String(bestOn && Boolean(b)));
    // a narrow stage has no room for several rows' numbers: the labels on stage carry them
    best.textContent = bestOn && b && !(compact && named) ? `${name}: ${each.join(', ')}` : name;
    best.title = b
      ? `Highlight the sample closest to the ground truth${named ? ' in each compared model\'s row' : ''}: the smallest mean per-joint distance to it (world frame), `
        + `over the ${b.frames} frames of ground truth that follow the history${named ? ` (${each.join('; ')})` : ''}`
      : 'Needs futures and the ground truth that follows the history';
    const own = view.best(); // the page's model's row
    if (own) best.dataset.sample = String(own.sample); else delete best.dataset.sample;
    if (b) best.dataset.rows = rows.map((r) => `${r.group ?? 0}:${r.sample}`).join(','); else delete best.dataset.rows;
    // there is a ground truth to hide only with futures and a clip that goes on (best() needs both)
    truth.disabled = truthOn && !b;
    truth.setAttribute('aria-pressed', String(truthOn));
    truth.textContent = compact ? (truthOn ? 'Truth: shown' : 'Truth: hidden') : truthOn ? 'Ground truth: shown' : 'Ground truth: hidden';
    for (const o of camera.options) o.textContent = compact ? PRESET_LABELS[o.value as CameraPreset].replace('Camera: ', '') : PRESET_LABELS[o.value as CameraPreset];
  };
  if (typeof ResizeObserver !== 'undefined') {
    new ResizeObserver(() => {
      const narrow = viewer.clientWidth > 0 && viewer.clientWidth < COMPACT_BELOW;
      if (narrow !== compact) { compact = narrow; refresh(); }
    }).observe(viewer);
  }
  camera.addEventListener('change', () => { view.setCamera(camera.value as CameraPreset); onChange(); });
  best.addEventListener('click', () => { bestOn = !bestOn; view.setBestShown(bestOn); refresh(); onChange(); });
  truth.addEventListener('click', () => { truthOn = !truthOn; view.setTruthShown(truthOn); refresh(); onChange(); });
  view.onTracks(refresh);
  refresh();
  return {
    root, refresh,
    choices: () => ({ camera: camera.value as CameraPreset, closest: bestOn, truth: truthOn }),
    set(c) {
      if (c.camera !== undefined) { camera.value = c.camera; view.setCamera(c.camera); }
      if (c.closest !== undefined) { bestOn = c.closest; view.setBestShown(bestOn); }
      if (c.truth !== undefined) { truthOn = c.truth; view.setTruthShown(truthOn); }
      refresh();
    },
  };
}
