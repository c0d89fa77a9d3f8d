import { test, expect } from '@playwright/test';
import { openDesigner, trackErrors } from './tests/e2e/helpers.mjs';
import { readFileSync } from 'node:fs';
test('drop', async ({ page }) => {
  const errors = trackErrors(page);
  await openDesigner(page);
  // a .gltf with external bin, dropped together
  const glb = readFileSync('dist/models/bunny.glb');
  const jsonLen = glb.readUInt32LE(12);
  const json = JSON.parse(glb.subarray(20, 20 + jsonLen).toString());
  const bin = glb.subarray(20 + jsonLen + 8);
  json.buffers[0].uri = 'bunny.bin';
  const drop = async (files) => page.evaluate(async (files) => {
    const dt = new DataTransfer();
    for (const f of files) dt.items.add(new File([new Uint8Array(f.bytes)], f.name));
    const vp = document.querySelector('#viewport canvas');
    vp.dispatchEvent(new DragEvent('dragenter', { dataTransfer: dt, bubbles: true }));
    vp.dispatchEvent(new DragEvent('drop', { dataTransfer: dt, bubbles: true }));
  }, files);
  await drop([{ name: 'bunny.gltf', bytes: [...Buffer.from(JSON.stringify(json))] }, { name: 'bunny.bin', bytes: [...bin] }]);
  await expect(page.locator('#status')).toContainText('bunny.gltf');
  await expect(page.locator('#error-banner')).toBeHidden();
  // OFF tetra-ish: a cube
  const off = 'OFF\n8 12 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n3 0 2 1\n3 0 3 2\n3 4 5 6\n3 4 6 7\n3 0 1 5\n3 0 5 4\n3 1 2 6\n3 1 6 5\n3 2 3 7\n3 2 7 6\n3 3 0 4\n3 3 4 7\n';
  await page.setInputFiles('#file-input', { name: 'cube.off', mimeType: 'text/plain', buffer: Buffer.from(off) });
  await expect(page.locator('#status')).toContainText('cube.off');
  console.log(JSON.stringify(await page.evaluate(() => window.tvf.info())));
  await page.screenshot({ path: '/tmp/cube.png' });
  await page.evaluate(() => window.tvf.loadModel('models/bunny.glb'));
  await page.getByRole('button', { name: 'Stroke', exact: true }).click();
  await page.mouse.move(420, 420); await page.mouse.down(); await page.mouse.move(620, 380, { steps: 40 }); await page.mouse.up();
  await page.mouse.move(400, 250); await page.mouse.down(); await page.mouse.move(450, 330, { steps: 30 }); await page.mouse.up();
  await expect(page.locator('#constraint-list li')).toHaveCount(2);
  await page.screenshot({ path: '/tmp/strokes.png' });
  console.log(JSON.stringify(await page.evaluate(() => window.tvf.stats())));
  console.log(errors);
});
