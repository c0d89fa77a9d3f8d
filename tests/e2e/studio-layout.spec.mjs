// Small screens and touch (issue 10, item 7) on the real page: at 800×600 and on a 390×844 phone nothing
// overlaps (bounding boxes of the toolbar, panels, status line, hint and view presets), everything lies in the
// viewport and at least 40% of the viewport still shows the model's canvas unobscured, with the panels closed
// (drawers) and open; the model stays framed when the view turns from landscape to portrait; a touch stroke
// adds a stroke constraint.
import { mkdirSync } from 'node:fs';
import { dirname, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { expect, test } from '@playwright/test';
import { openDesigner, trackErrors } from './helpers.mjs';

const ROOT = resolve(dirname(fileURLToPath(import.meta.url)), '../..');
const OUT = resolve(ROOT, 'test-results/layout');
const PARTS = ['.toolbar', '#side-panel', '#constraints-panel', '#status', '#hint', '#view-presets'];
const OVERLAYS = ['#side-panel', '#constraints-panel', '#hint', '#view-presets']; // drawn over the canvas

// Boxes (viewport pixels) of the parts that are shown, and of the canvas.
function layout(page) {
  return page.evaluate((parts) => {
    const root = document.querySelector('tangent-field-designer').shadowRoot;
    const box = (el) => {
      const r = el.getBoundingClientRect();
      return { x0: r.left, y0: r.top, x1: r.right, y1: r.bottom };
    };
    const shown = {};
    for (const sel of parts) {
      const el = root.querySelector(sel);
      if (el && el.checkVisibility() && el.getBoundingClientRect().width > 0) shown[sel] = box(el);
    }
    return { shown, canvas: box(root.querySelector('#view')), vw: innerWidth, vh: innerHeight };
  }, PARTS);
}

const area = (b) => Math.max(0, b.x1 - b.x0) * Math.max(0, b.y1 - b.y0);
const meet = (a, b) => ({ x0: Math.max(a.x0, b.x0), y0: Math.max(a.y0, b.y0), x1: Math.min(a.x1, b.x1), y1: Math.min(a.y1, b.y1) });

function checkLayout({ shown, canvas, vw, vh }, label) {
  const names = Object.keys(shown);
  for (const n of names) {
    const b = shown[n];
    expect(b.x0, `${label}: ${n} left`).toBeGreaterThanOrEqual(0);
    expect(b.y0, `${label}: ${n} top`).toBeGreaterThanOrEqual(0);
    expect(b.x1, `${label}: ${n} right`).toBeLessThanOrEqual(vw + 0.5);
    expect(b.y1, `${label}: ${n} bottom`).toBeLessThanOrEqual(vh + 0.5);
  }
  for (let i = 0; i < names.length; i++)
    for (let j = i + 1; j < names.length; j++)
      expect(area(meet(shown[names[i]], shown[names[j]])), `${label}: ${names[i]} overlaps ${names[j]}`).toBe(0);
  // The overlays do not overlap each other (checked above), so their covers of the canvas add up.
  const visible = meet(canvas, { x0: 0, y0: 0, x1: vw, y1: vh });
  let free = area(visible);
  for (const n of OVERLAYS) if (shown[n]) free -= area(meet(visible, shown[n]));
  const fraction = free / (vw * vh);
  expect(fraction, `${label}: unobscured canvas`).toBeGreaterThanOrEqual(0.4);
  return fraction;
}

// Bounding box (canvas pixels) of what is not background in the WebGL canvas, and the canvas size.
function modelExtent(page) {
  return page.evaluate(() => {
    const src = document.querySelector('tangent-field-designer').shadowRoot.querySelector('#view');
    const w = src.width, h = src.height;
    const c = document.createElement('canvas');
    c.width = w;
    c.height = h;
    const ctx = c.getContext('2d', { willReadFrequently: true });
    ctx.drawImage(src, 0, 0);
    const data = ctx.getImageData(0, 0, w, h).data;
    let x0 = w, y0 = h, x1 = -1, y1 = -1;
    for (let y = 0; y < h; y++)
      for (let x = 0; x < w; x++) {
        const i = 4 * (y * w + x);
        if (Math.abs(data[i] - 0x1b) + Math.abs(data[i + 1] - 0x1d) + Math.abs(data[i + 2] - 0x21) > 24) {
          x0 = Math.min(x0, x); x1 = Math.max(x1, x); y0 = Math.min(y0, y); y1 = Math.max(y1, y);
        }
      }
    return { x0, y0, x1, y1, w, h };
  });
}
const settle = (page) => page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));

