// What the figures read: the manifest (through the page-wide shared loader), clips on demand,
// and the graph worker, created the first time a figure needs a model.
import type { ClipIndex, Manifest, ModelEntry } from '../contract/types';
import { fetchContract } from '../contract/validate';
import { sharedManifest } from '../embed/shared';
import { loadClip, type Motion } from '../motion/clip';
import type { FileLoader } from '../predictor/types';
import { GraphClient } from './graph-client';

export interface ExplainerData {
  /** The site root URL, ending in '/'. */
  root: string;
  index: ClipIndex;
  /** The first served clip of an action (e.g. the first-listed walk), or of any action when none. */
  firstOf(action: string): string;
  /** The clip the site opens on (the index's default held-out take), else the first test clip. */
  defaultClip(): string;
  manifest: Manifest | null;
  /** Why the manifest did not load (null when it did). */
  manifestProblem: string | null;
  clip(name: string): Promise<Motion>;
  /** The served model of a method, or null. */
  model(method: ModelEntry['method']): ModelEntry | null;
  /** The graph worker; throws ModelLoadError without WebAssembly. */
  graphs(): GraphClient;
  loadFile: FileLoader;
}

export async function loadExplainerData(root: string): Promise<ExplainerData> {
  const index = await fetchContract(`${root}clips/index.json`, 'clip-index');
  let manifest: Manifest | null = null;
  let manifestProblem: string | null = null;
  try {
    manifest = await sharedManifest(root);
  } catch (err) {
    manifestProblem = (err as Error).message;
  }
  const clips = new Map<string, Promise<Motion>>();
  let graphs: GraphClient | null = null;
  return {
    root, index, manifest, manifestProblem,
    clip(name) {
      let c = clips.get(name);
      if (!c) {
        const entry = index.clips.find((e) => e.name === name);
        if (!entry) return Promise.reject(new Error(`this site has no clip '${name}'`));
        c = loadClip(root, entry);
        c.catch(() => clips.delete(name));
        clips.set(name, c);
      }
      return c;
    },
    firstOf: (action) => (index.clips.find((c) => c.action === action) ?? index.clips[0]).name,
    defaultClip: () => index.default?.clip ?? (index.clips.find((c) => c.role === 'test') ?? index.clips[0]).name,
    model: (method) => manifest?.models.find((m) => m.method === method) ?? null,
    graphs() {
      if (!manifest) throw new Error(`the models did not load: ${manifestProblem}`);
      graphs ??= new GraphClient(root, manifest);
      return graphs;
    },
    async loadFile(file) {
      const res = await fetch(`${root}models/${file}`);
      if (!res.ok) throw new Error(`models/${file} could not be loaded (HTTP ${res.status})`);
      return new Uint8Array(await res.arrayBuffer());
    },
  };
}
