// Loads the clip index and the chosen clip; reports each loaded Motion (or its failure) to the page.
import type { ClipIndex, ClipIndexEntry } from '../contract/types';
import { fetchContract } from '../contract/validate';
import { loadClip, type Motion } from '../motion/clip';
import type { ClipInfo } from './clip-info';
import { mountClipPanel, type ClipPanel } from './clip-panel';
import type { StatusSink } from './dom';
import type { MessageBanner } from './messages';

export interface ClipBrowserOptions {
  /** Site root URL ending in '/'. */
  baseUrl: string;
  list: HTMLElement;
  info: ClipInfo;
  banner: MessageBanner;
  /** Called with each newly loaded clip, or null when the chosen one failed. */
  onMotion(motion: Motion | null, entry: ClipIndexEntry | null): void;
  /** The clip asked for (a link's); without one, the index's `default` history, then `fallbackClip`. */
  defaultClip?: string;
  /** Used when the index names no default (indexes written before it had one). */
  fallbackClip?: string;
  /** Receives currentClip and clipStatus. */
  status: StatusSink;
}

export type ClipStatus = 'loading' | 'ready' | 'error';

export class ClipBrowser {
  index: ClipIndex | null = null;
  current: Motion | null = null;
  private panel: ClipPanel | null = null;
  private request = 0;

  constructor(private readonly opts: ClipBrowserOptions) {}

  async start(): Promise<void> {
    const { list, banner } = this.opts;
    list.textContent = 'Loading clips…';
    const url = `${this.opts.baseUrl}clips/index.json`;
    try {
      this.index = await fetchContract(url, 'clip-index');
    } catch (err) {
      list.textContent = 'The clip list could not be loaded.';
      banner.error(err, 'clip-index');
      this.setStatus(null, 'error');
      return;
    }
    const clips = this.index.clips;
    this.panel = mountClipPanel(list, clips, (entry) => { void this.select(entry); }, this.index.notes);
    const named = (name?: string) => (name ? clips.find((c) => c.name === name) : undefined);
    const first = named(this.opts.defaultClip) ?? this.defaultEntry() ?? clips[0];
    if (first) await this.select(first);
  }

  /** The history the site opens on: the index's `default`, else the fallback, else the first test clip. */
  defaultEntry(): ClipIndexEntry | undefined {
    const clips = this.index?.clips ?? [];
    const named = (name?: string) => (name ? clips.find((c) => c.name === name) : undefined);
    return named(this.index?.default?.clip) ?? named(this.opts.fallbackClip) ?? clips.find((c) => c.role === 'test');
  }

  /** The first history frame the index's `default` names for this clip, if it names one. */
  defaultStart(name: string): number | undefined {
    const d = this.index?.default;
    return d && d.clip === name ? d.start : undefined;
  }

  /** The index entry of a clip by name. */
  entry(name: string): ClipIndexEntry | undefined {
    return this.index?.clips.find((c) => c.name === name);
  }

  async select(entry: ClipIndexEntry): Promise<void> {
    const ticket = ++this.request;
    this.panel?.select(entry.name);
    this.opts.info.status(`Loading ${entry.name}…`);
    this.setStatus(entry.name, 'loading');
    let motion: Motion;
    try {
      motion = await loadClip(this.opts.baseUrl, entry);
    } catch (err) {
      if (ticket !== this.request) return; // a later choice superseded this one
      this.current = null;
      this.opts.banner.error(err, 'clip');
      this.opts.info.status(`${entry.name} could not be loaded; pick another clip.`);
      this.setStatus(entry.name, 'error');
      this.opts.onMotion(null, entry);
      return;
    }
    if (ticket !== this.request) return;
    this.current = motion;
    this.opts.banner.clear('clip');
    this.opts.info.show(motion, entry, this.index?.notes?.[entry.action]);
    try {
      this.opts.onMotion(motion, entry);
    } catch (err) {
      this.opts.banner.error(err, 'clip');
      this.setStatus(entry.name, 'error');
      return;
    }
    this.setStatus(entry.name, 'ready');
  }

  /** Exposed on the instance root so tests and styles can see what is on stage. */
  private setStatus(name: string | null, status: ClipStatus): void {
    this.opts.status('currentClip', name ?? undefined);
    this.opts.status('clipStatus', status);
  }
}
