// The import panel's sorting of a drop (web/src/ui/dropped-files.ts), its links to the served guide
// (ui/guide-link.ts) and its left/right swap (ui/import-panel.ts swappedMotion), without a browser;
// tests/e2e/byo.e2e.test.ts drops the same kinds of files on the real page.
import { readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import type { ClipIndex } from '../../web/src/contract/types';
import { importBvh, motionName } from '../../web/src/motion/bvh';
import { handedness } from '../../web/src/motion/handedness';
import { BUILTIN_MAPS, loadJointMap } from '../../web/src/motion/joint-map';
import {
  clipName, filesOfEntries, ignoredText, JOINT_MAP_FIELDS, MAX_DROPPED_FILES, notAJointMap, planDrop, type DroppedFile, type EntryLike,
} from '../../web/src/ui/dropped-files';
import { guideSegments, guideUrl } from '../../web/src/ui/guide-link';
import { swappedMotion } from '../../web/src/ui/import-panel';

const root = new URL('../../', import.meta.url);
const read = (rel: string) => readFileSync(new URL(rel, root), 'utf8');
const skeleton = (JSON.parse(read('public/clips/index.json')) as ClipIndex).skeleton;
const walk = read('tests/fixtures/walk.bvh');
const file = (path: string, text = ''): DroppedFile => ({ path, size: text.length, text: async () => text });
/** The game dataset's kind of sidecar: metadata beside each take, not a joint map. */
const METADATA = JSON.stringify({ content: 'walk forward', fps: 30, actor: 'A1' });
const MAP = JSON.stringify({ extends: 'cmu-bvh', joints: { chest: ['Spine1'] } });

describe('a .json is a joint map only when it is one', () => {
  it('every built-in map is one, and so is a user map that lists only what differs', () => {
    for (const [name, doc] of Object.entries(BUILTIN_MAPS)) expect(notAJointMap(doc), name).toBeNull();
    expect(notAJointMap(JSON.parse(MAP))).toBeNull();
    expect(notAJointMap({ up: 'z' })).toBeNull();
  });
  it('metadata, a list, an empty object and a number are not, each with the reason', () => {
    expect(notAJointMap(JSON.parse(METADATA))).toBe("not a joint map (it has the fields 'actor', 'content', 'fps')");
    expect(notAJointMap([1, 2])).toBe('not a joint map (a joint map is a JSON object, this is a list)');
    expect(notAJointMap({})).toBe('not a joint map (it has none of extends, up, joints, orders)');
    expect(notAJointMap({ name: 'x', about: 'y' })).toBe('not a joint map (it has none of extends, up, joints, orders)');
    expect(notAJointMap(3)).toBe('not a joint map (a joint map is a JSON object, this is number)');
  });
  it('the fields are the ones the joint map reader accepts', () => {
    // the reader names its fields when it refuses one; the panel's list must be the same
    let message = '';
    try { loadJointMap('cmu-bvh', skeleton.joints, { content: 1 }, 'm.json'); } catch (err) { message = (err as Error).message; }
    const listed = /a joint map has ([^)]*)\)/.exec(message)?.[1].split(', ');
    expect(listed).toEqual(JOINT_MAP_FIELDS);
  });
});

