// Permalink state: any valid state round-trips through the URL, for controls generated the way a
// manifest declares them; bad links are named, not silently replaced.
import { readFileSync } from 'node:fs';
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import type { ControlSpec, Manifest, ModelEntry } from '../../web/src/contract/types';
import { validate } from '../../web/src/contract/validate';
import { MAX_SEED } from '../../web/src/rng/prng';
import { embedSnippet, iframeSnippet, permalink } from '../../web/src/share/links';
import {
  decodeState, DEFAULT_MAX_ACTIONS, encodeSearch, encodeState, shortHash, stageModel, STATE_KEYS, UrlStateError, VIEW_KEYS,
  type ControlValue, type ShareState,
} from '../../web/src/share/url-state';
import { olderRelease, releaseUrl } from '../../web/src/share/versions';

const RESERVED = new Set<string>([...STATE_KEYS, ...VIEW_KEYS]);
const served = validate(JSON.parse(readFileSync(new URL('../../public/models/manifest.json', import.meta.url), 'utf8')), 'manifest', 'manifest.json');

// --- generators: controls as a manifest may declare them, and values the UI can hold -------------
function decimals(step: number): number {
  const t = String(step);
  return t.includes('.') ? t.length - t.indexOf('.') - 1 : 0;
}

const controlId = fc.stringMatching(/^[a-z][a-z0-9_]{0,11}$/).filter((id) => !RESERVED.has(id));
const label = fc.constantFrom('Samples (K)', 'Temperature', 'Sigma scale', 'Refine', 'Horizon (s)');

const intSpec = fc.record({ id: controlId, label, min: fc.integer({ min: -50, max: 50 }), steps: fc.integer({ min: 0, max: 200 }),
  step: fc.integer({ min: 1, max: 5 }) })
  .map(({ steps, ...s }): ControlSpec => ({ ...s, type: 'int', max: s.min + steps * s.step, default: s.min }));
// Manifests write decimal ranges (min 0.05, step 0.05, max 1.5); the browser's range input holds
// min + n * step rounded to those decimals, so the generator does the same.
const onStep = (min: number, step: number, n: number) => Number((min + n * step).toFixed(Math.max(2, decimals(step))));
const steppedNumber = fc.record({ id: controlId, label, min: fc.integer({ min: -500, max: 500 }).map((v) => v / 100),
  steps: fc.integer({ min: 0, max: 400 }), step: fc.constantFrom(0.01, 0.05, 0.1, 0.25, 0.5, 1) })
  .map(({ steps, ...s }): ControlSpec => ({ ...s, type: 'number', max: onStep(s.min, s.step, steps), default: s.min }));
const freeNumber = fc.record({ id: controlId, label, min: fc.double({ min: -1e3, max: 1e3, noNaN: true }).map((v) => v || 0),
  span: fc.double({ min: 0, max: 1e4, noNaN: true }) })
  .map(({ span, ...s }): ControlSpec => ({ ...s, type: 'number', max: s.min + span, default: s.min }));
const boolSpec = fc.record({ id: controlId, label }).map((s): ControlSpec => ({ ...s, type: 'bool', default: false }));
const actionsSpec = fc.record({ id: controlId, label, max_length: fc.option(fc.integer({ min: 1, max: 8 }), { nil: undefined }) })
  .map((s): ControlSpec => ({ ...s, type: 'actions', default: [] }));
const specs = fc.uniqueArray(fc.oneof(intSpec, steppedNumber, freeNumber, boolSpec, actionsSpec), { selector: (s) => s.id, maxLength: 6 });

// Built once: building a stringMatching arbitrary is slow, sampling it is not.
const modelId = fc.stringMatching(/^[a-z0-9][a-z0-9_-]{0,15}$/);
const sha256 = fc.string({ unit: fc.constantFrom(...'0123456789abcdef'), minLength: 64, maxLength: 64 });
const modelEntry = (controls: ControlSpec[]) => fc.record({ id: modelId, hash: sha256 })
  .map(({ id, hash }): ModelEntry => ({
    id, method: 'regression', label: `Model ${id}`, hash: `sha256:${hash}`, graphs: {}, controls,
    params: { history_frames: 10, future_frames: 30 },
  }));

function manifestWith(models: ModelEntry[], actions: string[]): Manifest {
  return { format: 'motion-futures/manifest', version: 1, fps: 30, skeleton: { joints: ['root'], parents: [-1] }, actions, data_hash: `sha256:${'0'.repeat(64)}`, models };
}

