// The 3D view, zoomed in on the flat square (TEXCOORD_0 = (x, y)) to 24 screen pixels per atlas texel, shows no
// texel-sized steps: the surface is shaded per pixel from the synthesized coordinates (magnification), not from
// a colour image at atlas resolution. Read back from a screenshot of the real view, whose pixels are mapped to
// atlas coordinates by the camera placed straight above the square (a plane parallel to the image plane maps
// affinely to the screen). The truth the statistics are read against: the same coordinates shaded per texel
// (each pixel from its own texel's patch only), which does step at texel boundaries.
import { expect, test } from '@playwright/test';
import { flatSquareGlb } from '../node/export-fixtures.mjs';
import { openDesignerPage } from './helpers.mjs';
import { decodePng } from './surface-texture-metrics.mjs';

const R = 64; // atlas resolution
const SIDE = 768; // screenshot pixels
const VISIBLE = 0.5; // model units across the screenshot: the square is [0, 1]^2, so 24 pixels per texel
const CENTRE = 0.6; // of the view, on the square's diagonal: the vector constraint's handle on face 0 stays out

// Share of large colour jumps (sum of RGB differences > big, about a fifth of the stripes' contrast) between neighbouring pixels, split by whether the
// pair straddles an atlas texel boundary or lies inside one texel. uvOf(x, y) gives the pixel centre's (u, v).
function texelStepStatistics({ width, height, pixels }, uvOf, big = 30) {
  let across = 0, nAcross = 0, inside = 0, nInside = 0;
  const texel = (x, y) => uvOf(x, y).map((t) => Math.floor(t * R));
  const jump = (i, j) => Math.abs(pixels[i] - pixels[j]) + Math.abs(pixels[i + 1] - pixels[j + 1]) + Math.abs(pixels[i + 2] - pixels[j + 2]);
  for (let y = 0; y < height - 1; y++)
    for (let x = 0; x < width - 1; x++) {
      const i = 4 * (y * width + x), [tu, tv] = texel(x, y);
      for (const [dx, dy] of [[1, 0], [0, 1]]) {
        const [su, sv] = texel(x + dx, y + dy);
        const large = jump(i, i + 4 * (dy * width + dx)) > big ? 1 : 0;
        if (su !== tu || sv !== tv) (across += large), nAcross++;
        else (inside += large), nInside++;
      }
    }
  return { across: across / nAcross, inside: inside / nInside, pairsAcross: nAcross };
}

