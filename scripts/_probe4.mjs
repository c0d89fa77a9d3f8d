import { chromium } from '@playwright/test';
import { icosphereOff } from '../tests/icosphere.mjs';
const b = await chromium.launch({ executablePath: '/usr/bin/chromium', args: ['--use-angle=swiftshader','--enable-unsafe-swiftshader'] });
const p = await b.newPage({ viewport: { width: 500, height: 560 } });
p.on('pageerror', (e) => console.log('pageerror', e.message));
await p.goto('http://127.0.0.1:8191/');
await p.waitForFunction(() => window.tvf && window.tvf.ready);
await p.evaluate(() => window.tvf.ready);
const hide = () => p.evaluate(() => { document.querySelector('tangent-field-designer').shadowRoot.querySelector('#hint').style.display = 'none'; });
const F = Number(process.env.F ?? 8), L = Number(process.env.L ?? 5), tag = process.env.TAG ?? 'x';
await p.evaluate((t) => window.tvf.loadModel(new TextEncoder().encode(t), { name: 'ico.off', restore: false }), icosphereOff(L));
const mesh = await p.evaluate(() => Array.from(window.tvf.mesh().positions));
for (const [sym, profile] of [[2, 'stripes'], [4, 'grid']]) {
  await p.evaluate(async (sym) => { await window.tvf.loadDesign({ symmetry: sym, constraints: [] }); }, sym);
  await p.evaluate(([F, profile, A]) => window.tvf.setStripes({ visible: true, frequency: F, profile, light: '#ffffff', dark: '#000000', adaptSpacing: A }), [F, profile, process.env.ADAPT !== '0']);
  await p.evaluate(() => window.tvf.setViews({ arrows: false, singularities: false }));
  const sings = await p.evaluate(() => window.tvf.singularities());
  let k = 0;
  for (const s of sings) {
    const q = mesh.slice(3 * s.vertex, 3 * s.vertex + 3), n = Math.hypot(...q);
    await p.evaluate(([pos, t]) => window.tvf.setCamera({ position: pos, target: t }), [q.map((x) => (1.9 * x) / n), q]);
    await hide();
    await p.waitForTimeout(150);
    await p.screenshot({ path: `/tmp/e2e/all-${tag}-${sym}-${k++}.png`, clip: { x: 100, y: 130, width: 300, height: 300 } });
  }
}
await b.close();