/** A value the UI can hold for this control. */
function controlValue(spec: ControlSpec, actions: string[]): fc.Arbitrary<ControlValue> {
  switch (spec.type) {
    case 'bool': return fc.boolean();
    case 'actions': return fc.array(fc.constantFrom(...actions), { maxLength: spec.max_length ?? DEFAULT_MAX_ACTIONS });
    case 'int': return fc.integer({ min: 0, max: (spec.max! - spec.min!) / (spec.step ?? 1) }).map((n) => spec.min! + n * (spec.step ?? 1));
    default:
      if (spec.step) return fc.integer({ min: 0, max: Math.round((spec.max! - spec.min!) / spec.step) }).map((n) => onStep(spec.min!, spec.step!, n));
      return fc.double({ min: spec.min!, max: spec.max!, noNaN: true }).map((v) => v || 0); // the UI never holds -0
  }
}

const version = fc.stringMatching(/^\d{1,2}\.\d{1,2}\.\d{1,2}$/);

function stateFor(manifest: Manifest): fc.Arbitrary<ShareState> {
  return fc.constantFrom(...manifest.models).chain((entry) => fc.record({
    version,
    clip: fc.string({ minLength: 1, maxLength: 24 }),
    start: fc.nat({ max: 100_000 }),
    seed: fc.integer({ min: 0, max: MAX_SEED }),
    controls: fc.record(Object.fromEntries(entry.controls.map((c) => [c.id, controlValue(c, manifest.actions)]))),
    own: fc.boolean(),
  }).map(({ own, ...s }): ShareState => ({ ...s, model: entry.id, hash: shortHash(entry.hash), ...(own ? { feet: 'own' as const } : {}) })));
}

const actionName = fc.stringMatching(/^[a-z][a-z_]{0,9}$/);
const generated = fc.tuple(
  fc.uniqueArray(actionName, { minLength: 1, maxLength: 15 }),
  fc.array(specs, { minLength: 1, maxLength: 3 }),
).chain(([actions, controlLists]) => fc.tuple(...controlLists.map(modelEntry))
  .filter((models) => new Set(models.map((m) => m.id)).size === models.length)
  .map((models) => manifestWith(models, actions)))
  .chain((manifest) => fc.tuple(fc.constant(manifest), stateFor(manifest)));

function roundTrip(state: ShareState, manifest: Manifest) {
  const url = new URL(`https://example.org/sub/path/?${encodeSearch(state, manifest)}`);
  return decodeState(url.searchParams, manifest, state.version, { reportUnknown: true });
}

/** A served model's state at its controls' defaults. */
function atDefaults(entry: ModelEntry): ShareState {
  return { version: '0.1.0', model: entry.id, hash: shortHash(entry.hash), clip: 'cmu_10_04', start: 0, seed: 7,
    controls: Object.fromEntries(entry.controls.map((c) => [c.id, c.default as ControlValue])) };
}

