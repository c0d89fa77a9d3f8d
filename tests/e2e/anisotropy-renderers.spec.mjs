// The exported line-field GLB's anisotropy where it is used (issue 45, item 3): drawn by three.js (the package's
// peer) and by Babylon.js (npm) with their own glTF loaders and anisotropic materials, under a point light at the
// camera, on a flat patch and on a curved one (a sphere cap). The highlight's elongation, from the picture
// alone (the second moments of its pixels), lies along the field's direction on screen (mod pi) within 3
// degrees: KHR_materials_anisotropy's direction is the one along which the roughness grows, so the highlight
// stretches along the field. The GLBs are `tvf export`'s (the page's exportGlb() writes the same bytes).
import { execFileSync } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { expect, test } from '@playwright/test';
import { build } from 'esbuild';

const ROOT = resolve(dirname(fileURLToPath(import.meta.url)), '../..');
const TVF = resolve(ROOT, 'build/tvf');
const SIZE = 320;

// An n × n grid over [-1, 1]^2, z = height(x, y), as OFF text.
function patchOff(n, height) {
  const v = [], f = [];
  for (let j = 0; j <= n; j++)
    for (let i = 0; i <= n; i++) {
      const x = -1 + (2 * i) / n, y = -1 + (2 * j) / n;
      v.push(`${x} ${y} ${height(x, y)}`);
    }
  const at = (i, j) => j * (n + 1) + i;
  for (let j = 0; j < n; j++)
    for (let i = 0; i < n; i++) f.push(`3 ${at(i, j)} ${at(i + 1, j)} ${at(i + 1, j + 1)}`, `3 ${at(i, j)} ${at(i + 1, j + 1)} ${at(i, j + 1)}`);
  return `OFF\n${v.length} ${f.length} 0\n${v.join('\n')}\n${f.join('\n')}\n`;
}

// The highlight's long axis on screen (radians, x right, y down, mod pi): the pixels brighter than half way from
// the picture's median to its brightest, weighted by how much brighter, and their second moments.
function highlightAxis(rgba, size) {
  const lum = new Float64Array(size * size);
  for (let i = 0; i < lum.length; i++) lum[i] = 0.299 * rgba[4 * i] + 0.587 * rgba[4 * i + 1] + 0.114 * rgba[4 * i + 2];
  const sorted = Float64Array.from(lum).sort();
  const median = sorted[Math.floor(sorted.length / 2)], max = sorted.at(-1);
  const cut = median + 0.5 * (max - median);
  let w = 0, mx = 0, my = 0;
  for (let i = 0; i < lum.length; i++) {
    if (lum[i] <= cut) continue;
    const q = lum[i] - cut;
    w += q, mx += q * (i % size), my += q * Math.floor(i / size);
  }
  mx /= w, my /= w;
  let sxx = 0, syy = 0, sxy = 0;
  for (let i = 0; i < lum.length; i++) {
    if (lum[i] <= cut) continue;
    const q = lum[i] - cut, dx = (i % size) - mx, dy = Math.floor(i / size) - my;
    sxx += q * dx * dx, syy += q * dy * dy, sxy += q * dx * dy;
  }
  const angle = 0.5 * Math.atan2(2 * sxy, sxx - syy);
  const l1 = 0.5 * (sxx + syy) + Math.hypot(0.5 * (sxx - syy), sxy), l2 = sxx + syy - l1;
  return { angle, elongation: Math.sqrt(l1 / Math.max(l2, 1e-9)), max, median };
}

const modPiDegrees = (a) => {
  const d = (((a % Math.PI) + Math.PI) % Math.PI) * (180 / Math.PI);
  return Math.min(d, 180 - d);
};

