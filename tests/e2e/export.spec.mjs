// Exports in the page against independent truth: the GLB the page writes passes the Khronos glTF-Validator,
// three.js's GLTFLoader (the material preview) reads back an anisotropic physical material whose tangents
// are the solved field projected into the tangent plane (1e-6), reopening the GLB restores the design
// (one-form 1e-9), and the flow map decoded by the browser points along the stroke (2 deg) in both
// conventions. With a synthesized texture the one GLB also carries it: valid, indexed with a vertex per
// distinct (position, UV) corner, one connected surface per atlas chart, the texture where three.js's
// GLTFLoader (bundled here from node_modules, not the page's copy) finds it. The material-preview pictures of
// docs/export.md are scripts/material-preview-pictures.mjs's.
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { expect, test } from '@playwright/test';
import * as esbuild from 'esbuild';
import validator from 'gltf-validator';
import { icosphereOff } from '../icosphere.mjs';
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

// three.js's GLTFLoader, bundled for the page on its own (window.__GLTFLoader): an importer independent of the
// page's code.
async function addGltfLoader(page) {
  const { outputFiles } = await esbuild.build({
    stdin: { contents: "import { GLTFLoader } from 'three/examples/jsm/loaders/GLTFLoader.js'; window.__GLTFLoader = GLTFLoader;", resolveDir: fileURLToPath(new URL('../..', import.meta.url)) },
    bundle: true,
    write: false,
    format: 'iife',
    logLevel: 'silent',
  });
  await page.addScriptTag({ content: outputFiles[0].text });
}

// The GLB as GLTFLoader reads it: its one mesh's geometry and its base-colour image's pixels (top row first).
function loadWithThree(page, glb) {
  return page.evaluate(async (bytes) => {
    const gltf = await new Promise((resolve, reject) => new window.__GLTFLoader().parse(new Uint8Array(bytes).buffer, '', resolve, reject));
    const meshes = [];
    gltf.scene.traverse((o) => o.isMesh && meshes.push(o));
    const [mesh] = meshes;
    const g = mesh.geometry, map = mesh.material.map;
    let image = null;
    if (map) {
      const { width, height } = map.image;
      const canvas = new OffscreenCanvas(width, height);
      const ctx = canvas.getContext('2d');
      ctx.drawImage(map.image, 0, 0);
      image = { width, height, flipY: map.flipY, pixels: Array.from(ctx.getImageData(0, 0, width, height).data) };
    }
    return {
      meshes: meshes.length,
      index: g.index ? Array.from(g.index.array) : null,
      positions: Array.from(g.attributes.position.array),
      uvs: g.attributes.uv ? Array.from(g.attributes.uv.array) : null,
      attributes: Object.keys(g.attributes),
      image,
    };
  }, Array.from(glb));
}

// Faces sharing a vertex index are connected: the components of `faces` (a list of face numbers) under that.
function components(index, faces) {
  const parent = new Map();
  const find = (x) => {
    while (parent.get(x) !== x) {
      parent.set(x, parent.get(parent.get(x)));
      x = parent.get(x);
    }
    return x;
  };
  for (const f of faces) for (let k = 0; k < 3; k++) if (!parent.has(index[3 * f + k])) parent.set(index[3 * f + k], index[3 * f + k]);
  for (const f of faces) for (let k = 1; k < 3; k++) parent.set(find(index[3 * f + k]), find(index[3 * f]));
  return new Set(faces.map((f) => find(index[3 * f]))).size;
}

