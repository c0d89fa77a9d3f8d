import { test } from '@playwright/test';
import { openDesigner } from './tests/e2e/helpers.mjs';
test('shot', async ({ page }) => {
  await openDesigner(page);
  await page.evaluate(() => window.tvf.loadModel(new Uint8Array([1,2,3,4,5,6,7,8])).catch(e => document.querySelector('#error-banner .message').textContent = e.message) );
  await page.evaluate(() => document.querySelector('#error-banner').hidden = false);
  await page.screenshot({ path: '/tmp/shot.png' });
});
