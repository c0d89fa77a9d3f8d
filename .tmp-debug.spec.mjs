import { test } from '@playwright/test';
import { openDesigner, surfacePoint, faceVector, faceNormal, angleInPlane, sub } from './tests/e2e/helpers.mjs';
test('debug', async ({ page }) => {
  await openDesigner(page);
  const mesh = await page.evaluate(() => { const m = window.tvf.mesh(); return { positions: Array.from(m.positions), triangles: Array.from(m.triangles) }; });
  const r = await page.evaluate(() => { const r = document.querySelector('#viewport canvas').getBoundingClientRect(); return [r.left + r.width/2, r.top + r.height/2]; });
  await page.getByRole('button', { name: 'Stroke', exact: true }).click();
  await page.mouse.move(r[0]-80, r[1]+40); await page.mouse.down(); await page.mouse.move(r[0]+80, r[1]+40, {steps: 40}); await page.mouse.up();
  await page.waitForTimeout(300);
  const c = await page.evaluate(() => window.tvf.constraints());
  const pts = c[0].points;
  const field = await page.evaluate(() => Array.from(window.tvf.faceVectors()));
  let prev = null;
  for (const p of pts) { const x = surfacePoint(mesh, p); console.log(p.face, x.map(v=>v.toFixed(4)).join(' '), prev ? sub(x, prev).map(v=>v.toFixed(4)).join(' ') : '', angleInPlane(faceVector(field,p.face), prev? sub(x,prev):[1,0,0], faceNormal(mesh,p.face)).toFixed(1)); prev = x; }
});