test('one GLB with the synthesized texture: valid, a vertex per (position, UV), one surface per chart, the texture on its faces', async ({ page }) => {
  test.setTimeout(300_000);
  const errors = trackErrors(page);
  await openDesigner(page);
  await addGltfLoader(page);
  // A closed model without UVs: the texture lives in a generated atlas of several charts.
  await page.evaluate((off) => window.tvf.loadModel(new TextEncoder().encode(off).buffer, { name: 'sphere.off', restore: false }), icosphereOff(3));
  await page.evaluate(() => window.tvf.loadDesign({ constraints: [{ type: 'source', vertex: 0, strength: 1 }, { type: 'sink', vertex: 3, strength: 1 }] }));
  await page.evaluate(() => window.tvf.setExemplar('stripes'));
  const stats = await page.evaluate(() => window.tvf.synthesize({ resolution: 128 }));
  expect(stats.atlas.source).toBe('generated');
  const { glb, mesh, rb } = await page.evaluate(async () => {
    const glb = await window.tvf.exportGlb({ size: 128 });
    const r = await window.tvf.synthesisReadback();
    const m = window.tvf.mesh();
    return {
      glb: Array.from(glb),
      mesh: { positions: Array.from(m.positions), triangles: Array.from(m.triangles) },
      rb: { resolution: r.resolution, colour: Array.from(r.colour), cornerUVs: Array.from(r.cornerUVs), faceCharts: Array.from(r.faceCharts) },
    };
  });
  expect(await page.evaluate(() => 'exportGLB' in window.tvf), 'one spelling: exportGlb').toBe(false);

  const report = await validator.validateBytes(new Uint8Array(glb), { uri: 'textured.glb', maxIssues: 50 });
  expect(report.issues.numErrors, JSON.stringify(report.issues.messages.filter((m) => m.severity === 0).slice(0, 5))).toBe(0);
  const json = JSON.parse(new TextDecoder().decode(Uint8Array.from(glb.slice(20, 20 + new DataView(Uint8Array.from(glb).buffer).getUint32(12, true)))));
  expect(json.extras.tangentFieldDesigner.flowMapTexture, 'the flow map is in the same file').toBeGreaterThanOrEqual(0);
  expect(json.extras.tangentFieldDesigner.design.constraints).toHaveLength(2);

  const three = await loadWithThree(page, glb);
  const nF = mesh.triangles.length / 3;
  expect(three.meshes).toBe(1);
  expect(three.attributes).toEqual(expect.arrayContaining(['position', 'normal', 'tangent', 'uv', '_field']));
  expect(three.image, 'GLTFLoader finds the base-colour texture').not.toBeNull();
  expect(three.image.width).toBe(2 * stats.resolution);
  expect(three.index).toHaveLength(3 * nF);
  // The loaded triangles are the core's faces, in order, at the atlas's UVs.
  const f32 = (x) => Math.fround(x);
  const corners = new Set();
  let worstUV = 0;
  for (let c = 0; c < 3 * nF; c++) {
    const i = three.index[c], v = mesh.triangles[c];
    for (let k = 0; k < 3; k++) expect(three.positions[3 * i + k]).toBe(f32(mesh.positions[3 * v + k]));
    worstUV = Math.max(worstUV, Math.abs(three.uvs[2 * i] - rb.cornerUVs[2 * c]), Math.abs(three.uvs[2 * i + 1] - rb.cornerUVs[2 * c + 1]));
    corners.add([0, 1, 2].map((k) => f32(mesh.positions[3 * v + k])).concat([f32(rb.cornerUVs[2 * c]), f32(rb.cornerUVs[2 * c + 1])]).join(' '));
  }
  expect(worstUV).toBe(0);
  const vertices = three.positions.length / 3;
  const charts = new Map();
  rb.faceCharts.forEach((chart, f) => charts.set(chart, [...(charts.get(chart) ?? []), f]));
  console.log(JSON.stringify({ faces: nF, cornersAsBefore: 3 * nF, distinctPositionUV: corners.size, glbVertices: vertices, charts: charts.size }));
  expect(vertices, 'a vertex per distinct (position, UV) corner').toBe(corners.size);
  expect(vertices).toBeLessThan(3 * nF);
  expect(charts.size).toBeGreaterThan(1);
  for (const [chart, faces] of charts) expect(components(three.index, faces), `chart ${chart}: one connected surface`).toBe(1);

  // The texture on the right faces: at each face's UV centroid, the loaded image (top row = v 0, as glTF samples
  // it) shows the synthesized colour of that atlas texel (the read-back, row 0 = v 0); flipped, it would not.
  const { width: W, height: H, pixels } = three.image;
  const R = rb.resolution;
  const agree = (flip) => {
    let n = 0;
    for (let f = 0; f < nF; f++) {
      const u = (rb.cornerUVs[6 * f] + rb.cornerUVs[6 * f + 2] + rb.cornerUVs[6 * f + 4]) / 3;
      const v = (rb.cornerUVs[6 * f + 1] + rb.cornerUVs[6 * f + 3] + rb.cornerUVs[6 * f + 5]) / 3;
      const t = 4 * (Math.floor(v * R) * R + Math.floor(u * R));
      const p = 4 * (Math.floor((flip ? 1 - v : v) * H) * W + Math.floor(u * W));
      if ([0, 1, 2].every((k) => Math.abs(pixels[p + k] - rb.colour[t + k]) < 64)) n++;
    }
    return n / nF;
  };
  const share = agree(false), flipped = agree(true);
  console.log(JSON.stringify({ textureAgreement: +share.toFixed(3), ifFlipped: +flipped.toFixed(3) }));
  expect(share).toBeGreaterThan(0.9);
  expect(flipped).toBeLessThan(share - 0.2);

  // The Texture panel's GLB button downloads the same one export.
  const [download] = await Promise.all([page.waitForEvent('download'), page.locator('#tex-glb').click()]);
  expect(download.suggestedFilename()).toBe('sphere.field.glb');
  const downloaded = readFileSync(await download.path());
  const again = await validator.validateBytes(new Uint8Array(downloaded), { uri: 'download.glb' });
  expect(again.issues.numErrors).toBe(0);
  expect(downloaded.length).toBeGreaterThan(glb.length / 2);
  expect(errors).toEqual([]);
});

