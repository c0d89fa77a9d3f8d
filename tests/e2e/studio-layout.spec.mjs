// Small screens and touch (issue 10, item 7) on the real page: at 800×600 and on a 390×844 phone nothing
// overlaps (bounding boxes of the toolbar, panels, status line, hint and view presets), everything lies in the
// viewport and at least 40% of the viewport still shows the model's canvas unobscured, with the panels closed
// (drawers) and open; the model stays framed when the view turns from landscape to portrait; a touch stroke
// adds a stroke constraint.
// Wide windows (issue 10, item 9): at 1280×800 and 1024×720 the toolbar keeps one row whichever tool is active
// (what does not fit goes into the ⋯ menu, which works from the keyboard), so the panels never move; the
// stroke ribbon and the live stroke are drawn a fixed width in pixels, the same on a coarse and a dense mesh.
import { mkdirSync } from 'node:fs';
import { dirname, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { expect, test } from '@playwright/test';
import { openDesigner, subdividedOff, readMesh, surfacePointsAlongScreenLine, trackErrors } from './helpers.mjs';

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

// The toolbar's box, the panels' tops, and where each overflowable toolbar button is now: in the row, in the ⋯
// menu (a stand-in with its name) or hidden for another reason (readonly).
function toolbarState(page) {
  return page.evaluate(() => {
    const root = document.querySelector('tangent-field-designer').shadowRoot;
    const bar = root.querySelector('.toolbar');
    const r = bar.getBoundingClientRect();
    const shown = (el) => el.checkVisibility() && el.getBoundingClientRect().width > 0;
    const menu = [...root.querySelectorAll('#more-menu [role="menuitem"]')].map((m) => m.textContent);
    const rowRight = Math.max(...[...bar.children].filter(shown).map((el) => el.getBoundingClientRect().right));
    return {
      height: r.height,
      right: r.right,
      rowRight,
      sideTop: root.querySelector('#side-panel').getBoundingClientRect().top,
      constraintsTop: root.querySelector('#constraints-panel').getBoundingClientRect().top,
      tools: [...root.querySelectorAll('[data-tool]')].every(shown),
      more: shown(root.querySelector('#more-button')),
      menu,
      missing: [...bar.querySelectorAll('button[data-overflow]')]
        .filter((b) => !shown(b) && !menu.includes(b.getAttribute('aria-label') ?? b.textContent))
        .map((b) => b.id),
    };
  });
}

const RIBBON_RGB = [0xff, 0x7a, 0x1a]; // handles.js COLORS.stroke, drawn unlit

// Width in canvas pixels of the ribbon-coloured band crossing each column from x0 to x1 (fractions of the view's
// width) within ±30 px of row y (a fraction of its height): the median over the columns it crosses, and the
// fraction of columns it crosses at all (a dotted line crosses few).
function ribbonWidth(page, { x0, x1, y }) {
  return page.evaluate(({ x0, x1, y, rgb }) => {
    const src = document.querySelector('tangent-field-designer').shadowRoot.querySelector('#view');
    const w = src.width, h = src.height;
    const c = document.createElement('canvas');
    c.width = w;
    c.height = h;
    const ctx = c.getContext('2d', { willReadFrequently: true });
    ctx.drawImage(src, 0, 0);
    const data = ctx.getImageData(0, 0, w, h).data;
    const yc = Math.round(y * h), counts = [];
    for (let x = Math.round(x0 * w); x <= Math.round(x1 * w); x++) {
      let n = 0;
      for (let yy = Math.max(0, yc - 30); yy < Math.min(h, yc + 30); yy++) {
        const i = 4 * (yy * w + x);
        if (Math.abs(data[i] - rgb[0]) + Math.abs(data[i + 1] - rgb[1]) + Math.abs(data[i + 2] - rgb[2]) < 60) n++;
      }
      counts.push(n);
    }
    const crossed = counts.filter((n) => n > 0).sort((a, b) => a - b);
    return { median: crossed.length ? crossed[Math.floor(crossed.length / 2)] : 0, coverage: crossed.length / counts.length };
  }, { x0, x1, y, rgb: RIBBON_RGB });
}

test.describe.serial('wide windows: one toolbar row, strokes in pixels', () => {
  test.beforeAll(() => mkdirSync(OUT, { recursive: true }));

  for (const [width, height] of [[1280, 800], [1024, 720]]) {
    test(`the toolbar keeps one row at ${width}×${height} with any tool active`, async ({ browser }) => {
      const context = await browser.newContext({ viewport: { width, height } });
      const page = await context.newPage();
      const errors = trackErrors(page);
      await openDesigner(page);
      await page.getByRole('button', { name: 'Orbit', exact: true }).click();
      await settle(page);
      const orbit = await toolbarState(page);
      const heights = { orbit: orbit.height };
      for (const tool of ['Stroke', 'Vortex', 'Vector', 'Source', 'Select']) {
        await page.getByRole('button', { name: tool, exact: true }).click();
        await settle(page);
        const s = await toolbarState(page);
        heights[tool.toLowerCase()] = s.height;
        expect(s.height, `${tool}: toolbar height`).toBeCloseTo(orbit.height, 1);
        expect(s.sideTop, `${tool}: settings panel top`).toBeCloseTo(orbit.sideTop, 1);
        expect(s.constraintsTop, `${tool}: constraints panel top`).toBeCloseTo(orbit.constraintsTop, 1);
        expect(s.rowRight, `${tool}: the row ends inside the toolbar`).toBeLessThanOrEqual(s.right + 0.5);
        expect(s.tools, `${tool}: every tool button shows`).toBe(true);
        expect(s.missing, `${tool}: buttons neither in the row nor in the ⋯ menu`).toEqual([]);
        expect(s.more, `${tool}: ⋯ shows exactly when it holds something`).toBe(s.menu.length > 0);
        if (tool === 'Stroke' || tool === 'Vortex') await page.screenshot({ path: resolve(OUT, `toolbar-${width}x${height}-${tool.toLowerCase()}.png`) });
      }
      // One row: a toolbar button's height plus the padding, far from two rows.
      const button = await page.getByRole('button', { name: 'Orbit', exact: true }).boundingBox();
      expect(orbit.height).toBeLessThan(1.6 * button.height + 12);
      await page.getByRole('button', { name: 'Stroke', exact: true }).click();
      const inMenu = (await toolbarState(page)).menu;
      console.log(`${width}x${height}: toolbar height ${JSON.stringify(heights)} px; panels' top ${orbit.sideTop} px; ⋯ menu with Stroke: [${inMenu.join(', ')}]`);
      expect(errors).toEqual([]);
      await context.close();
    });
  }

  test('the ⋯ menu holds what does not fit and works from the keyboard', async ({ browser }) => {
    const context = await browser.newContext({ viewport: { width: 960, height: 720 } });
    const page = await context.newPage();
    const errors = trackErrors(page);
    await openDesigner(page);
    const stroke = page.getByRole('button', { name: 'Stroke', exact: true });
    await stroke.click();
    const more = page.getByRole('button', { name: 'More', exact: true });
    await expect(more).toBeVisible();
    await expect(more).toHaveAttribute('aria-expanded', 'false');
    const menu = page.getByRole('menu', { name: 'More' });
    const items = menu.getByRole('menuitem');
    const names = await page.locator('#more-menu [role="menuitem"]').allTextContents(); // while it is closed
    expect(names).toContain('Frame');
    // Keyboard: ↓ opens on the first entry, ↓ ↑ Home End move, Escape closes and gives the focus back.
    await more.focus();
    await page.keyboard.press('ArrowDown');
    await expect(menu).toBeVisible();
    await expect(more).toHaveAttribute('aria-expanded', 'true');
    await expect(items.first()).toBeFocused();
    await page.keyboard.press('End');
    await expect(items.last()).toBeFocused();
    await page.keyboard.press('ArrowDown');
    await expect(items.first()).toBeFocused();
    await page.keyboard.press('Escape');
    await expect(menu).toBeHidden();
    await expect(more).toBeFocused();
    await expect(stroke).toHaveAttribute('aria-pressed', 'true'); // Escape closed the menu only
    // Enter opens it too; choosing Frame brings a lost model back.
    const home = await page.evaluate(() => window.tvf.camera());
    await page.evaluate(() => {
      const { target } = window.tvf.camera();
      window.tvf.setCamera({ target: [target[0] + 50, target[1] + 50, target[2]], position: [target[0] + 50, target[1] + 50, target[2] + 200] });
    });
    await page.keyboard.press('Enter');
    await expect(items.first()).toBeFocused();
    for (let i = 0; i < names.indexOf('Frame'); i++) await page.keyboard.press('ArrowDown');
    await expect(items.nth(names.indexOf('Frame'))).toBeFocused();
    await page.keyboard.press('Enter');
    await expect(menu).toBeHidden();
    const framed = await page.evaluate(() => window.tvf.camera());
    for (let k = 0; k < 3; k++) expect(framed.target[k]).toBeCloseTo(home.target[k], 5);
    // A press elsewhere closes it.
    await more.click();
    await expect(menu).toBeVisible();
    await page.locator('#status').click();
    await expect(menu).toBeHidden();
    expect(errors).toEqual([]);
    await context.close();
  });

  test('stroke ribbons and the live stroke keep their width in pixels on a coarse and a dense mesh', async ({ browser }) => {
    test.setTimeout(420_000);
    const context = await browser.newContext({ viewport: { width: 1024, height: 720 } });
    const page = await context.newPage();
    const errors = trackErrors(page);
    await openDesigner(page);
    await page.evaluate(() => window.tvf.setViews({ arrows: false }));
    const bunny = await readMesh(page);
    const line = { x0: 0.4, x1: 0.6, y: 0.5 };
    const measure = async (label) => {
      // The ribbon of a stroke through the surface points under a horizontal screen line.
      const points = await surfacePointsAlongScreenLine(page, { x0: 0.36, dx: 0.28 / 40, y: line.y, count: 40 });
      expect(points.length, `${label}: the line crosses the model`).toBeGreaterThan(30);
      const id = await page.evaluate((pts) => window.tvf.addStroke(pts), points);
      await settle(page);
      const ribbon = await ribbonWidth(page, line);
      await page.screenshot({ path: resolve(OUT, `ribbon-${label}.png`) });
      await page.evaluate((id) => window.tvf.remove(id), id);
      // The live stroke, while the mouse is still down: a little above, from left to right.
      await page.getByRole('button', { name: 'Stroke', exact: true }).click();
      const box = await page.locator('#view').boundingBox();
      const yLive = 0.45;
      await page.mouse.move(box.x + 0.38 * box.width, box.y + yLive * box.height);
      await page.mouse.down();
      await page.mouse.move(box.x + 0.62 * box.width, box.y + yLive * box.height, { steps: 40 });
      await settle(page);
      const live = await ribbonWidth(page, { ...line, y: yLive });
      await page.screenshot({ path: resolve(OUT, `live-stroke-${label}.png`) });
      await page.mouse.up();
      await expect.poll(() => page.evaluate(() => window.tvf.constraints().length)).toBe(1);
      await page.evaluate(() => window.tvf.remove(window.tvf.constraints()[0].id));
      await page.getByRole('button', { name: 'Orbit', exact: true }).click();
      return { ribbon, live };
    };

    const coarse = await measure('coarse');
    const faces = bunny.triangles.length / 3;
    await page.evaluate((text) => window.tvf.loadModel(new TextEncoder().encode(text), { name: 'bunny-x16.off', restore: false }), subdividedOff(bunny, 2));
    await expect.poll(() => page.evaluate(() => window.tvf.info().faces), { timeout: 300_000 }).toBe(16 * faces);
    const edges = await page.evaluate(() => window.tvf.info().edges);
    await page.evaluate(() => window.tvf.setViews({ arrows: false }));
    const dense = await measure('dense');
    console.log(
      `stroke ribbon width: ${coarse.ribbon.median} px (${faces} faces) / ${dense.ribbon.median} px (${16 * faces} faces, ${edges} edges), ` +
        `columns crossed ${(100 * coarse.ribbon.coverage).toFixed(0)}% / ${(100 * dense.ribbon.coverage).toFixed(0)}%; ` +
        `live stroke ${coarse.live.median} px / ${dense.live.median} px, crossed ${(100 * coarse.live.coverage).toFixed(0)}% / ${(100 * dense.live.coverage).toFixed(0)}%`,
    );
    for (const [label, r] of Object.entries({ coarse, dense })) {
      for (const kind of ['ribbon', 'live']) {
        expect(r[kind].median, `${label} ${kind}: width in pixels`).toBeGreaterThanOrEqual(3);
        expect(r[kind].coverage, `${label} ${kind}: a solid band, not dots`).toBeGreaterThan(0.9);
      }
    }
    for (const kind of ['ribbon', 'live']) {
      expect(dense[kind].median / coarse[kind].median, `${kind}: dense / coarse width`).toBeGreaterThan(0.75);
      expect(dense[kind].median / coarse[kind].median, `${kind}: dense / coarse width`).toBeLessThan(1.34);
    }
    expect(errors).toEqual([]);
    await context.close();
  });
});
