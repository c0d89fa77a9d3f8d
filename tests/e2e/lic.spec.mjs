// Flow-texture view (issue 10, item 3) on the real page: the line integral convolution of a flat square under
// a constant field shows streaks along the field. The truth is independent of the view: the field's direction
// on screen comes from projecting the designed vector with the camera, and the streaks' direction from the
// structure tensor of the picture read back from the canvas. The perpendicular field must give perpendicular
// streaks, and with the view off the square shows no streaks at all.
import { mkdirSync, writeFileSync } from 'node:fs';
import { dirname, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { expect, test } from '@playwright/test';
import { openDesigner, trackErrors, openDesignerPage, readCanvasGrey } from './helpers.mjs';

const ROOT = resolve(dirname(fileURLToPath(import.meta.url)), '../..');
const OUT = resolve(ROOT, 'test-results/views');

// A flat n×n grid on [-1, 1]² in the z = 0 plane, facing +z (the front view looks at it), as OFF text.
function squareOff(n) {
  const v = [], f = [];
  for (let j = 0; j <= n; j++) for (let i = 0; i <= n; i++) v.push(`${-1 + (2 * i) / n} ${-1 + (2 * j) / n} 0`);
  for (let j = 0; j < n; j++)
    for (let i = 0; i < n; i++) {
      const a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      f.push(`3 ${a} ${b} ${d}`, `3 ${a} ${d} ${c}`);
    }
  return `OFF\n${v.length} ${f.length} 0\n${v.join('\n')}\n${f.join('\n')}\n`;
}

// Structure tensor of the canvas's grey levels inside the screen box of [-0.6, 0.6]² (Scharr derivatives).
// Returns the streak direction (perpendicular to the dominant gradient) in degrees, in screen coordinates
// (x right, y down), modulo 180, with the coherence (λ1 − λ2) / (λ1 + λ2) and the grey levels' spread.
function streaks(page) {
  return page.evaluate(() => {
    const tvf = window.tvf;
    const src = document.querySelector('tangent-field-designer').shadowRoot.querySelector('#view');
    const rect = src.getBoundingClientRect();
    const sx = src.width / rect.width, sy = src.height / rect.height;
    const a = tvf.projectToScreen([-0.6, -0.6, 0]), b = tvf.projectToScreen([0.6, 0.6, 0]);
    const x0 = Math.ceil((Math.min(a.x, b.x) - rect.left) * sx), x1 = Math.floor((Math.max(a.x, b.x) - rect.left) * sx);
    const y0 = Math.ceil((Math.min(a.y, b.y) - rect.top) * sy), y1 = Math.floor((Math.max(a.y, b.y) - rect.top) * sy);
    const c = document.createElement('canvas');
    c.width = src.width;
    c.height = src.height;
    const ctx = c.getContext('2d', { willReadFrequently: true });
    ctx.drawImage(src, 0, 0);
    const w = x1 - x0, h = y1 - y0;
    const d = ctx.getImageData(x0, y0, w, h).data;
    const g = new Float64Array(w * h);
    for (let i = 0; i < w * h; i++) g[i] = (d[4 * i] + d[4 * i + 1] + d[4 * i + 2]) / 3;
    let jxx = 0, jxy = 0, jyy = 0, sum = 0, sum2 = 0;
    for (let y = 1; y < h - 1; y++)
      for (let x = 1; x < w - 1; x++) {
        // Scharr derivatives: nearly isotropic, so the measured angle has no pull towards the axes or diagonals.
        const at = (dx, dy) => g[(y + dy) * w + x + dx];
        const gx = 3 * (at(1, -1) - at(-1, -1) + at(1, 1) - at(-1, 1)) + 10 * (at(1, 0) - at(-1, 0));
        const gy = 3 * (at(-1, 1) - at(-1, -1) + at(1, 1) - at(1, -1)) + 10 * (at(0, 1) - at(0, -1));
        jxx += gx * gx; jxy += gx * gy; jyy += gy * gy;
        sum += g[y * w + x]; sum2 += g[y * w + x] ** 2;
      }
    const n = (w - 2) * (h - 2);
    const gradient = 0.5 * Math.atan2(2 * jxy, jxx - jyy);
    const root = Math.hypot(jxx - jyy, 2 * jxy);
    const deg = ((((gradient + Math.PI / 2) * 180) / Math.PI) % 180 + 180) % 180;
    return { deg, coherence: root / (jxx + jyy || 1), spread: Math.sqrt(Math.max(0, sum2 / n - (sum / n) ** 2)), box: [x0, y0, w, h] };
  });
}
const angleGap = (a, b) => { const d = Math.abs(a - b) % 180; return Math.min(d, 180 - d); };

// The grey levels of the central box (40 % of each side) of the canvas, row by row, with the box's width.
async function centreGrey(page) {
  const img = await readCanvasGrey(page);
  const w = Math.floor(0.4 * img.w), h = Math.floor(0.4 * img.h);
  const x0 = Math.floor(0.3 * img.w), y0 = Math.floor(0.3 * img.h);
  const grey = [];
  for (let y = y0; y < y0 + h; y++) grey.push(...img.grey.slice(y * img.w + x0, y * img.w + x0 + w));
  return { w, grey };
}

// Fine detail: the mean absolute difference between a pixel and the mean of its four neighbours.
function detail({ w, grey }) {
  const h = grey.length / w;
  let sum = 0;
  for (let y = 1; y < h - 1; y++)
    for (let x = 1; x < w - 1; x++) {
      const i = y * w + x;
      sum += Math.abs(grey[i] - (grey[i - 1] + grey[i + 1] + grey[i - w] + grey[i + w]) / 4);
    }
  return sum / ((w - 2) * (h - 2));
}

// The share of pixels whose grey level differs by more than 24 between two pictures of the same box.
const changed = (a, b) => a.grey.filter((g, i) => Math.abs(g - b.grey[i]) > 24).length / a.grey.length;

test.describe.serial('flow-texture view', () => {
  let page, errors;
  const evaluate = (fn, arg) => page.evaluate(fn, arg);
  const settle = () => evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));

  test.beforeAll(async ({ browser }) => {
    ({ page, errors } = await openDesignerPage(browser, { viewport: { width: 1024, height: 720 } }));
    mkdirSync(OUT, { recursive: true });
    await evaluate((text) => window.tvf.loadModel(new TextEncoder().encode(text), { name: 'square.off', restore: false }), squareOff(24));
    await evaluate(() => window.tvf.setViews({ arrows: false, streamlines: false, singularities: false, colorMap: false }));
  });

  test.afterAll(async () => {
    expect(errors).toEqual([]);
    await page?.close();
  });

  const results = {};
  for (const degrees of [30, 120]) {
    test(`streaks follow a constant field at ${degrees}°`, async () => {
      await evaluate(async (deg) => {
        const tvf = window.tvf;
        for (const c of tvf.constraints()) await tvf.remove(c.id);
        const t = (deg * Math.PI) / 180;
        // The same vector on faces spread over the square: the smoothest field is that constant vector.
        const faces = tvf.mesh().triangles.length / 3;
        for (const f of [0, Math.floor(faces / 3), Math.floor(faces / 2), Math.floor((2 * faces) / 3), faces - 1])
          await tvf.addVector(f, [Math.cos(t), Math.sin(t), 0], { weight: 1e6 });
        tvf.frame('front');
        tvf.setViews({ lic: true });
      }, degrees);
      await settle();
      // Truth: the field's direction on screen, from the camera's projection of the designed vector.
      const expected = await evaluate((deg) => {
        const t = (deg * Math.PI) / 180;
        const a = window.tvf.projectToScreen([0, 0, 0]), b = window.tvf.projectToScreen([0.2 * Math.cos(t), 0.2 * Math.sin(t), 0]);
        return ((((Math.atan2(b.y - a.y, b.x - a.x) * 180) / Math.PI) % 180) + 180) % 180;
      }, degrees);
      // The solved field really is the constant one (else the truth above would be wrong).
      const vv = await evaluate(() => window.tvf.vertexVectors());
      const t = (degrees * Math.PI) / 180;
      let sx = 0, sy = 0;
      for (let v = 0; v < vv.length / 3; v++) (sx += vv[3 * v]), (sy += vv[3 * v + 1]);
      console.log(`mean field angle ${((Math.atan2(sy, sx) * 180) / Math.PI).toFixed(3)}°`);
      for (let v = 0; v < vv.length / 3; v++) {
        const m = Math.hypot(vv[3 * v], vv[3 * v + 1]);
        expect((vv[3 * v] * Math.cos(t) + vv[3 * v + 1] * Math.sin(t)) / m).toBeGreaterThan(0.999);
      }
      const s = await streaks(page);
      console.log(`LIC ${degrees}°: expected ${expected.toFixed(2)}°, streaks ${s.deg.toFixed(2)}°, coherence ${s.coherence.toFixed(3)}, grey spread ${s.spread.toFixed(1)}, box ${s.box}`);
      expect(angleGap(s.deg, expected)).toBeLessThan(3);
      expect(s.coherence).toBeGreaterThan(0.3);
      results[degrees] = s.deg;
      const png = await evaluate(async () => {
        const blob = await window.tvf.screenshot({ width: 600, height: 450 });
        return Array.from(new Uint8Array(await blob.arrayBuffer()));
      });
      writeFileSync(resolve(OUT, `lic-square-${degrees}.png`), Buffer.from(png));
    });
  }

  test('the perpendicular field gives perpendicular streaks; with the view off there are none', async () => {
    expect(angleGap(results[30], results[120])).toBeGreaterThan(87);
    await evaluate(() => window.tvf.setViews({ lic: false }));
    await expect(page.locator('#show-lic')).not.toBeChecked();
    await settle();
    const off = await streaks(page);
    expect(off.spread).toBeLessThan(3); // a plainly shaded flat square
  });

  test('the checkbox turns the view on, on the bunny too', async () => {
    await evaluate(() => window.tvf.loadModel('models/bunny.glb', { restore: false }));
    await evaluate(async () => {
      const n = window.tvf.mesh().positions.length / 3;
      await window.tvf.addSource(0);
      await window.tvf.addSink(Math.floor(n / 2));
      window.tvf.setViews({ arrows: true });
    });
    await page.locator('#show-lic').check();
    await expect.poll(() => evaluate(() => window.tvf.views().lic)).toBe(true);
    await settle();
    const png = await evaluate(async () => {
      const blob = await window.tvf.screenshot({ width: 640, height: 480 });
      return Array.from(new Uint8Array(await blob.arrayBuffer()));
    });
    writeFileSync(resolve(OUT, 'lic-bunny.png'), Buffer.from(png));
    // Read back from the canvas: the arrows in front of the surface stay visible through the flow texture (it
    // is depth-tested), and the flow texture itself puts fine streaks on the bunny that plain shading has not.
    const withArrows = await centreGrey(page);
    await evaluate(() => window.tvf.setViews({ arrows: false }));
    await settle();
    const licOnly = await centreGrey(page);
    await evaluate(() => window.tvf.setViews({ lic: false }));
    await settle();
    const plain = await centreGrey(page);
    const measured = { arrowsChange: changed(withArrows, licOnly), licDetail: detail(licOnly), plainDetail: detail(plain) };
    console.log(`LIC on the bunny: ${JSON.stringify(measured)}`);
    expect(measured.arrowsChange, 'share of the centre the arrows change').toBeGreaterThan(0.01);
    expect(measured.licDetail, 'fine detail with the flow texture vs plain shading').toBeGreaterThan(2 * measured.plainDetail);
  });
});

