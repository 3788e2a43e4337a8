// Bring your own motion in a real Chromium: drop a BVH on the page, predict from it, export a GLB;
// a bad file is named and the stage keeps what it had. Then the import panel's sorting of a drop
// (issue 30): a metadata sidecar is ignored by name, a map applies to its own drop only, a folder stays
// in the name, two AMC files import nothing and the banner says so, a mirrored body is offered the
// swap; and the served guide (bring-your-own.html) the messages link to.
import { readFileSync } from 'node:fs';
import { afterAll, beforeAll, describe, expect, inject, it } from 'vitest';
import type { Page } from 'playwright-core';
import { openBrowser, type BrowserSession } from './browser';
import { pixelStats } from './pixels';

const baseUrl = inject('baseUrl');
const NO_PROBLEMS = { consoleErrors: [], pageErrors: [], failedRequests: [] };
const fixture = (name: string) => readFileSync(new URL(`../fixtures/${name}`, import.meta.url), 'utf8');
const status = (page: Page, key: string, value: string) =>
  page.waitForSelector(`body[data-${key}="${value}"]`, { state: 'attached', timeout: 90_000 });
const settle = (page: Page) => page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));

/** Drop a folder: Chromium hands a real one over as file system entries; these fake entries carry the files. */
async function dropFolder(page: Page, folder: string, files: { name: string; text: string }[]): Promise<void> {
  await page.evaluate(([dir, fs]) => {
    const file = (f: { name: string; text: string }) => ({
      isFile: true, isDirectory: false, name: f.name, fullPath: `/${dir}/${f.name}`,
      file: (ok: (x: File) => void) => ok(new File([f.text], f.name)),
    });
    let given = false;
    const folderEntry = {
      isFile: false, isDirectory: true, name: dir, fullPath: `/${dir}`,
      createReader: () => ({ readEntries: (ok: (x: unknown[]) => void) => { ok(given ? [] : fs.map(file)); given = true; } }),
    };
    const dt = { files: [] as File[], items: [{ kind: 'file', webkitGetAsEntry: () => folderEntry }] };
    const e = new Event('drop', { bubbles: true, cancelable: true });
    Object.defineProperty(e, 'dataTransfer', { value: dt });
    document.querySelector('motion-futures')!.dispatchEvent(e);
  }, [folder, files] as const);
}

/** Drop files on the widget the way a person does: a drop event carrying a DataTransfer. */
async function drop(page: Page, files: { name: string; text: string }[]): Promise<void> {
  await page.evaluate((fs) => {
    const dt = new DataTransfer();
    for (const f of fs) dt.items.add(new File([f.text], f.name, { type: 'application/octet-stream' }));
    const host = document.querySelector('motion-futures')!;
    host.dispatchEvent(new DragEvent('dragover', { dataTransfer: dt, bubbles: true, cancelable: true }));
    host.dispatchEvent(new DragEvent('drop', { dataTransfer: dt, bubbles: true, cancelable: true }));
  }, files);
}

