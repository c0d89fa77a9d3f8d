// The quad meshers' files from the page (issue 44, item 5; docs/export.md) against the real wasm core in its
// worker: the Export panel's .sing, .rosy and .sharp buttons download what exportSing(), exportRosy() and
// exportSharp() give, and each file, parsed here by the formats' readers' rules, holds what the page's own
// field and design hold (the singularities with their indices, every face's direction up to a quarter turn,
// both sides of every feature edge in use, convex on a box); .rosy is disabled with its reason and refused by
// name unless the field is a cross field. A .sing file opened on the page adds its singularities as one undo
// step, and a bad one is refused in the banner with the design unchanged. The Field panel's "Only prescribed
// singularities" toggles exactSingularities with undo: a torus's cross field then has none.
import { execFileSync } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { expect, test } from '@playwright/test';
import { boxOff } from '../box.mjs';
import { icosphereOff } from '../icosphere.mjs';
import { cross, dot, faceNormal, norm, openDesignerPage, readMesh, sub, vertex } from './helpers.mjs';

const ROOT = resolve(dirname(fileURLToPath(import.meta.url)), '../..');
const CROSS = { boundary: 'free', gamma: 0, symmetry: 4, featureAngle: 35, constraints: [] };


// A torus (chi = 0), n segments around, m around the tube.
function torusOff(n, m, R = 2, r = 0.7) {
  const verts = [], faces = [];
  const at = (a, b) => ((a + n) % n) * m + ((b + m) % m);
  for (let i = 0; i < n; i++)
    for (let j = 0; j < m; j++) {
      const [u, v] = [(2 * Math.PI * i) / n, (2 * Math.PI * j) / m];
      verts.push([(R + r * Math.cos(v)) * Math.cos(u), (R + r * Math.cos(v)) * Math.sin(u), r * Math.sin(v)]);
      faces.push(`3 ${at(i, j)} ${at(i + 1, j)} ${at(i + 1, j + 1)}`, `3 ${at(i, j)} ${at(i + 1, j + 1)} ${at(i, j + 1)}`);
    }
  return `OFF\n${verts.length} ${faces.length} 0\n${verts.map((p) => p.join(' ')).join('\n')}\n${faces.join('\n')}\n`;
}

// Directional's .sing (read_singularities): "N count", then "vertex k" per singularity of index k / N.
function parseSing(text) {
  const [head, ...lines] = text.trim().split('\n');
  const [n, count] = head.split(/\s+/).map(Number);
  const entries = lines.map((l) => l.trim().split(/\s+/).map(Number));
  expect(entries.length).toBe(count);
  return { n, entries };
}

// QuadWild's .sharp (LoadSharpFeatures): a count, then "type,face,corner" per face side on a feature.
function parseSharp(text) {
  const [head, ...lines] = text.trim().split('\n');
  const entries = lines.filter((l) => l.trim()).map((l) => l.split(',').map(Number));
  expect(entries.length).toBe(Number(head));
  return entries;
}

const edgeKey = (a, b) => (a < b ? `${a},${b}` : `${b},${a}`);

