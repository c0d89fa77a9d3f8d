// Design files that cannot hurt, and honest inputs (issue 10, items 8 and 9), through the page's own controls:
// a design for another mesh and a malformed design are refused with the one-form unchanged; the page's
// fingerprint is the CLI's; opening a model over unsaved edits asks first; a negative strength is shown
// invalid and never coerced; the banner clears on the next success; constraint numbers restart per model.
import { execFileSync, spawnSync } from 'node:child_process';
import { mkdtempSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { expect, test } from '@playwright/test';
import { openDesigner, trackErrors } from './helpers.mjs';

const ROOT = resolve(dirname(fileURLToPath(import.meta.url)), '../..');
const TVF = resolve(ROOT, 'build/tvf');
const BUNNY_GLB = resolve(ROOT, 'dist/models/bunny.glb');
const EMPTY = { boundary: 'free', gamma: 0, constraints: [] };

// A regular octahedron: a closed genus-0 mesh small enough to write inline.
const OCTAHEDRON = `OFF
6 8 0
1 0 0
-1 0 0
0 1 0
0 -1 0
0 0 1
0 0 -1
3 0 2 4
3 2 1 4
3 1 3 4
3 3 0 4
3 2 0 5
3 1 2 5
3 3 1 5
3 0 3 5
`;

test.describe.serial('design files and inputs', () => {
  let page, dir;
  const evaluate = (fn, arg) => page.evaluate(fn, arg);
  const oneForm = () => evaluate(() => Array.from(window.tvf.oneForm()));
  const constraints = () => evaluate(() => window.tvf.constraints());
  const banner = () => page.locator('#error-banner');
  const status = () => page.locator('#status');

  // The surface point under the canvas centre, in client coordinates.
  const centreHit = () =>
    evaluate(() => {
      const r = document.querySelector('tangent-field-designer').shadowRoot.querySelector('#view').getBoundingClientRect();
      for (const [dx, dy] of [[0, 0], [10, 10], [-10, 20], [20, -10]]) {
        const x = r.left + r.width / 2 + dx, y = r.top + r.height / 2 + dy;
        const hit = window.tvf.pick(x, y);
        if (hit) return { ...hit, x, y };
      }
      return null;
    });

  async function loadDesignFile(name, design) {
    const path = join(dir, name);
    writeFileSync(path, typeof design === 'string' ? design : JSON.stringify(design));
    const unsaved = await evaluate(() => window.tvf.hasUnsavedEdits());
    await page.locator('#design-input').setInputFiles(path);
    // Over unsaved edits the page asks first; going ahead is the explicit choice.
    if (unsaved) {
      await expect(page.getByRole('alertdialog')).toContainText('unsaved edits');
      await page.getByRole('button', { name: 'Load anyway' }).click();
    }
  }

  test.beforeAll(async ({ browser }) => {
    dir = mkdtempSync(join(tmpdir(), 'tvf-design-files-'));
    page = await browser.newPage({ viewport: { width: 1024, height: 720 } });
    trackErrors(page);
    await openDesigner(page);
  });

  test.afterAll(async () => {
    await page?.close();
  });

  test('a saved design carries the fingerprint the CLI checks', async () => {
    await evaluate((d) => window.tvf.loadDesign(d), EMPTY);
    await evaluate(() => window.tvf.addSource(10));
    await evaluate(() => window.tvf.addSink(500));
    const design = await evaluate(() => window.tvf.saveDesign());
    const info = await evaluate(() => window.tvf.info());
    expect(design.schema).toBe('tvf-design/1');
    expect(design.mesh.vertices).toBe(info.vertices);
    expect(design.mesh.faces).toBe(info.faces);
    expect(design.mesh.hash).toMatch(/^[0-9a-f]{16}$/);
    const designPath = join(dir, 'bunny.design.json');
    writeFileSync(designPath, JSON.stringify(design));
    // The CLI accepts it on the same model file (so its fingerprint is the page's) and refuses it elsewhere.
    const same = spawnSync(TVF, ['design', BUNNY_GLB, designPath], { encoding: 'utf8', maxBuffer: 1 << 28 });
    expect(same.status, same.stderr).toBe(0);
    const octa = join(dir, 'octahedron.off');
    writeFileSync(octa, OCTAHEDRON);
    const other = spawnSync(TVF, ['design', octa, designPath], { encoding: 'utf8' });
    expect(other.status).toBe(2);
    expect(other.stderr).toContain('another mesh');
    expect(() => execFileSync(TVF, ['design', octa, join(dir, 'nope.json')], { stdio: 'pipe' })).toThrow();
  });

  test('a design for another mesh is refused until the user applies it anyway, undoably', async () => {
    const before = await oneForm();
    const listBefore = await constraints();
    const foreign = await evaluate(() => window.tvf.saveDesign());
    foreign.mesh = { vertices: 6, faces: 8, hash: '0123456789abcdef' };
    foreign.constraints = [{ type: 'vortex', face: 3, strength: 1 }];
    await loadDesignFile('foreign.design.json', foreign);
    await expect(banner()).toBeVisible();
    await expect(banner()).toContainText('another mesh');
    await expect(banner()).toContainText('6 vertices, 8 faces');
    expect(await oneForm()).toEqual(before);
    expect(await constraints()).toEqual(listBefore);
    // The explicit choice applies it; one undo brings the previous design back.
    await page.getByRole('button', { name: 'Apply anyway' }).click();
    await expect.poll(async () => (await constraints()).map((c) => c.type)).toEqual(['vortex']);
    await expect(banner()).toBeHidden();
    await evaluate(() => window.tvf.undo());
    expect((await constraints()).map((c) => c.type)).toEqual(listBefore.map((c) => c.type));
    const restored = await oneForm();
    const scale = Math.max(...before.map(Math.abs));
    expect(Math.max(...restored.map((x, k) => Math.abs(x - before[k])))).toBeLessThan(1e-9 * scale);
  });

  test('malformed and unknown-schema designs are refused with the reason, design untouched', async () => {
    const before = await oneForm();
    const listBefore = await constraints();
    for (const [name, text, reason] of [
      ['foo.json', '{"foo": 1}', 'unknown key "foo"'],
      ['schema.json', '{"schema": "tvf-design/9", "constraints": []}', 'unknown design schema'],
      ['broken.json', '{ nope', 'broken.json'],
    ]) {
      await loadDesignFile(name, text);
      await expect(banner()).toContainText(reason);
      expect(await oneForm()).toEqual(before);
      expect(await constraints()).toEqual(listBefore);
    }
    // The banner goes on the next success.
    await evaluate(() => window.tvf.addSource(20));
    await expect(banner()).toBeHidden();
    await evaluate(() => window.tvf.undo());
  });

  test('a negative strength is shown invalid and refused, never coerced', async () => {
    const count = (await constraints()).length;
    await page.getByRole('button', { name: 'Source', exact: true }).click();
    const strength = page.locator('#strength');
    await strength.fill('-5');
    await expect(strength).toHaveAttribute('aria-invalid', 'true');
    const hit = await centreHit();
    expect(hit).not.toBeNull();
    await page.mouse.click(hit.x, hit.y);
    await expect(banner()).toContainText('strength');
    await expect(banner()).toContainText('-5');
    expect(await constraints()).toHaveLength(count);
    await expect(strength).toHaveValue('-5');
    await strength.fill('2.5');
    await expect(strength).toHaveAttribute('aria-invalid', 'false');
    await page.mouse.click(hit.x, hit.y);
    await expect.poll(async () => (await constraints()).length).toBe(count + 1);
    expect((await constraints()).at(-1).strength).toBe(2.5);
    await expect(banner()).toBeHidden();
    await page.getByRole('button', { name: 'Orbit', exact: true }).click();
  });

  test('Save confirms; opening a model over unsaved edits asks first; numbers restart per model', async () => {
    expect(await evaluate(() => window.tvf.hasUnsavedEdits())).toBe(true);
    const octa = join(dir, 'octahedron.off');
    writeFileSync(octa, OCTAHEDRON);
    const facesBefore = (await evaluate(() => window.tvf.info())).faces;
    const before = await oneForm();
    await page.locator('#file-input').setInputFiles(octa);
    const dialog = page.getByRole('alertdialog');
    await expect(dialog).toBeVisible();
    await expect(dialog).toContainText('unsaved edits');
    await page.getByRole('button', { name: 'Cancel' }).click();
    await expect(dialog).toBeHidden();
    expect((await evaluate(() => window.tvf.info())).faces).toBe(facesBefore);
    expect(await oneForm()).toEqual(before);

    const download = page.waitForEvent('download');
    await page.getByRole('button', { name: 'Save', exact: true }).click();
    expect((await download).suggestedFilename()).toMatch(/\.design\.json$/);
    await expect(status()).toContainText('Saved');
    expect(await evaluate(() => window.tvf.hasUnsavedEdits())).toBe(false);

    const maxId = Math.max(...(await constraints()).map((c) => c.id));
    expect(maxId).toBeGreaterThan(1);
    await page.locator('#file-input').setInputFiles(octa);
    await expect.poll(() => evaluate(() => window.tvf.ready && window.tvf.info().faces)).toBe(8);
    await expect(dialog).toBeHidden();
    const id = await evaluate(() => window.tvf.addSource(0));
    expect(id).toBe(1);
  });
});