// Issue 10, item 9: the texture status belongs to the current model. After a texture on the bunny, opening
// another model must not leave the bunny's atlas numbers in the status line.
test('the texture status is cleared when another model loads', async ({ page }) => {
  const errors = trackErrors(page);
  await openDesigner(page);
  await page.evaluate(() => window.tvf.setTextureAutoUpdate(false));
  await page.evaluate(() => window.tvf.synthesize({ resolution: 64 }));
  const status = page.locator('#tex-status');
  await expect(status).toContainText('atlas');
  const bunnyStatus = await status.textContent();
  await page.evaluate((text) => window.tvf.loadModel(new TextEncoder().encode(text), { name: 'square.off', restore: false }), squareOff(6));
  await expect(status).not.toHaveText(bunnyStatus);
  await expect(status).toHaveText('No texture for this model yet: Synthesize makes one.');
  // Synthesizing again gives the square's own numbers.
  await page.evaluate(() => window.tvf.synthesize({ resolution: 64 }));
  await expect(status).toContainText('atlas');
  // With the texture turned off, the last numbers stay until another model loads.
  await page.evaluate(() => window.tvf.clearTexture());
  const squareStatus = await status.textContent();
  expect(squareStatus).toContain('atlas');
  await page.evaluate(() => window.tvf.loadModel('models/bunny.glb', { restore: false }));
  await expect(status).toHaveText('No texture yet.');
  expect(errors).toEqual([]);
});
