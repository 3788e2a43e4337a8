// Inline SVG icons: glyph characters vary by installed fonts, these do not.

const PATHS = {
  play: 'M7 4.5v15l12.5-7.5z',
  pause: 'M6.5 4.5h4v15h-4zM13.5 4.5h4v15h-4z',
  back: 'M5 5h2.5v14H5zM19 5v14L8.5 12z',
  forward: 'M16.5 5H19v14h-2.5zM5 5v14l10.5-7z',
  reset: 'M12 5a7 7 0 1 1-6.7 5H3l3.5-4 3.5 4H7.4A5 5 0 1 0 12 7z',
} as const;

export type IconName = keyof typeof PATHS;

export function icon(name: IconName): SVGSVGElement {
  const svg = document.createElementNS('http://www.w3.org/2000/svg', 'svg');
  svg.setAttribute('viewBox', '0 0 24 24');
  svg.setAttribute('aria-hidden', 'true');
  svg.setAttribute('focusable', 'false');
  svg.classList.add('icon');
  const path = document.createElementNS('http://www.w3.org/2000/svg', 'path');
  path.setAttribute('d', PATHS[name]);
  svg.append(path);
  return svg;
}