test('on the model\'s own UVs the textured GLB keeps the model\'s layout; texture: false leaves it out', async ({ page }) => {
  const errors = trackErrors(page);
  await openDesigner(page);
  await loadPatchWithStroke(page);
  await page.evaluate(() => window.tvf.setExemplar('stripes'));
  const stats = await page.evaluate(() => window.tvf.synthesize({ resolution: 64 }));
  expect(stats.atlas.source).toBe('TEXCOORD_0');
  const [textured, plain] = await page.evaluate(async () =>
    [await window.tvf.exportGlb({ size: 128 }), await window.tvf.exportGlb({ size: 128, texture: false })].map((b) => Array.from(b)),
  );
  for (const [name, bytes] of [['textured', textured], ['plain', plain]]) {
    const report = await validator.validateBytes(new Uint8Array(bytes), { uri: `${name}.glb` });
    expect(report.issues.numErrors, name).toBe(0);
  }
  const jsonOf = (b) => JSON.parse(new TextDecoder().decode(Uint8Array.from(b.slice(20, 20 + new DataView(Uint8Array.from(b).buffer).getUint32(12, true)))));
  const t = jsonOf(textured), p = jsonOf(plain);
  // The source's own vertices (289) and material, with the texture as its base colour.
  expect(t.accessors[t.meshes[0].primitives[0].attributes.POSITION].count).toBe(289);
  expect(t.materials[0].name).toBe('own');
  expect(t.materials[0].pbrMetallicRoughness.baseColorTexture).toBeDefined();
  expect(p.materials[0].pbrMetallicRoughness.baseColorTexture).toBeUndefined();
  // Switched off, the texture leaves the default export; asked for, it still comes.
  await page.evaluate(() => window.tvf.clearTexture());
  const off = jsonOf(await page.evaluate(() => window.tvf.exportGlb({ size: 128 }).then((b) => Array.from(b))));
  expect(off.materials[0].pbrMetallicRoughness.baseColorTexture).toBeUndefined();
  const asked = jsonOf(await page.evaluate(() => window.tvf.exportGlb({ size: 128, texture: true }).then((b) => Array.from(b))));
  expect(asked.materials[0].pbrMetallicRoughness.baseColorTexture).toBeDefined();
  expect(errors).toEqual([]);
});
