// The side panel is a stack of independent sections; each feature mounts into its own.

export interface PanelSection {
  root: HTMLElement;
  /** Where the section's content goes. */
  body: HTMLElement;
}

/** Add a titled section to the panel (appended, or placed before the section with id `before`). */
export function addSection(panel: HTMLElement, id: string, title: string, before?: string): PanelSection {
  const root = document.createElement('section');
  root.className = 'panel-section';
  root.dataset.section = id;
  const heading = document.createElement('h2');
  heading.id = `section-${id}-title`;
  heading.textContent = title;
  root.setAttribute('aria-labelledby', heading.id);
  const body = document.createElement('div');
  body.className = 'panel-section-body';
  root.append(heading, body);
  const next = before ? panel.querySelector(`:scope > [data-section="${before}"]`) : null;
  panel.insertBefore(root, next);
  return { root, body };
}