test.describe.serial('small screens and touch', () => {
  test.beforeAll(() => mkdirSync(OUT, { recursive: true }));

  for (const [name, width, height] of [['800x600', 800, 600], ['390x844', 390, 844]]) {
    test(`nothing overlaps at ${name}, with the panels closed and open`, async ({ browser }) => {
      const context = await browser.newContext({ viewport: { width, height }, hasTouch: width < 500 });
      const page = await context.newPage();
      const errors = trackErrors(page);
      await openDesigner(page);
      const toggle = page.getByRole('button', { name: /Panels/ });
      await expect(toggle).toBeVisible();
      await expect(page.locator('#side-panel')).toBeHidden();
      await expect(page.locator('#hint')).toBeVisible();
      await settle(page);
      const closed = checkLayout(await layout(page), `${name} closed`);
      await page.screenshot({ path: resolve(OUT, `layout-${name}-closed.png`) });
      await toggle.click();
      await expect(toggle).toHaveAttribute('aria-expanded', 'true');
      await expect(page.locator('#side-panel')).toBeVisible();
      await expect(page.locator('#constraints-panel')).toBeVisible();
      await settle(page);
      const open = checkLayout(await layout(page), `${name} open`);
      await page.screenshot({ path: resolve(OUT, `layout-${name}-open.png`) });
      // The panels' controls still work from the drawer.
      await page.locator('#show-streamlines').check();
      await expect.poll(() => page.evaluate(() => window.tvf.views().streamlines)).toBe(true);
      console.log(`${name}: unobscured canvas ${(100 * closed).toFixed(1)}% closed, ${(100 * open).toFixed(1)}% open`);
      await toggle.click();
      await expect(page.locator('#side-panel')).toBeHidden();
      expect(errors).toEqual([]);
      await context.close();
    });
  }

  test('the model stays framed when a phone turns from landscape to portrait', async ({ browser }) => {
    const context = await browser.newContext({ viewport: { width: 844, height: 390 }, hasTouch: true });
    const page = await context.newPage();
    const errors = trackErrors(page);
    await openDesigner(page);
    await page.evaluate(() => window.tvf.frame('front'));
    await settle(page);
    await page.setViewportSize({ width: 390, height: 844 });
    await expect.poll(() => page.evaluate(() => window.tvf.camera() && document.querySelector('tangent-field-designer').shadowRoot.querySelector('#view').clientWidth)).toBe(390);
    await settle(page);
    const e = await modelExtent(page);
    // Framed: background on both sides (not clipped by the now narrow width), and still a good part of it.
    expect(e.x0).toBeGreaterThan(0);
    expect(e.x1).toBeLessThan(e.w - 1);
    expect((e.x1 - e.x0) / e.w).toBeGreaterThan(0.5);
    await page.screenshot({ path: resolve(OUT, 'refit-portrait.png') });
    expect(errors).toEqual([]);
    await context.close();
  });

  test('a touch stroke on the phone adds a stroke constraint', async ({ browser }) => {
    const context = await browser.newContext({ viewport: { width: 390, height: 844 }, hasTouch: true, isMobile: true });
    const page = await context.newPage();
    const errors = trackErrors(page);
    await openDesigner(page);
    const touchAction = await page.evaluate(() =>
      getComputedStyle(document.querySelector('tangent-field-designer').shadowRoot.querySelector('#view')).touchAction);
    expect(touchAction).toBe('none');
    await page.getByRole('button', { name: 'Stroke', exact: true }).tap();
    const before = await page.evaluate(() => window.tvf.constraints().length);
    await page.evaluate(() => {
      const canvas = document.querySelector('tangent-field-designer').shadowRoot.querySelector('#view');
      window.__pointerTypes = [];
      // Capture at the window: the tools take the events at the canvas.
      window.addEventListener('pointerdown', (e) => e.composedPath()[0] === canvas && window.__pointerTypes.push(e.pointerType), true);
    });
    // Real touches through the browser's input pipeline: they arrive at the canvas as pointer events of type touch.
    const box = await page.locator('#view').boundingBox();
    const cx = box.x + box.width / 2, cy = box.y + box.height / 2;
    const cdp = await context.newCDPSession(page);
    const touch = (type, x, y) => cdp.send('Input.dispatchTouchEvent', { type, touchPoints: type === 'touchEnd' ? [] : [{ x, y, id: 1 }] });
    await touch('touchStart', cx - 0.15 * box.width, cy);
    for (let i = 1; i <= 12; i++) await touch('touchMove', cx - 0.15 * box.width + (0.3 * box.width * i) / 12, cy + 2 * i);
    await touch('touchEnd');
    await expect.poll(() => page.evaluate(() => window.tvf.constraints().length)).toBe(before + 1);
    const added = await page.evaluate(() => window.tvf.constraints().at(-1));
    expect(JSON.stringify(added)).toContain('stroke');
    expect(await page.evaluate(() => window.__pointerTypes.length)).toBeGreaterThan(0);
    expect(await page.evaluate(() => window.__pointerTypes.every((t) => t === 'touch'))).toBe(true);
    await page.screenshot({ path: resolve(OUT, 'touch-stroke-390x844.png') });
    expect(errors).toEqual([]);
    await context.close();
  });
});
