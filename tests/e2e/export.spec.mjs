// Exports in the page against independent truth: the GLB the page writes passes the Khronos glTF-Validator,
// three.js's GLTFLoader (the material preview) reads back an anisotropic physical material whose tangents
// are the solved field projected into the tangent plane (1e-6), reopening the GLB restores the design
// (one-form 1e-9), and the flow map decoded by the browser points along the stroke (2 deg) in both
// conventions. TVF_DOC_PICTURES=1 also writes the material-preview pictures in docs/images/.
import { mkdirSync, readFileSync } from 'node:fs';
import { expect, test } from '@playwright/test';
import validator from 'gltf-validator';
import { diagonalStrokeDesign, patchGlb } from '../node/export-fixtures.mjs';
import { openDesigner, trackErrors } from './helpers.mjs';

const warpedUV = (x, y) => [0.05 + 0.8 * x + 0.1 * y * y, 0.05 + 0.7 * y + 0.1 * x];
const unit = (a) => {
  const l = Math.hypot(...a);
  return a.map((x) => x / l);
};
const degrees = (a, b) => (Math.acos(Math.max(-1, Math.min(1, unit(a).reduce((s, x, i) => s + x * unit(b)[i], 0)))) * 180) / Math.PI;

async function loadPatchWithStroke(page) {
  const bytes = Array.from(patchGlb());
  await page.evaluate((b) => window.tvf.loadModel(new Uint8Array(b).buffer, { name: 'patch.glb', restore: false }), bytes);
  await page.evaluate((d) => window.tvf.loadDesign(d), diagonalStrokeDesign());
}

test('the GLB reads back as an anisotropic material along the field and reopens with its design', async ({ page }) => {
  const errors = trackErrors(page);
  await openDesigner(page);
  await loadPatchWithStroke(page);

  const glb = await page.evaluate(() => window.tvf.exportGlb({ size: 128 }).then((b) => Array.from(b)));
  const report = await validator.validateBytes(new Uint8Array(glb), { uri: 'page.glb' });
  expect(report.issues.numErrors, JSON.stringify(report.issues.messages.slice(0, 5))).toBe(0);

  await page.evaluate(() => window.tvf.materialPreview('brushed metal'));
  const info = await page.evaluate(() => window.tvf.materialPreviewInfo());
  const field = await page.evaluate(() => Array.from(window.tvf.vertexVectors()));
  expect(info.meshes).toHaveLength(1);
  const [mesh] = info.meshes;
  expect(mesh.material.isMeshPhysicalMaterial).toBe(true);
  expect(mesh.material.anisotropy).toBeCloseTo(1, 12);
  expect(mesh.material.anisotropyRotation).toBe(0);
  expect(mesh.material.hasEnvMap).toBe(true);
  // The fixture's node scales uniformly by 2: local and world directions agree. Welded = source vertices.
  let worstTangent = 0, worstField = 0;
  const nV = mesh.positions.length / 3;
  expect(field.length).toBe(3 * nV);
  for (let v = 0; v < nV; v++) {
    const n = mesh.normals.slice(3 * v, 3 * v + 3);
    const u = field.slice(3 * v, 3 * v + 3);
    const un = u[0] * n[0] + u[1] * n[1] + u[2] * n[2];
    const expected = unit([u[0] - un * n[0], u[1] - un * n[1], u[2] - un * n[2]]);
    const t = mesh.tangents.slice(4 * v, 4 * v + 3);
    expect(mesh.tangents[4 * v + 3]).toBe(1);
    worstTangent = Math.max(worstTangent, ...t.map((x, k) => Math.abs(x - expected[k])));
    // _FIELD holds the local field: the world field divided by the node's scale.
    const f = mesh.field.slice(3 * v, 3 * v + 3);
    worstField = Math.max(worstField, ...f.map((x, k) => Math.abs(2 * x - u[k]) / Math.max(1e-12, Math.hypot(...u))));
  }
  console.log(`tangents vs the field: max component difference ${worstTangent.toExponential(2)}; _FIELD ${worstField.toExponential(2)}`);
  expect(worstTangent).toBeLessThan(1e-6);
  expect(worstField).toBeLessThan(1e-6);

  // Reopening the exported GLB restores the design.
  const before = await page.evaluate(() => Array.from(window.tvf.oneForm()));
  await page.evaluate((b) => window.tvf.loadModel(new Uint8Array(b).buffer, { name: 'patch.field.glb' }), glb);
  const after = await page.evaluate(() => ({ oneForm: Array.from(window.tvf.oneForm()), constraints: window.tvf.constraints().length }));
  expect(after.constraints).toBe(1);
  expect(after.oneForm.length).toBe(before.length);
  const worst = Math.max(...after.oneForm.map((c, e) => Math.abs(c - before[e])));
  console.log(`one-form after reopening: max difference ${worst.toExponential(2)}`);
  expect(worst).toBeLessThan(1e-9);
  expect(errors).toEqual([]);
});