describe('bring your own motion', () => {
  let session: BrowserSession;
  let page: Page;

  beforeAll(async () => {
    session = await openBrowser();
    page = session.page;
    await page.goto(baseUrl);
    await status(page, 'predict-status', 'done');
  });
  afterAll(async () => { await session?.close(); });

  it('a dropped BVH becomes the history source, and the model predicts from it', async () => {
    await page.evaluate(() => { document.body.dataset.importStatus = 'waiting'; });
    await drop(page, [{ name: 'My Walk.bvh', text: fixture('walk.bvh') }]);
    await status(page, 'import-status', 'done');
    expect(await page.locator('.import-status').textContent()).toMatch(/my_walk: 46 frames at 30 Hz .* from 151 at 100 Hz, joint map cmu-bvh/);
    const stage = await page.evaluate(() => { const s = window.motionFutures!.onStage(); return { name: s.motion?.name, frames: s.motion?.frames, source: s.source }; });
    expect(stage).toEqual({ name: 'my_walk', frames: 46, source: { kind: 'dropped', name: 'My Walk.bvh' } });
    // a dropped file predicts again on its own (issue 20: never stale)
    await page.waitForFunction(() => window.motionFutures!.predictor.last?.clip === 'my_walk' && document.body.dataset.predictStatus === 'done',
      undefined, { timeout: 90_000 });

    await page.locator('#model-select').selectOption('regression-gru');
    await page.locator('#history-start').fill('20');
    await page.locator('#history-start').dispatchEvent('change');
    await page.evaluate(() => { document.body.dataset.predictStatus = 'waiting'; });
    await page.locator('#predict').click();
    await status(page, 'predict-status', 'done');
    expect(await page.locator('.predict-status').textContent()).toMatch(/Regression GRU.*frames 20–29 of my_walk/);
    expect(await page.locator(".history-note").textContent()).toMatch(/from your file My Walk.bvh/);
    await page.evaluate(() => { const p = window.motionFutures!.player; p.pause(); p.seek(22); });
    await settle(page);
    await session.screenshot('byo-dropped-bvh.png');
    const stats = await pixelStats(session.context, await session.screenshot('byo-dropped-bvh-stage.png', page.locator('#viewer')));
    expect(stats.foreground).toBeGreaterThan(0.01 * stats.width * stats.height);
  });

  it('the Export panel saves a GLB of the history and the future', async () => {
    expect(await page.locator('#export-glb').isDisabled()).toBe(false);
    const [download] = await Promise.all([page.waitForEvent('download'), page.locator('#export-glb').click()]);
    expect(download.suggestedFilename()).toBe('my_walk.regression-gru.sample_1.glb');
    const path = await download.path();
    const bytes = readFileSync(path!);
    expect(bytes.subarray(0, 4).toString('latin1')).toBe('glTF');
    const jsonLength = bytes.readUInt32LE(12);
    const gltf = JSON.parse(bytes.subarray(20, 20 + jsonLength).toString('utf8'));
    const names = gltf.nodes.map((n: { name: string }) => n.name);
    expect(names).toContain('history_root');
    expect(names).toContain('sample_1_left_toe');
    expect(gltf.animations).toHaveLength(1);
    const [csv] = await Promise.all([page.waitForEvent('download'), page.locator('#export-csv').click()]);
    expect(readFileSync((await csv.path())!, 'utf8').split('\n')[0]).toBe('figure,frame,time,joint,x,y,z');
    expect(session.problems).toEqual(NO_PROBLEMS);
  });

  it('a bad file is named and the stage keeps the dropped walk and its prediction', async () => {
    await page.evaluate(() => { document.body.dataset.importStatus = 'waiting'; });
    await drop(page, [{ name: 'notes.bvh', text: 'These are my notes, not motion.' }]);
    await status(page, 'import-status', 'error');
    await expect.poll(() => page.locator('.message-text').allTextContents()).toContainEqual(
      'Could not import: notes.bvh: not a BVH file (it must start with a line "HIERARCHY")');
    await drop(page, [{ name: 'odd.bvh', text: fixture('unknown_skeleton.bvh') }]);
    await expect.poll(() => page.locator('.import-status').textContent()).toMatch(/odd.bvh: unknown skeleton for joint map cmu-bvh/);
    await drop(page, [{ name: 'short.bvh', text: fixture('short.bvh') }]);
    await expect.poll(() => page.locator('.import-status').textContent()).toMatch(/short.bvh: too few frames/);
    const stage = await page.evaluate(() => ({ name: window.motionFutures!.onStage().motion?.name, last: window.motionFutures!.predictor.last?.start }));
    expect(stage).toEqual({ name: 'my_walk', last: 20 });
    await settle(page);
    await session.screenshot('byo-bad-file.png');
    expect(session.problems).toEqual(NO_PROBLEMS);
  });

  // last: it replaces the dropped walk the tests above keep on stage
  it('a dropped .asf and .amc pair becomes the history source too', async () => {
    // CMU take 05_02 as its original files (data/cmu/index.json names them)
    const index = JSON.parse(readFileSync(new URL('../../data/cmu/index.json', import.meta.url), 'utf8')) as { take: string; file: string; asf: string }[];
    const e = index.find((t) => t.take === '05_02')!;
    const read = (rel: string) => readFileSync(new URL(`../../data/cmu/${rel}`, import.meta.url), 'utf8');
    const take = { asf_file: e.asf.split('/').pop()!, amc_file: e.file.split('/').pop()!, asf: read(e.asf), amc: read(e.file) };
    await page.evaluate(() => { document.body.dataset.importStatus = 'waiting'; });
    await drop(page, [{ name: take.asf_file, text: take.asf }, { name: take.amc_file, text: take.amc }]);
    await status(page, 'import-status', 'done');
    expect(await page.locator('.import-status').textContent()).toMatch(/: 28\d frames at 30 Hz \(9\.\d s\) from 112\d at 120 Hz, joint map cmu-asf/);
    const source = await page.evaluate(() => window.motionFutures!.onStage().source);
    expect(source).toEqual({ kind: 'dropped', name: take.amc_file });
  });

  describe('what a drop holds', () => {
    const walk = fixture('walk.bvh');
    const METADATA = JSON.stringify({ content: 'walk forward', fps: 100 });
    const imported = async (files: { name: string; text: string }[]) => {
      await page.evaluate(() => { document.body.dataset.importStatus = 'waiting'; });
      await drop(page, files);
      await page.waitForSelector('body[data-import-status="done"], body[data-import-status="error"]', { state: 'attached', timeout: 90_000 });
      // the widget's parts sit in its shadow root: locators reach them, document.querySelector does not
      const ignored = page.locator('.import-ignored');
      return {
        state: await page.evaluate(() => document.body.dataset.importStatus), status: await page.locator('.import-status').textContent(),
        ignored: (await ignored.isHidden()) ? '' : await ignored.textContent(),
        banner: await page.locator('.message-text').allTextContents(),
        stage: await page.evaluate(() => window.motionFutures!.onStage().motion?.name),
      };
    };

    it('two AMC files import nothing, and the banner never says "Imported"', async () => {
      const r = await imported([{ name: '05_07.amc', text: '1\nroot 0 0 0 0 0 0\n' }, { name: '05_08.amc', text: '1\n' }]);
      expect(r.state).toBe('error');
      expect(r.status).toBe('05_07.amc, 05_08.amc: an AMC motion needs its ASF skeleton: drop the .asf (e.g. 05.asf) together with one .amc');
      expect(r.banner.filter((t) => /Imported/.test(t))).toEqual([]);
      expect(r.banner.some((t) => t.startsWith('Could not import: 05_07.amc, 05_08.amc'))).toBe(true);
    });

    it('a metadata .json beside a BVH is ignored by name, and the next file imports on its own', async () => {
      const r = await imported([{ name: 'take.bvh', text: walk }, { name: 'take.json', text: METADATA }]);
      expect([r.state, r.stage]).toEqual(['done', 'take']);
      expect(r.ignored).toBe("Ignored take.json: not a joint map (it has the fields 'content', 'fps').");
      expect(r.banner.filter((t) => /Imported/.test(t))).toEqual(['Imported take.bvh.']);
      const next = await imported([{ name: 'again.bvh', text: walk }]);
      expect([next.state, next.stage, next.ignored]).toEqual(['done', 'again', '']);
    });

    it('a joint map applies to its own drop only; the error after it links to the served guide', async () => {
      // a left wrist no built-in map names
      const game = walk.replace(/^(\s*JOINT\s+)LeftHand\b/m, '$1HandL');
      const map = JSON.stringify({ extends: 'cmu-bvh', joints: { left_wrist: ['HandL'] } });
      const r = await imported([{ name: 'game.bvh', text: game }, { name: 'rig.json', text: map }]);
      expect(r.state).toBe('done');
      expect(r.status).toMatch(/joint map cmu-bvh \+ rig\.json\.$/);
      const after = await imported([{ name: 'game.bvh', text: game }]);
      expect([after.state, after.stage]).toEqual(['error', 'game']);
      expect(after.status).toMatch(/game.bvh: unknown skeleton/);
      // the message names the guide (bring-your-own.html, or the repository file before the readers say so): a link to the page
      const href = await page.locator('.import-status a.guide-link').first().getAttribute('href');
      expect(href).toMatch(/\/bring-your-own\.html(#[\w-]+)?$/);
      expect(new URL(href!).origin).toBe(new URL(baseUrl).origin);
    });

    it('a z-up file read as y-up imports with the readers\' warning; with its map, without', async () => {
      const zup = fixture('walk_zup.bvh');
      const r = await imported([{ name: 'zup.bvh', text: zup }]);
      expect(r.state).toBe('done');
      expect(await page.locator('.import-warnings li').allTextContents()).toEqual([expect.stringContaining('set "up": "z"')]);
      expect(r.banner.some((t) => t.startsWith('zup.bvh: '))).toBe(true);
      const fixed = await imported([{ name: 'zup.bvh', text: zup }, { name: 'up.json', text: '{"up": "z"}' }]);
      expect([fixed.state, await page.locator('.import-warnings').isHidden()]).toEqual(['done', true]);
    });

    it('a dropped folder keeps its name in the clip\'s', async () => {
      await page.evaluate(() => { document.body.dataset.importStatus = 'waiting'; });
      await dropFolder(page, 'Walk', [{ name: '07_01.bvh', text: walk }, { name: '07_01.json', text: METADATA }]);
      await status(page, 'import-status', 'done');
      const stage = await page.evaluate(() => { const s = window.motionFutures!.onStage(); return { name: s.motion?.name, source: s.source }; });
      expect(stage).toEqual({ name: 'walk_07_01', source: { kind: 'dropped', name: 'Walk/07_01.bvh' } });
      expect(await page.locator('.import-ignored').textContent()).toMatch(/^Ignored Walk\/07_01\.json: not a joint map/);
    });

    it('a mirrored body is offered the swap of left and right, and the swap is what goes on stage', async () => {
      const mirrored = walk.replace(/Left|Right/g, (x) => (x === 'Left' ? 'Right' : 'Left'));
      const r = await imported([{ name: 'mirror.bvh', text: mirrored }]);
      expect(r.state).toBe('done');
      await status(page, 'import-handedness', 'reflected');
      expect(await page.locator('.import-swap').textContent()).toMatch(/^mirror: Left and right look swapped/);
      await session.screenshot('byo-swap-offer.png', page.locator('#import-drop').locator('xpath=..'));
      await page.locator('#import-swap').click();
      await status(page, 'import-handedness', 'swapped');
      expect(await page.locator('.import-swap').isHidden()).toBe(true);
      expect(await page.locator('.import-status').textContent()).toMatch(/joint map cmu-bvh, left and right swapped\.$/);
      expect(await page.evaluate(() => window.motionFutures!.onStage().motion?.name)).toBe('mirror');
      expect(session.problems).toEqual(NO_PROBLEMS);
    });
  });

  it('the site serves its bring-your-own guide with an example joint map, offline too', async () => {
    const guide = await session.context.newPage();
    await guide.goto(`${baseUrl}bring-your-own.html#an-example-joint-map`);
    await guide.waitForSelector('body[data-guide-status="done"]', { state: 'attached' });
    expect(await guide.locator('h1').textContent()).toBe('Bring your own motion, take the predictions away');
    expect(await guide.locator('#joint-maps').count()).toBe(1);
    const example = JSON.parse((await guide.locator('[data-testid="example-map"] pre').nth(1).textContent())!);
    expect(example.name).toBe('my-rig');
    await session.screenshot('byo-guide.png', guide);
    const [saved] = await Promise.all([guide.waitForEvent('download'), guide.locator('[data-testid="example-map"] button').nth(1).click()]);
    expect(saved.suggestedFilename()).toBe('my-rig.json');
    expect(JSON.parse(readFileSync((await saved.path())!, 'utf8'))).toEqual(example);
    // the service worker precaches it with the other pages
    expect(await guide.evaluate(async () => (await (await fetch('./sw.js')).text()).includes('bring-your-own.html'))).toBe(true);
    await guide.close();
  });
});