test.describe.serial('the quad meshers files and .sing files on the page', () => {
  let page, errors;
  const evaluate = (fn, arg) => page.evaluate(fn, arg);
  const refusal = (fn, arg) => page.evaluate(fn, arg).then(() => 'resolved', (err) => err.message);

  async function loadOff(text, name, design = CROSS) {
    await evaluate(([text, name]) => window.tvf.loadModel(new TextEncoder().encode(text), { name, restore: false }), [
      text,
      name,
    ]);
    await evaluate((d) => window.tvf.loadDesign(d), design);
    return readMesh(page);
  }

  async function download(button) {
    const [file] = await Promise.all([page.waitForEvent('download'), page.locator(button).click()]);
    return { name: file.suggestedFilename(), text: readFileSync(await file.path(), 'utf8') };
  }

  test.beforeAll(async ({ browser }) => {
    ({ page, errors } = await openDesignerPage(browser));
  });
  test.afterAll(async () => {
    expect(errors).toEqual([]);
    await page.close();
  });

  test('Export writes .sing, .rosy and .sharp: the API bytes, holding the field and features the page has', async () => {
    const n = 6;
    const off = boxOff(n);
    const mesh = await loadOff(off, 'box.off');
    // A +/- pair at the centres of two sides of the box, away from the faces the creases hold, besides what the
    // field places.
    const centre = (p) =>
      [...Array(mesh.positions.length / 3).keys()].find((v) => norm(sub(vertex(mesh, v), p)) < 1e-9) ?? -1;
    const plus = centre([0, 0, 1]), minus = centre([0, 0, -1]);
    expect(Math.min(plus, minus)).toBeGreaterThanOrEqual(0);
    await evaluate(([a, b]) => Promise.all([window.tvf.addSingularity(a, 0.25), window.tvf.addSingularity(b, -0.25)]),
      [plus, minus]);

    const api = await evaluate(async () => ({
      sing: await window.tvf.exportSing(),
      rosy: await window.tvf.exportRosy(),
      sharp: await window.tvf.exportSharp(),
      singularities: window.tvf.singularities(),
      faceVectors: Array.from(window.tvf.faceVectors()),
      features: window.tvf.features(),
    }));
    await page.locator('#export-panel summary').click();
    const files = { sing: await download('#export-sing'), rosy: await download('#export-rosy'),
      sharp: await download('#export-sharp') };
    for (const ext of ['sing', 'rosy', 'sharp']) {
      expect(files[ext].name).toBe(`box.${ext}`);
      expect(files[ext].text, `the .${ext} button downloads the API's bytes`).toBe(api[ext]);
    }

    // The CLI writes the same bytes for the same model and the design the page saves. Its .rosy comes from its
    // own solve, which the wasm build's (supernodal, threaded) agrees with to round-off; the writer's 9
    // decimals make the two files the same.
    const dir = mkdtempSync(resolve(tmpdir(), 'tvf-quad-e2e-'));
    try {
      writeFileSync(resolve(dir, 'box.off'), off);
      writeFileSync(resolve(dir, 'design.json'), JSON.stringify(await evaluate(() => window.tvf.saveDesign())));
      const out = (ext) => resolve(dir, `cli.${ext}`);
      execFileSync(resolve(ROOT, 'build/tvf'), ['export', resolve(dir, 'box.off'), resolve(dir, 'design.json'),
        '--sing', out('sing'), '--rosy', out('rosy'), '--sharp', out('sharp')]);
      const [cli, ours] = [readFileSync(out('rosy'), 'utf8'), api.rosy].map((t) => t.trim().split('\n'));
      expect(cli.length).toBe(ours.length);
      let apart = 0, differ = 0;
      cli.forEach((line, k) => {
        const [a, b] = [line, ours[k]].map((l) => l.trim().split(/\s+/).map(Number));
        differ += line !== ours[k];
        a.forEach((x, c) => (apart = Math.max(apart, Math.abs(x - b[c]))));
      });
      console.log(`tvf export --rosy: ${differ} of ${cli.length} lines differ from the page's, by at most ` +
        `${apart.toExponential(1)}`);
      for (const ext of ['sing', 'rosy', 'sharp'])
        expect(readFileSync(out(ext), 'utf8'), `tvf export --${ext} writes the page's bytes`).toBe(api[ext]);
    } finally {
      rmSync(dir, { recursive: true, force: true });
    }

    // .sing: every singularity of the field, the prescribed pair among them, as vertex and k = index * N.
    const sing = parseSing(api.sing);
    expect(sing.n).toBe(4);
    const asKeys = (list) => list.map(([v, k]) => `${v}:${k}`).sort();
    expect(asKeys(sing.entries)).toEqual(asKeys(api.singularities.map((s) => [s.vertex, Math.round(s.index * 4)])));
    expect(asKeys(sing.entries)).toEqual(expect.arrayContaining([`${plus}:1`, `${minus}:-1`]));
    expect(sing.entries.reduce((sum, [, k]) => sum + k, 0)).toBe(8); // chi = 2 of a closed box, in quarters

    // .rosy: the face count, 4, then each face's direction: unit, in the face's plane, and the field's own up to
    // a quarter turn (the 9 digits written).
    const rosy = api.rosy.trim().split('\n');
    const numF = mesh.triangles.length / 3;
    expect(rosy.slice(0, 2)).toEqual([String(numF), '4']);
    expect(rosy.length).toBe(numF + 2);
    let worst = 0;
    for (let f = 0; f < numF; f++) {
      const d = rosy[f + 2].trim().split(/\s+/).map(Number);
      const u = api.faceVectors.slice(3 * f, 3 * f + 3);
      const nrm = faceNormal(mesh, f);
      expect(Math.abs(norm(d) - 1)).toBeLessThan(1e-6);
      expect(Math.abs(dot(d, nrm))).toBeLessThan(1e-6);
      const angle = Math.atan2(dot(cross(u, d), nrm), dot(u, d));
      worst = Math.max(worst, Math.abs(Math.atan2(Math.sin(4 * angle), Math.cos(4 * angle)) / 4));
    }
    expect(worst, 'the .rosy direction is the field in each face').toBeLessThan(1e-6);

    // .sharp: both sides of every feature edge in use, and only those; every one of the box's creases convex.
    const sharp = parseSharp(api.sharp);
    const sides = new Map();
    for (const [type, f, corner] of sharp) {
      expect(type).toBe(1);
      const [a, b] = [mesh.triangles[3 * f + corner], mesh.triangles[3 * f + ((corner + 1) % 3)]];
      sides.set(edgeKey(a, b), (sides.get(edgeKey(a, b)) ?? 0) + 1);
    }
    const used = api.features.edges.map(([a, b]) => edgeKey(a, b)).sort();
    expect(used.length).toBe(12 * n);
    expect([...sides.keys()].sort()).toEqual(used);
    expect([...sides.values()].every((count) => count === 2)).toBe(true);
    console.log(`box (${numF} faces): .sing ${sing.entries.length} singularities, .sharp ${sharp.length} sides, ` +
      `.rosy within ${worst.toExponential(1)} rad of the field`);

    // .rosy holds a cross field alone: a line field has the button disabled with the reason, the API refuses.
    await evaluate(() => window.tvf.setSymmetry(2));
    const rosyButton = page.locator('#export-rosy');
    await expect(rosyButton).toBeDisabled();
    expect(await rosyButton.getAttribute('title')).toMatch(/cross field \(N = 4\): choose Cross/);
    expect(await refusal(() => window.tvf.exportRosy())).toMatch(/\.rosy file holds a cross field.*this is a line field/);
    expect(parseSing(await evaluate(() => window.tvf.exportSing())).n).toBe(2);
    await evaluate(() => window.tvf.undo());
    await expect(rosyButton).toBeEnabled();
  });

  test('a .sing opened on the page adds its singularities as one step; one undo removes them all', async () => {
    const mesh = await loadOff(icosphereOff(2), 'ico2.off');
    const nV = mesh.positions.length / 3;
    // Four vertices far apart, +1/4 and -1/4 alternately (the file of another tool, written here).
    const far = [0];
    while (far.length < 4) {
      let best = -1, bestD = -1;
      for (let v = 0; v < nV; v++) {
        const d = Math.min(...far.map((w) => norm(sub(vertex(mesh, v), vertex(mesh, w)))));
        if (d > bestD) [best, bestD] = [v, d];
      }
      far.push(best);
    }
    const text = `4 4\n${far.map((v, k) => `${v} ${k % 2 ? -1 : 1}`).join('\n')}\n`;
    const steps = (await evaluate(() => window.tvf.history())).undo.length;
    await page.locator('#file-input').setInputFiles({ name: 'four.sing', mimeType: 'text/plain',
      buffer: Buffer.from(text) });
    const prescribed = () => evaluate(() => window.tvf.singularities().filter((s) => s.prescribed)
      .map((s) => `${s.vertex}:${s.index}`).sort());
    const expected = far.map((v, k) => `${v}:${k % 2 ? -0.25 : 0.25}`).sort();
    await expect.poll(prescribed).toEqual(expected);
    const history = await evaluate(() => window.tvf.history());
    expect(history.undo.length).toBe(steps + 1);
    expect(history.undo.at(-1)).toMatch(/4 singularities from four\.sing/);
    expect((await evaluate(() => window.tvf.constraints())).filter((c) => c.type === 'singularity').length).toBe(4);
    await evaluate(() => window.tvf.undo());
    expect(await prescribed()).toEqual([]);
    await evaluate(() => window.tvf.redo());
    expect(await prescribed()).toEqual(expected);

    // A .sing the page can read back is the page's own export.
    const exported = parseSing(await evaluate(() => window.tvf.exportSing()));
    expect(exported.entries.map(([v, k]) => `${v}:${k / 4}`)).toEqual(expect.arrayContaining(expected));

    // Refusals in the banner, naming the file; nothing changes.
    const design = await evaluate(() => window.tvf.saveDesign());
    const banner = page.locator('#error-banner');
    await page.locator('#design-input').setInputFiles({ name: 'bad.sing', mimeType: 'text/plain',
      buffer: Buffer.from('4 2\n5 1\n') });
    await expect(banner).toBeVisible();
    await expect(banner.locator('.message')).toContainText('bad.sing: .sing line 1: announces 2 singularities');
    await page.locator('#file-input').setInputFiles({ name: 'again.sing', mimeType: 'text/plain',
      buffer: Buffer.from(`4 1\n${far[0]} 1\n`) });
    await expect(banner.locator('.message')).toContainText('again.sing');
    await expect(banner.locator('.message')).toContainText(`vertex ${far[0]}`);
    expect(await evaluate(() => window.tvf.saveDesign())).toEqual(design);
    expect((await evaluate(() => window.tvf.history())).undo.length).toBe(steps + 1);
    await banner.locator('.dismiss').click();
  });

  test('"Only prescribed singularities" toggles exactSingularities with undo: a torus then has none', async () => {
    await loadOff(torusOff(24, 12), 'torus.off', { ...CROSS, featureAngle: 0 });
    const box = page.locator('#exact-singularities');
    await expect(box).not.toBeChecked();
    expect(await evaluate(() => window.tvf.settings().exactSingularities)).toBe(false);
    await box.check();
    await expect.poll(() => evaluate(() => window.tvf.settings().exactSingularities)).toBe(true);
    expect(await evaluate(() => window.tvf.singularities())).toEqual([]);
    expect(await evaluate(() => window.tvf.singularitySummary())).toMatchObject({ mode: 'exact', exact: true,
      eulerCharacteristic: 0 });
    expect(await evaluate(() => window.tvf.saveDesign().exactSingularities)).toBe(true);
    expect((await evaluate(() => window.tvf.history())).undo.at(-1)).toBe('only prescribed singularities');
    await evaluate(() => window.tvf.undo());
    await expect(box).not.toBeChecked();
    expect(await evaluate(() => window.tvf.settings().exactSingularities)).toBe(false);
    expect(await evaluate(() => 'exactSingularities' in window.tvf.saveDesign())).toBe(false);
    await evaluate(() => window.tvf.redo());
    await expect(box).toBeChecked();
    // The API as the checkbox, and its refusal.
    await evaluate(() => window.tvf.setExactSingularities(false));
    await expect(box).not.toBeChecked();
    expect(await refusal(() => window.tvf.setExactSingularities('yes'))).toMatch(/true or false/);
  });
});
