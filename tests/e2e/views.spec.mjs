// Legible field views (issue 10, items 1, 2, 4 and 10) on the real page: arrows spaced by the screen (the
// same visible count and on-screen length on a 3.7k-face and a 59k-face model), resampled on zoom, coloured
// with viridis; screenshots in test-results/views.
import { mkdirSync, writeFileSync } from 'node:fs';
import { dirname, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { expect, test } from '@playwright/test';
import { CENTRE, cross, dot, faceCorners, facesAround, norm, readMesh, sub, subdividedOff, topFacePair, vertex, openDesignerPage } from './helpers.mjs';

const ROOT = resolve(dirname(fileURLToPath(import.meta.url)), '../..');
const OUT = resolve(ROOT, 'test-results/views');
const median = (a) => a.slice().sort((x, y) => x - y)[Math.floor(a.length / 2)];

test.describe.serial('field views', () => {
  let page, errors, bunny;
  const evaluate = (fn, arg) => page.evaluate(fn, arg);
  const settle = () => evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));

  // Arrows drawn (instances on the GPU) whose anchor projects inside the canvas, and the median length on
  // screen of those. Projection through the page's camera (window.tvf.projectToScreen).
  const visibleArrows = () =>
    evaluate(() => {
      const { anchors, vectors } = window.tvf.arrowInstances();
      const el = document.querySelector('tangent-field-designer');
      const rect = el.shadowRoot.querySelector('#view').getBoundingClientRect();
      const lengths = [];
      for (let i = 0; i < anchors.length; i += 3) {
        const a = anchors.slice(i, i + 3), v = vectors.slice(i, i + 3);
        const p = window.tvf.projectToScreen(a);
        if (p.x < rect.left || p.x > rect.right || p.y < rect.top || p.y > rect.bottom) continue;
        const h = window.tvf.projectToScreen(a.map((x, k) => x + v[k] / 2));
        const t = window.tvf.projectToScreen(a.map((x, k) => x - v[k] / 2));
        lengths.push(Math.hypot(h.x - t.x, h.y - t.y));
      }
      return { drawn: anchors.length / 3, visible: lengths.length, lengths };
    });

  // A stroke near the ears: a field with no zeros to speak of away from its singularities. On a big model
  // addStroke resolves with the preview's field on the page (a coarse stand-in's, docs/architecture.md "Big
  // meshes"), which the exact field replaces some hundreds of milliseconds later: measured on a 235k-face model
  // (the bunny subdivided three times), this stroke's preview is near zero (below the arrows' floor) on all but
  // the stroke's surroundings, 102 arrows of the same 1,508 samples. The arrows measured here are the exact
  // field's, whenever it lands.
  const addStroke = async () => {
    const mesh = await readMesh(page);
    const pair = topFacePair(mesh);
    await evaluate(([f0, f1, c]) => window.tvf.addStroke([{ face: f0, bary: c }, { face: f1, bary: c }]), [...pair, CENTRE]);
    await evaluate(() => window.tvf.settled());
    expect(await evaluate(() => window.tvf.stats().preview)).toBeFalsy();
    return mesh;
  };

  test.beforeAll(async ({ browser }) => {
    ({ page, errors } = await openDesignerPage(browser, { viewport: { width: 1024, height: 720 } }));
    mkdirSync(OUT, { recursive: true });
  });

  test.afterAll(async () => {
    expect(errors).toEqual([]);
    await page?.close();
  });

  // Every program a view draws with is made when the viewer starts (views/shader-warm-up.js): a program first
  // used later reads its uniforms back synchronously, which held the page's thread for seconds at the first
  // stroke on a big model under software GL.
  test('no view makes a new shader program on first use', async () => {
    await settle();
    const before = await evaluate(() => window.tvf.debugGlPrograms());
    const mesh = await addStroke(); // a ribbon with chevrons
    const [f0] = topFacePair(mesh);
    await evaluate((f) => window.tvf.addVector(f, [1, 0, 0]), f0); // an arrow handle
    await evaluate((v) => window.tvf.addSource(v), mesh.triangles[0]); // a marker sprite
    await evaluate(() => window.tvf.setViews({ singularities: true, colorMap: true, streamlines: true }));
    await settle();
    await evaluate(() => window.tvf.setViews({ singularities: false, colorMap: false, streamlines: false }));
    await settle();
    const after = await evaluate(() => window.tvf.debugGlPrograms());
    for (let k = 0; k < 3; k++) await evaluate(() => window.tvf.undo());
    expect(after, 'programs made after the start').toBe(before);
  });

  test('singularity markers lie on the surface at their vertex', async () => {
    const mesh = await readMesh(page);
    // A source at the vertex nearest the top: a +1 singularity there.
    let top = 0;
    for (let v = 0; v < mesh.positions.length / 3; v++) if (mesh.positions[3 * v + 1] > mesh.positions[3 * top + 1]) top = v;
    await evaluate((v) => window.tvf.addSource(v), top);
    await evaluate(() => window.tvf.setViews({ singularities: true }));
    await settle();
    const markers = await evaluate(() => window.tvf.singularityMarkers());
    const singular = await evaluate(() => window.tvf.singularities().map((s) => s.vertex));
    expect(markers.length).toBeGreaterThan(0);
    expect(markers.map((m) => m.vertex).sort()).toEqual(singular.slice(0, 400).sort());
    let meanEdge = 0;
    for (let f = 0; f < mesh.triangles.length / 3; f++) {
      const [a, b, c] = faceCorners(mesh, f);
      meanEdge += (norm(sub(b, a)) + norm(sub(c, b)) + norm(sub(a, c))) / 3;
    }
    meanEdge /= mesh.triangles.length / 3;
    let worst = 0;
    for (const { vertex: v, corners } of markers) {
      // Area-weighted vertex normal, from the mesh as the test reads it.
      const n = [0, 0, 0];
      for (const f of facesAround(mesh, v)) {
        const [a, b, c] = faceCorners(mesh, f);
        const fn = cross(sub(b, a), sub(c, a));
        for (let k = 0; k < 3; k++) n[k] += fn[k];
      }
      const l = norm(n);
      const unit = n.map((x) => x / l);
      const x = vertex(mesh, v);
      let radius = 0;
      for (let i = 0; i < corners.length; i += 3) {
        const d = sub(corners.slice(i, i + 3), x);
        worst = Math.max(worst, Math.abs(dot(d, unit)));
        radius = Math.max(radius, norm(d));
      }
      expect(radius).toBeGreaterThan(0.2 * meanEdge); // a visible disc, not a point
    }
    console.log(`markers: ${markers.length}; farthest corner from the tangent plane ${(worst / meanEdge).toFixed(4)} mean edges`);
    expect(worst).toBeLessThan(0.05 * meanEdge);
    await page.screenshot({ path: resolve(OUT, 'singularities.png') });
    await evaluate(() => window.tvf.setViews({ singularities: false }));
  });

  test('stroke ribbons carry chevrons in the stroke direction', async () => {
    const mesh = await readMesh(page);
    // A longer stroke: five face centres in a row from the top pair outwards, drawn in that order.
    const [f0, f1] = topFacePair(mesh);
    const c0 = faceCorners(mesh, f0).reduce((a, p) => a.map((x, k) => x + p[k] / 3), [0, 0, 0]);
    const c1 = faceCorners(mesh, f1).reduce((a, p) => a.map((x, k) => x + p[k] / 3), [0, 0, 0]);
    const uid = await evaluate(([a, b, c]) => window.tvf.addStroke([{ face: a, bary: c }, { face: b, bary: c }]), [f0, f1, CENTRE]);
    await settle();
    const all = await evaluate(() => window.tvf.strokeCues());
    const mine = all.find((e) => e.uid === uid) ?? all[all.length - 1];
    expect(mine.cues.length).toBeGreaterThan(0);
    const way = sub(c1, c0);
    for (const { tip, back } of mine.cues) {
      const d = sub(tip, back);
      expect(dot(d, way) / (norm(d) * norm(way))).toBeGreaterThan(0.9);
    }
    await evaluate((id) => window.tvf.remove(id), mine.uid);
  });

  test('streamlines carry chevrons that point along the field', async () => {
    await evaluate(() => window.tvf.setViews({ streamlines: true }));
    await expect.poll(() => evaluate(() => window.tvf.streamlineCues().length), { timeout: 60_000 }).toBeGreaterThan(0);
    await settle();
    const mesh = await readMesh(page);
    const { cues, lines, vectors } = await evaluate(() => ({
      cues: window.tvf.streamlineCues(),
      lines: window.tvf.streamlines(),
      vectors: Array.from(window.tvf.faceVectors()),
    }));
    // Every line long enough for one has at least one chevron.
    const long = lines.filter((l) => l.length / 3 >= 6).length;
    expect(cues.length).toBeGreaterThanOrEqual(long);
    const nF = mesh.triangles.length / 3;
    const centres = Array.from({ length: nF }, (_, f) => faceCorners(mesh, f).reduce((a, p) => a.map((x, k) => x + p[k] / 3), [0, 0, 0]));
    let along = 0;
    for (const { tip, back } of cues) {
      let best = 0, bd = Infinity;
      for (let f = 0; f < nF; f++) {
        const d = norm(sub(centres[f], tip));
        if (d < bd) (bd = d), (best = f);
      }
      const v = [vectors[3 * best], vectors[3 * best + 1], vectors[3 * best + 2]];
      const d = sub(tip, back);
      if (dot(d, v) / (norm(d) * norm(v)) > Math.cos((30 * Math.PI) / 180)) along++;
    }
    console.log(`streamline cues: ${cues.length} chevrons on ${lines.length} lines; ${along} within 30° of the field`);
    expect(along / cues.length).toBeGreaterThan(0.9);
    await page.screenshot({ path: resolve(OUT, 'streamlines.png') });
    await evaluate(() => window.tvf.setViews({ streamlines: false }));
  });

  test('arrows: the same visible count and screen length on a 3.7k- and a 59k-face model, resampled on zoom', async () => {
    test.setTimeout(300_000);
    bunny = await addStroke();
    await settle();
    const small = await visibleArrows();
    await page.screenshot({ path: resolve(OUT, 'arrows-bunny.png') });
    // The legend explains the arrow colours.
    await expect(page.locator('#legend')).toBeVisible();

    await page.setInputFiles('#file-input', { name: 'bunny-x16.off', mimeType: 'text/plain', buffer: Buffer.from(subdividedOff(bunny, 2)) });
    // The stroke is an unsaved edit: opening a model asks first.
    await page.locator('#confirm-ok').click();
    await expect.poll(() => evaluate(() => window.tvf.info().faces), { timeout: 240_000 }).toBe(16 * (bunny.triangles.length / 3));
    await addStroke();
    await settle();
    const large = await visibleArrows();
    await page.screenshot({ path: resolve(OUT, 'arrows-bunny-x16.png') });
    console.log(`arrows visible: ${small.visible} of ${small.drawn} (3.7k faces), ${large.visible} of ${large.drawn} (59k faces); ` +
      `median length ${median(small.lengths).toFixed(1)} / ${median(large.lengths).toFixed(1)} px`);

    for (const r of [small, large]) {
      expect(r.visible).toBeGreaterThan(800);
      expect(r.visible).toBeLessThan(2500);
    }
    expect(large.visible / small.visible).toBeGreaterThan(0.8);
    expect(large.visible / small.visible).toBeLessThan(1.25);
    // Same length on screen (the old arrows were a mean edge long: 4× shorter on the finer mesh).
    expect(median(large.lengths) / median(small.lengths)).toBeGreaterThan(0.85);
    expect(median(large.lengths) / median(small.lengths)).toBeLessThan(1.18);

    // Zoom in 3×: the view shows a third of the model's width. Resampled, the arrows keep their spacing and
    // length on screen; the model now fills the whole view, so more of them are visible (not 1/9 as many, as
    // without resampling, nor 9 times as many, as with the default view's samples made finer).
    await evaluate(() => {
      const { target, position } = window.tvf.camera();
      window.tvf.setCamera({ target, position: position.map((x, k) => target[k] + (x - target[k]) / 3) });
    });
    await settle();
    const zoomed = await visibleArrows();
    await page.screenshot({ path: resolve(OUT, 'arrows-zoomed.png') });
    console.log(`zoomed 3×: ${zoomed.visible} visible of ${zoomed.drawn}, median length ${median(zoomed.lengths).toFixed(1)} px`);
    expect(zoomed.visible).toBeGreaterThan(0.6 * large.visible);
    expect(zoomed.visible).toBeLessThan(4 * large.visible);
    expect(median(zoomed.lengths) / median(large.lengths)).toBeGreaterThan(0.8);
    expect(median(zoomed.lengths) / median(large.lengths)).toBeLessThan(1.25);
  });

  test('screenshot: a PNG of the chosen size, with a transparent background on request', async () => {
    await evaluate(() => window.tvf.frame('home'));
    const shots = await evaluate(async () => {
      const read = async (options) => {
        const blob = await window.tvf.screenshot(options);
        const bytes = Array.from(new Uint8Array(await blob.arrayBuffer()));
        // Decoded by the browser's own PNG decoder, then read back from a 2D canvas.
        const bitmap = await createImageBitmap(blob);
        const c = document.createElement('canvas');
        c.width = bitmap.width;
        c.height = bitmap.height;
        const g = c.getContext('2d');
        g.drawImage(bitmap, 0, 0);
        const px = (x, y) => Array.from(g.getImageData(x, y, 1, 1).data);
        const alpha = g.getImageData(0, 0, c.width, c.height).data;
        let opaque = 0;
        for (let i = 3; i < alpha.length; i += 4) if (alpha[i] === 255) opaque++;
        return { type: blob.type, bytes, width: bitmap.width, height: bitmap.height, corner: px(1, 1), opaqueFraction: opaque / (alpha.length / 4) };
      };
      const canvas = document.querySelector('tangent-field-designer').shadowRoot.querySelector('#view');
      const before = [canvas.width, canvas.height];
      const clear = await read({ width: 640, height: 360, transparent: true });
      const solid = await read({ width: 300, height: 500 });
      let refused = null;
      await window.tvf.screenshot({ width: -3, height: 10 }).catch((e) => (refused = e.message));
      return { clear, solid, refused, before, after: [canvas.width, canvas.height] };
    });
    for (const [shot, w, h] of [[shots.clear, 640, 360], [shots.solid, 300, 500]]) {
      expect(shot.type).toBe('image/png');
      // The PNG header itself (independent of the browser's decoder): signature, IHDR width and height.
      const b = Buffer.from(shot.bytes);
      expect(b.subarray(0, 8)).toEqual(Buffer.from([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a]));
      expect([b.readUInt32BE(16), b.readUInt32BE(20)]).toEqual([w, h]);
      expect([shot.width, shot.height]).toEqual([w, h]);
    }
    // Transparent: the background is alpha 0, the model opaque; otherwise everything is opaque.
    expect(shots.clear.corner[3]).toBe(0);
    expect(shots.clear.opaqueFraction).toBeGreaterThan(0.05);
    expect(shots.clear.opaqueFraction).toBeLessThan(0.9);
    expect(shots.solid.corner[3]).toBe(255);
    expect(shots.solid.opaqueFraction).toBe(1);
    expect(shots.refused).toMatch(/width must be a whole number/);
    // The view is left as it was.
    expect(shots.after).toEqual(shots.before);
    writeFileSync(resolve(OUT, 'screenshot-transparent.png'), Buffer.from(shots.clear.bytes));
  });
});
