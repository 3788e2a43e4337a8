// The served bring-your-own guide (bring-your-own.html) is docs/BRING_YOUR_OWN.md read by
// web/src/guide/markdown.ts: its sections keep the anchors messages link to, and its example joint map
// is a joint map the import panel takes, which imports a walk from a rig no built-in map knows.
import { readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import type { ClipIndex } from '../../web/src/contract/types';
import { importBvh, MotionImportError } from '../../web/src/motion/bvh';
import { jsonBlocks, parseInline, parseMarkdown, slug } from '../../web/src/guide/markdown';
import { notAJointMap, planDrop } from '../../web/src/ui/dropped-files';

const root = new URL('../../', import.meta.url);
const read = (rel: string) => readFileSync(new URL(rel, root), 'utf8');
const skeleton = (JSON.parse(read('public/clips/index.json')) as ClipIndex).skeleton;
const guide = read('docs/BRING_YOUR_OWN.md');
const blocks = parseMarkdown(guide);

/** The fixture walk with its CMU joint names in a game rig's style (pelvis, thigh_l, spine_02, ...). */
const RENAME: Record<string, string> = {
  Hips: 'pelvis', LHipJoint: 'hip_joint_l', RHipJoint: 'hip_joint_r', LowerBack: 'spine_01', Spine: 'spine_02', Spine1: 'spine_03',
  Neck: 'neck_01', Neck1: 'neck_02', Head: 'head',
  ...Object.fromEntries(['l', 'r'].flatMap((s) => {
    const side = s === 'l' ? 'Left' : 'Right';
    return [['UpLeg', 'thigh'], ['Leg', 'calf'], ['Foot', 'foot'], ['ToeBase', 'ball'], ['Shoulder', 'clavicle'], ['Arm', 'upperarm'],
      ['ForeArm', 'lowerarm'], ['Hand', 'hand']].map(([cmu, game]) => [`${side}${cmu}`, `${game}_${s}`]);
  })),
};
const walk = read('tests/fixtures/walk.bvh');
const gameWalk = walk.replace(/^(\s*(?:ROOT|JOINT)\s+)(\S+)/gm, (_, head: string, name: string) => `${head}${RENAME[name] ?? name}`);

describe('the guide page reads docs/BRING_YOUR_OWN.md', () => {
  it('headings carry the anchors GitHub gives them, and the link to the example resolves', () => {
    const ids = blocks.filter((b) => b.kind === 'heading').map((b) => (b.kind === 'heading' ? b.id : ''));
    expect(ids).toContain('joint-maps');
    expect(ids).toContain('in-the-browser');
    expect(ids).toContain('an-example-joint-map');
    expect(slug('The retargeting method (one, in both languages)')).toBe('the-retargeting-method-one-in-both-languages');
    const anchors = [...guide.matchAll(/\]\((#[^)]+)\)/g)].map((m) => m[1].slice(1));
    expect(anchors.length).toBeGreaterThan(0);
    for (const a of anchors) expect(ids).toContain(a);
  });
  it('lists, code blocks and inline marks come out as written', () => {
    expect(blocks[0]).toEqual({ kind: 'heading', level: 1, text: 'Bring your own motion, take the predictions away', id: 'bring-your-own-motion-take-the-predictions-away' });
    const sh = blocks.find((b) => b.kind === 'code' && b.lang === 'sh');
    expect(sh?.kind === 'code' && sh.text.split('\n')[0]).toBe('python -m export data   --data my_mocap                      # convert and look: runs/data/my_mocap/');
    const steps = blocks.find((b) => b.kind === 'list' && b.ordered);
    expect(steps?.kind === 'list' && steps.items.length).toBe(6);
    expect(steps?.kind === 'list' && steps.items[0]).toMatch(/^\*\*Joint map\*\*: each of the 18 project joints .* \(`LeftUpLeg\+RightUpLeg`\)\. The root/);
    expect(parseInline('a **b `c`** [d](#e) `**f**`')).toEqual([
      { kind: 'text', text: 'a ' }, { kind: 'strong', children: [{ kind: 'text', text: 'b ' }, { kind: 'code', text: 'c' }] },
      { kind: 'text', text: ' ' }, { kind: 'link', href: '#e', children: [{ kind: 'text', text: 'd' }] }, { kind: 'text', text: ' ' },
      { kind: 'code', text: '**f**' },
    ]);
  });
});

describe('the example joint map', () => {
  const maps = jsonBlocks(blocks).map((t) => JSON.parse(t) as Record<string, unknown>);
  const example = maps.find((m) => m.name === 'my-rig')!;
  it('every JSON example in the guide is a joint map the panel takes as one', async () => {
    expect(maps.length).toBeGreaterThanOrEqual(2);
    for (const m of maps) expect(notAJointMap(m)).toBeNull();
    const text = JSON.stringify(example);
    const plan = await planDrop([{ path: 'my-rig.json', size: text.length, text: async () => text }, { path: 'walk.bvh', size: 1, text: async () => gameWalk }]);
    expect(plan.map?.path).toBe('my-rig.json');
    expect(Object.keys(example.joints as object).sort()).toEqual([...skeleton.joints].sort());
  });
  it('imports the game-style walk exactly as the built-in map imports the CMU walk; without it the rig is unknown', () => {
    let caught: unknown;
    try { importBvh(gameWalk, 'walk.bvh', { skeleton }); } catch (err) { caught = err; }
    expect(caught).toBeInstanceOf(MotionImportError);
    expect((caught as MotionImportError).problem).toBe('unknown-skeleton');
    const mapped = importBvh(gameWalk, 'walk.bvh', { skeleton, jointMap: example, jointMapName: 'my-rig.json' });
    const cmu = importBvh(walk, 'walk.bvh', { skeleton });
    expect(mapped.origin.jointMap).toBe('cmu-bvh + my-rig.json');
    expect(mapped.frames).toBe(cmu.frames);
    // the same joints under other names, read the same way in one process: the same numbers
    expect(mapped.positions).toEqual(cmu.positions);
  });
});
