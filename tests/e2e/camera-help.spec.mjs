// Camera and help (issue 10, items 5 and 6) on the real page: Frame (button, F, Home) brings a lost model
// back into view, view presets look along the axes, a double-click sets the orbit pivot on the surface, and
// the help overlay (?, H, F1) lists every tool of the toolbar; F no longer flips the vortex (X does).
import { mkdirSync } from 'node:fs';
import { dirname, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { expect, test } from '@playwright/test';
import { centreCoverage, openDesignerPage } from './helpers.mjs';

const ROOT = resolve(dirname(fileURLToPath(import.meta.url)), '../..');
const OUT = resolve(ROOT, 'test-results/views');

test.describe.serial('camera and help', () => {
  let page, errors;
  const evaluate = (fn, arg) => page.evaluate(fn, arg);
  const coverage = () => centreCoverage(page, 0.5);

  // Sends the model far off to the side and away: the centre of the view shows background only.
  const loseModel = () =>
    evaluate(() => {
      const { target } = window.tvf.camera();
      window.tvf.setCamera({ target: [target[0] + 50, target[1] + 50, target[2]], position: [target[0] + 50, target[1] + 50, target[2] + 200] });
    });
  const settle = () => evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));

  test.beforeAll(async ({ browser }) => {
    ({ page, errors } = await openDesignerPage(browser, { viewport: { width: 1024, height: 720 } }));
    mkdirSync(OUT, { recursive: true });
  });

  test.afterAll(async () => {
    expect(errors).toEqual([]);
    await page?.close();
  });

  test('a first-run hint shows in the viewport until the first press there', async () => {
    const hint = page.locator('#hint');
    await expect(hint).toBeVisible();
    await expect(hint).toContainText('Stroke');
    await expect(hint).toContainText('help');
    const box = await page.locator('#view').boundingBox();
    await page.mouse.click(box.x + box.width / 2, box.y + 30);
    await expect(hint).toBeHidden();
  });

  test('Frame, F and Home bring a lost model back into view', async () => {
    await settle();
    const framed = await coverage();
    expect(framed).toBeGreaterThan(0.15);
    for (const bring of [
      () => page.getByRole('button', { name: 'Frame', exact: true }).click(),
      () => page.keyboard.press('f'),
      () => page.keyboard.press('Home'),
    ]) {
      await loseModel();
      await settle();
      expect(await coverage()).toBeLessThan(0.01);
      await page.locator('#view').focus();
      await bring();
      await settle();
      expect(await coverage()).toBeGreaterThan(0.8 * framed);
    }
    await page.screenshot({ path: resolve(OUT, 'framed.png') });
  });

  test('view presets look along the axes at the model centre', async () => {
    const axes = { Front: [0, 0, 1], Side: [1, 0, 0], Top: [0, 1, 0] };
    for (const [name, axis] of Object.entries(axes)) {
      await page.getByRole('button', { name, exact: true }).click();
      const { position, target } = await evaluate(() => window.tvf.camera());
      const d = position.map((p, k) => p - target[k]);
      const len = Math.hypot(...d);
      const cos = d.reduce((s, x, k) => s + x * axis[k], 0) / len;
      expect(cos).toBeGreaterThan(0.999);
      await settle();
      expect(await coverage()).toBeGreaterThan(0.1);
    }
    await page.keyboard.press('f');
  });

  test('a double-click sets the orbit pivot on the surface', async () => {
    const box = await page.locator('#view').boundingBox();
    const x = box.x + box.width / 2 + 40, y = box.y + box.height / 2 + 30;
    const hit = await evaluate(([x, y]) => window.tvf.pick(x, y), [x, y]);
    expect(hit).not.toBeNull();
    await page.mouse.dblclick(x, y);
    const { target } = await evaluate(() => window.tvf.camera());
    const d = Math.hypot(...target.map((t, k) => t - hit.point[k]));
    const r = await evaluate(() => {
      const { positions } = window.tvf.mesh();
      let m = 0;
      for (let k = 0; k < positions.length; k++) m = Math.max(m, Math.abs(positions[k]));
      return m;
    });
    expect(d).toBeLessThan(1e-3 * r);
    // The picked point is now at the centre of the screen.
    const c = await evaluate((p) => window.tvf.projectToScreen(p), hit.point);
    expect(Math.abs(c.x - (box.x + box.width / 2))).toBeLessThan(2);
    expect(Math.abs(c.y - (box.y + box.height / 2))).toBeLessThan(2);
    await page.keyboard.press('Home');
  });

  test('the help overlay lists every tool, opens with ?, H and F1', async () => {
    const help = page.getByRole('dialog', { name: 'Help' });
    const tools = await page.locator('.toolbar [data-tool]').allTextContents();
    expect(tools.length).toBeGreaterThanOrEqual(7);
    for (const key of ['?', 'h', 'F1']) {
      await page.locator('#view').focus();
      await page.keyboard.press(key);
      await expect(help).toBeVisible();
      const rows = await help.locator('section').first().locator('th').allTextContents();
      for (const tool of tools) expect(rows).toContain(tool.trim());
      await expect(help).toContainText('Frame');
      await expect(help).toContainText('Double-click');
      if (key === '?') await page.screenshot({ path: resolve(OUT, 'help.png') });
      await page.keyboard.press('Escape');
      await expect(help).toBeHidden();
    }
    await page.getByRole('button', { name: 'Help' }).click();
    await expect(help).toBeVisible();
    await page.getByRole('button', { name: 'Close help' }).click();
    await expect(help).toBeHidden();
  });

  test('X flips the vortex turning; F frames instead', async () => {
    await page.getByRole('button', { name: 'Vortex', exact: true }).click();
    const ccw = page.getByRole('button', { name: '↺ CCW' });
    await expect(ccw).toHaveAttribute('aria-pressed', 'true');
    await page.locator('#view').focus();
    await page.keyboard.press('f');
    await expect(ccw).toHaveAttribute('aria-pressed', 'true');
    await page.keyboard.press('x');
    await expect(ccw).toHaveAttribute('aria-pressed', 'false');
    await page.keyboard.press('x');
    await page.getByRole('button', { name: 'Orbit', exact: true }).click();
  });
});