test('the page flow map points along the stroke in both conventions', async ({ page }) => {
  await openDesigner(page);
  await loadPatchWithStroke(page);
  const n = 256;
  const stroke = diagonalStrokeDesign().constraints[0].points;
  // The stroke's (x, y) samples before the node transform, as the fixture placed them.
  const xy = stroke.map((_, s) => {
    const x = 0.15 + (0.7 * s) / 24;
    return [x, 0.3 + 0.4 * x];
  });
  for (const convention of ['gltf', 'opengl']) {
    const rgba = await page.evaluate(async ([size, convention]) => {
      const png = await window.tvf.exportFlowMap({ size, convention, bits: 8 });
      const bitmap = await createImageBitmap(new Blob([png], { type: 'image/png' }), { premultiplyAlpha: 'none', colorSpaceConversion: 'none' });
      const canvas = new OffscreenCanvas(size, size);
      const ctx = canvas.getContext('2d');
      ctx.drawImage(bitmap, 0, 0);
      return Array.from(ctx.getImageData(0, 0, size, size).data);
    }, [n, convention]);
    let worst = 0;
    for (let s = 0; s + 1 < xy.length; s++) {
      const a = warpedUV(...xy[s]), b = warpedUV(...xy[s + 1]);
      const mid = [(a[0] + b[0]) / 2, (a[1] + b[1]) / 2];
      const x = Math.floor(mid[0] * n), y = Math.floor(mid[1] * n); // image row y holds v = (y + 0.5) / n
      const i = 4 * (y * n + x);
      expect(rgba[i + 3]).toBe(255);
      const g = rgba[i + 1] / 127.5 - 1;
      const decoded = [rgba[i] / 127.5 - 1, convention === 'gltf' ? g : -g];
      worst = Math.max(worst, degrees(decoded, [b[0] - a[0], b[1] - a[1]]));
    }
    console.log(`page flow map (${convention}): worst deviation from the stroke ${worst.toFixed(2)} deg`);
    expect(worst).toBeLessThan(2);
  }
  // The Export panel's buttons download the same files.
  await page.locator('#export-panel summary').click();
  await page.locator('#export-size').selectOption('256');
  await page.locator('#export-bits').selectOption('16');
  const [pngDownload] = await Promise.all([page.waitForEvent('download'), page.locator('#export-flowmap').click()]);
  expect(pngDownload.suggestedFilename()).toBe('patch.flow-gltf-256.png');
  const png = readFileSync(await pngDownload.path());
  expect(png.subarray(1, 4).toString()).toBe('PNG');
  expect(png.readUInt32BE(16)).toBe(256); // IHDR width
  expect(png[24]).toBe(16); // bit depth
  const [glbDownload] = await Promise.all([page.waitForEvent('download'), page.locator('#export-glb').click()]);
  expect(glbDownload.suggestedFilename()).toBe('patch.field.glb');
  const report = await validator.validateBytes(new Uint8Array(readFileSync(await glbDownload.path())), { uri: 'download.glb' });
  expect(report.issues.numErrors).toBe(0);
});

test('material preview pictures', async ({ page }) => {
  test.skip(!process.env.TVF_DOC_PICTURES, 'set TVF_DOC_PICTURES=1 to write docs/images/material-preview-*.png');
  await openDesigner(page);
  // A source at the lowest and a sink at the highest vertex of the default model: a field that sweeps over
  // the whole surface, so the highlights wrap around it.
  const [low, high] = await page.evaluate(() => {
    const { positions } = window.tvf.mesh();
    let lo = 0, hi = 0;
    for (let v = 0; v < positions.length / 3; v++) {
      if (positions[3 * v + 1] < positions[3 * lo + 1]) lo = v;
      if (positions[3 * v + 1] > positions[3 * hi + 1]) hi = v;
    }
    return [lo, hi];
  });
  await page.evaluate(([lo, hi]) => window.tvf.loadDesign({ constraints: [{ type: 'source', vertex: lo, strength: 1 }, { type: 'sink', vertex: hi, strength: 1 }] }), [low, high]);
  await page.evaluate(() => window.tvf.setViews({ arrows: false }));
  // The picture is of the model: panels and handles out of the way.
  await page.evaluate(() => {
    const style = document.createElement('style');
    style.textContent = '#side-panel, #constraints-panel { display: none !important; }';
    window.tvf.shadowRoot.append(style);
  });
  mkdirSync('docs/images', { recursive: true });
  for (const preset of ['brushed metal', 'satin']) {
    await page.evaluate((p) => window.tvf.materialPreview(p), preset);
    await page.locator('#view').screenshot({ path: `docs/images/material-preview-${preset.replace(' ', '-')}.png` });
  }
});