describe('a drop is sorted into one take, its joint map and what is left out', () => {
  it('a BVH with its metadata sidecar: the BVH is imported, the sidecar ignored and named', async () => {
    const plan = await planDrop([file('take.json', METADATA), file('take.bvh', walk)]);
    expect(plan.motion?.kind).toBe('bvh');
    expect(plan.motion?.kind === 'bvh' && plan.motion.file.path).toBe('take.bvh');
    expect(plan.map).toBeNull();
    expect(plan.problem).toBeNull();
    expect(ignoredText(plan.ignored)).toBe("Ignored take.json: not a joint map (it has the fields 'actor', 'content', 'fps').");
  });
  it('a BVH with a joint map: the map goes with it; a broken .json is named, not read as a map', async () => {
    const plan = await planDrop([file('take.bvh', walk), file('rig.json', MAP), file('notes.json', '{"joints": [')]);
    expect(plan.map).toEqual({ path: 'rig.json', doc: JSON.parse(MAP) });
    expect(plan.ignored.map((i) => i.path)).toEqual(['notes.json']);
    expect(plan.ignored[0].why).toMatch(/^not a joint map \(not readable JSON: /);
  });
  it('two joint maps are a problem that names both', async () => {
    const plan = await planDrop([file('take.bvh', walk), file('a.json', MAP), file('b.json', '{"up": "z"}')]);
    expect(plan.motion).toBeNull();
    expect(plan.problem).toBe('a.json, b.json: 2 joint maps dropped together; drop the one meant for the file');
  });
  it('two AMC files without their ASF import nothing, and the problem says what to drop', async () => {
    const plan = await planDrop([file('05_07.amc'), file('05_08.amc')]);
    expect(plan.motion).toBeNull();
    expect(plan.problem).toBe('05_07.amc, 05_08.amc: an AMC motion needs its ASF skeleton: drop the .asf (e.g. 05.asf) together with one .amc');
  });
  it('an .asf with several .amc: the first .amc with the .asf of its subject; the rest named', async () => {
    const plan = await planDrop([file('06_01.amc'), file('05.asf'), file('05_02.amc'), file('06.asf')]);
    expect(plan.motion?.kind === 'asf-amc' && [plan.motion.asf.path, plan.motion.amc.path]).toEqual(['05.asf', '05_02.amc']);
    expect(plan.ignored).toEqual([
      { path: '06.asf', why: 'not imported: an .amc is read with one .asf' },
      { path: '06_01.amc', why: 'not imported: the page imports one take per drop' },
    ]);
  });
  it('a folder of takes: the first by path, the others and other kinds named in groups', async () => {
    const names = ['walk/03.bvh', 'walk/01.bvh', 'walk/02.bvh', 'walk/04.bvh', 'walk/05.bvh', 'walk/06.bvh', 'walk/readme.txt'];
    const plan = await planDrop(names.map((n) => file(n, walk)));
    expect(plan.motion?.kind === 'bvh' && plan.motion.file.path).toBe('walk/01.bvh');
    expect(ignoredText(plan.ignored)).toBe('Ignored walk/readme.txt: not a BVH, ASF/AMC or joint map file; '
      + 'walk/02.bvh, walk/03.bvh, walk/04.bvh and 2 more: not imported: the page imports one take per drop.');
  });
  it('a joint map alone is kept for the next drop; an npz or a lone .asf is a problem', async () => {
    const alone = await planDrop([file('rig.json', MAP)]);
    expect([alone.motion, alone.problem, alone.map?.path]).toEqual([null, null, 'rig.json']);
    expect((await planDrop([file('take.npz')])).problem).toMatch(/^take.npz: the page reads BVH and ASF\/AMC files; .*bring-your-own\.html/);
    expect((await planDrop([file('05.asf')])).problem).toBe('05.asf: an ASF skeleton and its AMC motion go together: drop both files at once');
    expect((await planDrop([file('meta.json', METADATA)])).problem).toBe(
      'meta.json: nothing to import (the page reads .bvh files, an .asf with its .amc, and joint map .json files)');
  });
});

describe('a dropped take keeps its folder in its name', () => {
  it('named as python -m export data names it (export/data/sources.py clip_name)', () => {
    expect(clipName('walk/07_01.bvh')).toBe('walk_07_01');
    expect(clipName('My Mocap/Walk/01 01.bvh')).toBe('my_mocap_walk_01_01');
    expect(clipName('My Walk.bvh')).toBe(motionName('My Walk.bvh'));
    expect(clipName('/run.v2/take')).toBe('run.v2_take');
    expect(clipName('___.bvh')).toBe('clip');
  });
  it('a dropped folder is walked, each file with its path; a plain drop keeps the file names', async () => {
    const entry = (fullPath: string, kids?: EntryLike[]): EntryLike => {
      const name = fullPath.replace(/^.*\//, '');
      if (!kids) return { isFile: true, isDirectory: false, name, fullPath, file: (ok) => ok(new File(['x'], name)) };
      let given = false; // readEntries hands out the children once, then an empty batch
      return { isFile: false, isDirectory: true, name, fullPath, createReader: () => ({ readEntries: (ok) => { ok(given ? [] : kids); given = true; } }) };
    };
    const tree = entry('/mocap', [entry('/mocap/walk', [entry('/mocap/walk/07_01.bvh'), entry('/mocap/walk/07_01.json')]), entry('/mocap/rig.json')]);
    const { files, truncated } = await filesOfEntries([tree], []);
    expect(files.map((f) => f.path)).toEqual(['mocap/walk/07_01.bvh', 'mocap/walk/07_01.json', 'mocap/rig.json']);
    expect(truncated).toBe(false);
    expect(await files[0].text()).toBe('x');
    const plain = [new File(['a'], 'take.bvh')];
    expect((await filesOfEntries([null], plain)).files.map((f) => f.path)).toEqual(['take.bvh']);
    const big = entry('/big', Array.from({ length: MAX_DROPPED_FILES + 5 }, (_, i) => entry(`/big/${i}.bvh`)));
    const cut = await filesOfEntries([big], []);
    expect([cut.files.length, cut.truncated]).toEqual([MAX_DROPPED_FILES, true]);
  });
});

describe('messages link to the served guide', () => {
  it('each mention of bring-your-own.html (or the repository file) is a link, with its section', () => {
    const text = 'take.bvh: unknown skeleton; give a joint map (bring-your-own.html#joint-maps) or see docs/BRING_YOUR_OWN.md.';
    expect(guideSegments(text)).toEqual([
      { text: 'take.bvh: unknown skeleton; give a joint map (' },
      { text: 'bring-your-own.html#joint-maps', anchor: '#joint-maps' },
      { text: ') or see ' },
      { text: 'docs/BRING_YOUR_OWN.md', anchor: '' },
      { text: '.' },
    ]);
    expect(guideSegments('no link here')).toEqual([{ text: 'no link here' }]);
    expect(guideUrl('#joint-maps', 'https://example.org/sub/')).toBe('https://example.org/sub/bring-your-own.html#joint-maps');
  });
});

describe('a reflected body is offered the swap of left and right', () => {
  // the walk with its left and right labels exchanged: the mirror image of a person, labels kept
  const mirrored = walk.replace(/Left|Right/g, (s) => (s === 'Left' ? 'Right' : 'Left'));
  it('the mirrored walk is reflected, and the swapped motion is the walk as read from its own file', () => {
    const own = importBvh(walk, 'walk.bvh', { skeleton });
    const m = importBvh(mirrored, 'walk.bvh', { skeleton });
    expect(handedness(own.positions, own.frames, own.skeleton).reflected).toBe(false);
    expect(handedness(m.positions, m.frames, m.skeleton).reflected).toBe(true);
    const fixed = swappedMotion(m);
    expect(handedness(fixed.positions, fixed.frames, fixed.skeleton).reflected).toBe(false);
    expect(fixed.origin.jointMap).toBe('cmu-bvh, left and right swapped');
    expect([fixed.frames, fixed.name]).toEqual([own.frames, own.name]);
    // exact, in one process: every step of the retarget treats left and right alike (a + b is b + a)
    expect(m.positions).not.toEqual(own.positions);
    expect(fixed.positions).toEqual(own.positions);
  });
});
