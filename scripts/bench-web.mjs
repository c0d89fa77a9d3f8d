#!/usr/bin/env node
// Texture-synthesis benchmark in Debian's Chromium (never a downloaded browser): serves dist/ (build it first:
// npm run build:wasm && npm run build:web), opens /?bench=1, and prints per-level and total times for 256², 512²
// and 1024² atlases with the ratio to a plain full-screen pass of the same size (web/synthesis/bench.js).
// Writes bench-data/synthesis-bench.json.
// Usage: node scripts/bench-web.mjs [--sizes 256,512,1024] [--port 8194]
import { spawn } from 'node:child_process';
import { mkdirSync, writeFileSync } from 'node:fs';
import { dirname, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from '@playwright/test';

const ROOT = resolve(dirname(fileURLToPath(import.meta.url)), '..');
const arg = (name, fallback) => {
  const i = process.argv.indexOf(name);
  return i > 0 ? process.argv[i + 1] : fallback;
};
const sizes = arg('--sizes', '256,512,1024');
const port = Number(arg('--port', process.env.PORT || 8194));

const server = spawn(process.execPath, [resolve(ROOT, 'scripts/serve.mjs')], { env: { ...process.env, PORT: String(port) }, stdio: ['ignore', 'pipe', 'inherit'] });
await new Promise((ok, fail) => {
  server.stdout.on('data', (d) => String(d).includes('http://') && ok());
  server.on('exit', (code) => fail(new Error(`the server exited (${code})`)));
});
const browser = await chromium.launch({
  executablePath: process.env.TVF_CHROMIUM || '/usr/bin/chromium',
  args: ['--enable-unsafe-swiftshader', '--use-angle=swiftshader', '--no-first-run', '--disable-background-networking', '--disable-component-update', '--disable-sync'],
});
try {
  const page = await browser.newPage({ viewport: { width: 1024, height: 720 } });
  await page.goto(`http://127.0.0.1:${port}/?bench=1&sizes=${sizes}`);
  const handle = await page.waitForFunction(() => window.tvfBench, null, { timeout: 600_000 });
  const result = await handle.jsonValue();
  if (result.error) throw new Error(result.error);
  for (const r of result.runs) {
    console.log(`${r.size}²: total ${r.totalMs} ms (${r.totalNoLevelSyncMs} ms without per-level waits); plain pass ${r.plainPassMs} ms; ratio ${r.ratioToPlainPass}`);
    console.log(`   levels: ${r.levels.map((l) => `${l.size}²(s${l.stackLevel}) ${l.ms}`).join(', ')}`);
  }
  console.log(`device: ${result.device}; exemplar ${result.exemplar}; analysis ${result.analysis.totalMs.toFixed(0)} ms`);
  mkdirSync(resolve(ROOT, 'bench-data'), { recursive: true });
  writeFileSync(resolve(ROOT, 'bench-data/synthesis-bench.json'), JSON.stringify({ date: new Date().toISOString(), ...result }, null, 1));
} finally {
  await browser.close();
  server.kill();
}