test.describe.serial('the line-field GLB in three.js and Babylon.js', () => {
  let dir, page, bundles;
  test.beforeAll(async ({ browser }) => {
    dir = mkdtempSync(join(tmpdir(), 'tvf-renderers-'));
    // Without whitespace (the names kept, for a failure's stack): less for the page to parse.
    const bundle = async (file, globalName) =>
      (await build({ entryPoints: [resolve(ROOT, 'tests/e2e/renderers', file)], bundle: true, format: 'iife',
        globalName, write: false, logLevel: 'silent', minifyWhitespace: true, minifySyntax: true }))
        .outputFiles[0].text;
    bundles = { three: await bundle('three-scene.mjs', 'TvfThreeScene'),
      babylon: await bundle('babylon-scene.mjs', 'TvfBabylonScene') };
    page = await browser.newPage();
    await page.setContent(`<canvas id="c" width="${SIZE}" height="${SIZE}"></canvas>`);
    await page.addScriptTag({ content: bundles.three });
    await page.addScriptTag({ content: bundles.babylon });
  });
  test.afterAll(async () => {
    await page?.close();
    if (dir) rmSync(dir, { recursive: true, force: true });
  });

  // A line field along `angle` (radians from x in the xy plane) on the patch, exported as a GLB.
  const exportPatch = (name, height, angle, extra = []) => {
    writeFileSync(join(dir, `${name}.off`), patchOff(24, height));
    const mid = 24 * 12 + 12; // a face at the patch's middle
    writeFileSync(join(dir, `${name}.json`), JSON.stringify({ symmetry: 2, constraints: [
      { type: 'vector', face: 2 * mid, vector: [Math.cos(angle), Math.sin(angle), 0] }] }));
    execFileSync(TVF, ['export', join(dir, `${name}.off`), join(dir, `${name}.json`), '--glb', join(dir, `${name}.glb`),
      ...extra], { stdio: 'pipe' });
    return readFileSync(join(dir, `${name}.glb`));
  };

  const renderWith = (renderer, glb, camera) => page.evaluate(async ({ renderer, bytes, camera }) => {
    const canvas = document.getElementById('c').cloneNode();
    document.body.replaceChildren(canvas);
    const scene = renderer === 'three' ? window.TvfThreeScene : window.TvfBabylonScene;
    return Array.from(await scene.render(canvas, new Uint8Array(bytes), camera));
  }, { renderer, bytes: Array.from(glb), camera });

  for (const [patch, height] of [['flat', () => 0], ['curved', (x, y) => Math.sqrt(Math.max(0, 4 - x * x - y * y)) - 2]]) {
    test(`${patch} patch: the highlight stretches along the field in both renderers`, async () => {
      const angle = (30 * Math.PI) / 180;
      const glb = exportPatch(patch, height, angle);
      // Straight down the z axis at the patch's middle, y up: the field's angle on screen is -angle (y down).
      const camera = { position: [0, 0, 3], target: [0, 0, 0] };
      for (const renderer of ['three', 'babylon']) {
        const rgba = await renderWith(renderer, glb, camera);
        const h = highlightAxis(rgba, SIZE);
        const off = modPiDegrees(h.angle + angle);
        console.log(`[ measured ] ${patch} patch, ${renderer}: highlight ${(-h.angle * 180 / Math.PI).toFixed(2)}° ` +
          `(field 30°), ${off.toFixed(2)}° off, elongation ${h.elongation.toFixed(2)}, peak ${h.max.toFixed(0)}`);
        expect(h.max - h.median).toBeGreaterThan(40); // a highlight there
        expect(h.elongation).toBeGreaterThan(1.5);
        expect(off).toBeLessThan(3);
      }
    });
  }

  // The option for a renderer that reads the direction the other way: a quarter turn (anisotropyRotation) turns
  // the highlight across the field, in both renderers alike: the measure sees the convention.
  test('the rotation option turns the highlight a quarter, in both renderers', async () => {
    const angle = (30 * Math.PI) / 180;
    const glb = exportPatch('turned', () => 0, angle, ['--rotation', String(Math.PI / 2)]);
    for (const renderer of ['three', 'babylon']) {
      const h = highlightAxis(await renderWith(renderer, glb, { position: [0, 0, 3], target: [0, 0, 0] }), SIZE);
      const off = modPiDegrees(h.angle + angle);
      console.log(`[ measured ] rotation pi/2, ${renderer}: the highlight ${off.toFixed(2)}° off the field`);
      expect(off).toBeGreaterThan(87);
    }
  });
});