describe('URL state round trip', () => {
  it('any valid state for generated controls comes back unchanged, with no problems', () => {
    fc.assert(fc.property(generated, ([manifest, state]) => {
      const { state: back, problems } = roundTrip(state, manifest);
      expect(problems).toEqual([]);
      expect(back).toEqual(state);
    }), { numRuns: 400 });
  });

  it('any valid state for the served models comes back unchanged', () => {
    fc.assert(fc.property(stateFor(served), (state) => {
      const { state: back, problems } = roundTrip(state, served);
      expect(problems).toEqual([]);
      expect(back).toEqual(state);
    }), { numRuns: 200 });
  });

  it('element attributes carry the same names and values as the URL', () => {
    fc.assert(fc.property(generated, ([manifest, state]) => {
      const snippet = embedSnippet('https://example.org/mf/assets/motion-futures.js', state, manifest, { controls: 'minimal', autoplay: true });
      const tag = /<motion-futures ([^>]*)>/.exec(snippet)![1];
      const unescape = (v: string) => v.replace(/&quot;/g, '"').replace(/&lt;/g, '<').replace(/&gt;/g, '>').replace(/&amp;/g, '&');
      const attrs = [...tag.matchAll(/([a-z][a-z0-9_-]*)(?:="([^"]*)")?/g)].map((m): [string, string] => [m[1], unescape(m[2] ?? '')]);
      const { state: back, problems } = decodeState(attrs.filter(([k]) => k !== 'style'), manifest, state.version);
      expect(problems).toEqual([]);
      expect(back).toEqual(state);
    }), { numRuns: 200 });
  });
});

describe('the feet option', () => {
  const entry = served.models[0];
  it('is written only for the method\'s own root, and a bad value is named and planted', () => {
    const state = atDefaults(entry);
    expect(encodeState(state, served).some(([k]) => k === 'feet')).toBe(false);
    expect(encodeState({ ...state, feet: 'own' }, served)).toContainEqual(['feet', 'own']);
    const { state: back, problems } = decodeState([['model', entry.id], ['feet', 'sliding']], served, '0.1.0');
    expect(back.feet).toBeUndefined();
    expect(problems.map((p) => p.text)).toEqual([expect.stringContaining("The feet option must be planted or own, got 'sliding'")]);
  });
});

describe('the stage bar in a link', () => {
  const entry = served.models[0];
  const state = atDefaults(entry);
  it('writes only what differs from the page and reads it back', () => {
    expect(encodeState({ ...state, view: { camera: 'auto', closest: false, truth: true } }, served)
      .filter(([k]) => ['camera', 'closest', 'truth'].includes(k))).toEqual([]);
    const view = { camera: 'side' as const, closest: true, truth: false };
    const { state: back, problems } = roundTrip({ ...state, view }, served);
    expect(problems).toEqual([]);
    expect(back.view).toEqual(view);
  });
  it('names a bad value and keeps the default for it', () => {
    const { state: back, problems } = decodeState([['model', entry.id], ['camera', 'drone'], ['closest', 'yes'], ['truth', '2']], served, '0.1.0');
    expect(back.view).toBeUndefined();
    expect(problems.map((p) => p.text)).toEqual([
      expect.stringContaining("The camera must be auto, front, side, top, follow, got 'drone'"),
      expect.stringContaining("The closest option must be 1 or 0, got 'yes'"),
      expect.stringContaining("The truth option must be 1 or 0, got '2'"),
    ]);
  });
});

describe('links that do not fit this site say so', () => {
  const entry = served.models[0];
  const base: ShareState = {
    version: '0.1.0', model: entry.id, hash: shortHash(entry.hash), clip: 'cmu_10_04', start: 0, seed: 7,
    controls: Object.fromEntries(entry.controls.map((c) => [c.id, c.default as ControlValue])),
  };
  const decode = (edit: (q: URLSearchParams) => void, siteVersion = '0.1.0') => {
    const q = new URLSearchParams(encodeSearch(base, served));
    edit(q);
    return decodeState(q, served, siteVersion, { reportUnknown: true });
  };

  it('a different model hash is a warning naming both hashes', () => {
    const { state, problems } = decode((q) => q.set('hash', 'abcdef012345'));
    expect(state.model).toBe(entry.id);
    expect(problems).toHaveLength(1);
    expect(problems[0].level).toBe('warning');
    expect(problems[0].text).toContain('abcdef012345');
    expect(problems[0].text).toContain(shortHash(entry.hash));
    expect(problems[0].text).toMatch(/differ/);
  });

  it('an unknown model falls back to the stage model (WAT), and says so', () => {
    const { state, problems } = decode((q) => q.set('model', 'wat-from-the-future'));
    expect(state.model).toBe(stageModel(served).id);
    expect(served.models.find((m) => m.id === state.model)?.method).toBe('wat');
    expect(problems.map((p) => p.text).join(' ')).toMatch(/wat-from-the-future.*does not serve/);
  });

  it('another site version: info when the model is the same, a warning when it is not', () => {
    const same = decode(() => {}, '0.2.0');
    expect(same.problems).toEqual([{ level: 'info', text: expect.stringMatching(/made with motion-futures 0\.1\.0; this site is 0\.2\.0.*same/) }]);
    const other = decode((q) => q.set('hash', '000000000000'), '0.2.0');
    expect(other.problems.every((p) => p.level === 'warning')).toBe(true);
    expect(other.problems).toHaveLength(2);
  });

  it('bad values are named and left to the default', () => {
    const spec = entry.controls.find((c) => c.type === 'number' || c.type === 'int');
    expect(spec, 'the first served model has a numeric control').toBeDefined();
    const { state, problems } = decode((q) => { q.set(spec!.id, 'lots'); q.set('seed', '-3'); q.set('start', '1.5'); });
    expect(state.controls[spec!.id]).toBeUndefined();
    expect(state.seed).toBeUndefined();
    expect(state.start).toBeUndefined();
    const text = problems.map((p) => p.text).join('\n');
    expect(text).toContain(`(${spec!.id}) must be`);
    expect(text).toMatch(/seed must be an integer/);
    expect(text).toMatch(/history start must be a frame number/);
    const out = decode((q) => q.set(spec!.id, String((spec!.max ?? 0) + 1000)));
    expect(out.problems[0].text).toMatch(/must be between/);
  });

  it("a control another model declares means the link was made for that model", () => {
    const manifest = manifestWith([
      { ...entry, controls: [] },
      { ...entry, id: 'other', label: 'Other', controls: [{ id: 'temperature', type: 'number', label: 'Temperature', min: 0, max: 2, default: 1 }] },
    ], served.actions);
    const { problems } = decodeState([['model', entry.id], ['temperature', '0.5']], manifest, '0.1.0');
    expect(problems[0].text).toMatch(/'temperature', a control of Other that .* does not have/);
  });

  it('unknown parameters are mentioned only when asked', () => {
    expect(decode((q) => q.set('utm_source', 'x')).problems).toEqual([{ level: 'info', text: "Ignored the unknown link option 'utm_source'." }]);
    expect(decodeState([['utm_source', 'x']], served, '0.1.0').problems).toEqual([]);
  });

  it('a history from a dropped file cannot be encoded, and the error says why', () => {
    const dropped: ShareState = { ...base, source: { kind: 'dropped', name: 'my-walk.bvh' } };
    expect(() => encodeState(dropped, served)).toThrow(UrlStateError);
    expect(() => encodeState(dropped, served)).toThrow(/dropped file \(my-walk\.bvh\).*cannot be linked/);
  });

  it('a control named like a state field is refused rather than read ambiguously', () => {
    const manifest = manifestWith([{ ...entry, controls: [{ id: 'seed', type: 'int', label: 'Seed', min: 0, max: 9, default: 0 }] }], served.actions);
    expect(() => decodeState([], manifest, '0.1.0')).toThrow(/control 'seed', a name links reserve/);
  });

  it('the served models declare no reserved control ids', () => {
    for (const m of served.models) for (const c of m.controls) expect(RESERVED.has(c.id), `${m.id}.${c.id}`).toBe(false);
  });
});

describe('share snippets', () => {
  const entry = served.models[0];
  const state: ShareState = {
    version: '0.1.0', model: entry.id, hash: shortHash(entry.hash), clip: 'a"b<c>&d', start: 3, seed: 9,
    controls: Object.fromEntries(entry.controls.map((c) => [c.id, c.default as ControlValue])),
  };

  it('the permalink is the site root with the state as its query', () => {
    const link = new URL(permalink('http://127.0.0.1:9/mf/', state, served));
    expect(link.pathname).toBe('/mf/');
    expect(link.searchParams.get('clip')).toBe('a"b<c>&d');
    expect(link.searchParams.get('seed')).toBe('9');
    expect(link.searchParams.get('hash')).toBe(shortHash(entry.hash));
  });

  it('the element snippet is one script and one tag, with attributes escaped', () => {
    const s = embedSnippet('http://127.0.0.1:9/mf/assets/motion-futures.js', state, served, { controls: 'minimal', autoplay: true });
    expect(s.split('\n')[0]).toBe('<script type="module" src="http://127.0.0.1:9/mf/assets/motion-futures.js"></script>');
    expect(s).toContain('clip="a&quot;b&lt;c&gt;&amp;d"');
    expect(s).toMatch(/controls="minimal" autoplay/);
  });

  it('the iframe snippet points at embed.html with the same parameters', () => {
    const s = iframeSnippet('http://127.0.0.1:9/mf/', state, served, { controls: 'full', autoplay: false });
    const src = new URL(/src="([^"]+)"/.exec(s)![1].replace(/&amp;/g, '&').replace(/&quot;/g, '"').replace(/&lt;/g, '<').replace(/&gt;/g, '>'));
    expect(src.pathname).toBe('/mf/embed.html');
    expect(src.searchParams.get('controls')).toBe('full');
    expect(src.searchParams.get('clip')).toBe('a"b<c>&d');
    expect(src.searchParams.has('autoplay')).toBe(false);
    expect(s).not.toMatch(/width="\d+"/);
    expect(s).toContain('max-width: 720px; aspect-ratio: 3 / 2');
  });

  it('old versions are looked for beside this release', async () => {
    const root = 'https://h.org/x/motion-futures-0.2.0/';
    expect(releaseUrl(root, '0.1.0')).toBe('https://h.org/x/motion-futures-0.1.0/');
    expect(releaseUrl(root, '../../etc')).toBeNull();
    const serving = (body: string, status = 200) => (async (url: string) => {
      expect(url).toBe('https://h.org/x/motion-futures-0.1.0/version.json');
      return new Response(body, { status });
    }) as unknown as typeof fetch;
    expect(await olderRelease(root, '0.1.0', serving('{"name":"motion-futures","version":"0.1.0"}'))).toBe('https://h.org/x/motion-futures-0.1.0/');
    // a server that answers every path with a page, another version, a 404, or no network: no link
    expect(await olderRelease(root, '0.1.0', serving('<!doctype html><title>spa</title>'))).toBeNull();
    expect(await olderRelease(root, '0.1.0', serving('{"version":"0.3.0"}'))).toBeNull();
    expect(await olderRelease(root, '0.1.0', serving('nope', 404))).toBeNull();
    expect(await olderRelease(root, '0.1.0', (async () => { throw new TypeError('Failed to fetch'); }) as unknown as typeof fetch)).toBeNull();
  });
});