test.describe.serial('zoomed 3D view of the textured flat square', () => {
  let page, errors;

  test.beforeAll(async ({ browser }) => {
    ({ page, errors } = await openDesignerPage(browser));
    await page.evaluate((bytes) => window.tvf.loadModel(new Uint8Array(bytes), { name: 'flat-square.glb' }), Array.from(flatSquareGlb(8)));
    await page.evaluate(() => window.tvf.setExemplar('stripes'));
  });

  test.afterAll(async () => {
    await page?.close();
  });

  test(`${SIDE / (VISIBLE * R)} screen pixels per atlas texel: no texel-sized steps in the view`, async ({}, testInfo) => {
    const t = (30 * Math.PI) / 180;
    await page.evaluate((v) => window.tvf.loadDesign({ boundary: 'free', gamma: 0, constraints: [{ type: 'vector', face: 0, vector: v, weight: 1e4 }] }), [Math.cos(t), Math.sin(t), 0]);
    // A small atlas and a small feature scale: many patch seams per texel row, where per-texel shading steps.
    const stats = await page.evaluate((R) => window.tvf.synthesize({ resolution: R, featureScale: 0.5 }), R);
    expect(stats.resolution).toBe(R);
    await page.evaluate(() => window.tvf.setViews({ arrows: false, streamlines: false, lic: false, colorMap: false, singularities: false }));
    // Straight above a point of the square, looking down -z with +y up.
    const { fov } = await page.evaluate(() => window.tvf.camera());
    const dist = VISIBLE / 2 / Math.tan((fov * Math.PI) / 360);
    await page.evaluate((p) => window.tvf.setCamera(p), { position: [CENTRE, CENTRE, dist], target: [CENTRE, CENTRE, 0] });
    const bytes = await page.evaluate(async (side) => Array.from(new Uint8Array(await (await window.tvf.screenshot({ width: side, height: side })).arrayBuffer())), SIDE);
    testInfo.attach('view-zoomed.png', { body: Buffer.from(bytes), contentType: 'image/png' });
    if (process.env.TVF_ZOOM_PNG) (await import('node:fs')).writeFileSync(process.env.TVF_ZOOM_PNG, Buffer.from(bytes));
    const image = decodePng(bytes);
    expect(image.width).toBe(SIDE);
    // Pixel centre -> model (x, y) = TEXCOORD_0 (u, v): screen right is +x, screen down is -y.
    const uvOf = (x, y) => [CENTRE + VISIBLE * ((x + 0.5) / SIDE - 0.5), CENTRE - VISIBLE * ((y + 0.5) / SIDE - 0.5)];

    // The picture is the texture (not the background, not a flat colour): the stripes' two tones are both there.
    let dark = 0, light = 0;
    for (let i = 0; i < image.pixels.length; i += 4) {
      const g = image.pixels[i] + image.pixels[i + 1] + image.pixels[i + 2];
      if (g < 240) dark++;
      else if (g > 400) light++;
    }
    const n = image.pixels.length / 4;
    expect(dark / n, 'dark stripe pixels').toBeGreaterThan(0.1);
    expect(light / n, 'light stripe pixels').toBeGreaterThan(0.1);

    const view = texelStepStatistics(image, uvOf);
    // The contrast: the synthesized coordinates shaded per texel at the same pixels (exemplar colours, no light).
    const r = await page.evaluate(async () => {
      const r = await window.tvf.synthesisReadback();
      return { coords: Array.from(r.coords), jacobian: Array.from(r.jacobian), exemplar: Array.from(r.exemplar), m: r.exemplarSize, R: r.resolution };
    });
    expect(r.R).toBe(R);
    const { coords, jacobian, exemplar, m } = r;
    const bilinear = (cx, cy, k) => {
      const x0 = Math.floor(cx - 0.5), y0 = Math.floor(cy - 0.5), fx = cx - 0.5 - x0, fy = cy - 0.5 - y0;
      const at = (x, y) => exemplar[4 * ((((y % m) + m) % m) * m + (((x % m) + m) % m)) + k];
      return (1 - fy) * ((1 - fx) * at(x0, y0) + fx * at(x0 + 1, y0)) + fy * ((1 - fx) * at(x0, y0 + 1) + fx * at(x0 + 1, y0 + 1));
    };
    const px = new Uint8Array(SIDE * SIDE * 4);
    for (let y = 0; y < SIDE; y++)
      for (let x = 0; x < SIDE; x++) {
        // Atlas texel (tx, ty) covers [tx, tx + 1] x [ty, ty + 1] / R with v = 0 at the image's row 0.
        const [u, v] = uvOf(x, y), X = u * R, Y = v * R, tx = Math.floor(X), ty = Math.floor(Y), t = 4 * (ty * R + tx);
        const dx = X - tx - 0.5, dy = Y - ty - 0.5;
        const cx = coords[t] + jacobian[t] * dx + jacobian[t + 2] * dy, cy = coords[t + 1] + jacobian[t + 1] * dx + jacobian[t + 3] * dy;
        for (let k = 0; k < 3; k++) px[4 * (y * SIDE + x) + k] = Math.round(bilinear(cx, cy, k));
      }
    const perTexel = texelStepStatistics({ width: SIDE, height: SIDE, pixels: px }, uvOf);
    console.log(JSON.stringify({ pixelsPerTexel: SIDE / (VISIBLE * R), largeJumpShare: { view, perTexel } }));
    expect(perTexel.across, 'per-texel shading steps at texel boundaries (the test can see steps)').toBeGreaterThan(Math.max(3 * perTexel.inside, 1e-3));
    expect(view.across, 'the view: no texel-sized steps').toBeLessThan(Math.max(2 * view.inside, 1e-4));
    expect(view.across).toBeLessThan(perTexel.across / 10);
  });

  test('no console errors', () => {
    expect(errors).toEqual([]);
  });
});
