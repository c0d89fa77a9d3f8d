#!/usr/bin/env node
// Builds the static site in dist/: the bundled page, public/ assets, the wasm core (when built) and the
// default model. The core is copied, not bundled: it is an emscripten module that fetches its .wasm beside itself.
import { copyFileSync, cpSync, existsSync, mkdirSync, rmSync } from 'node:fs';
import { dirname, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import * as esbuild from 'esbuild';
import { makeDefaultModel } from './make-default-model.mjs';

const ROOT = resolve(dirname(fileURLToPath(import.meta.url)), '..');
const DIST = resolve(ROOT, 'dist');
const t0 = performance.now();

// Only the bundle and copied assets are cleared: a stale main.js must never survive a failed build.
for (const f of ['main.js', 'core-worker.js']) rmSync(resolve(DIST, f), { force: true });
rmSync(resolve(DIST, 'wasm'), { recursive: true, force: true });
mkdirSync(DIST, { recursive: true });

// The core runs in a module worker: a second entry point, loaded by the page as dist/core-worker.js.
await esbuild.build({
  entryPoints: { main: resolve(ROOT, 'web/main.js'), 'core-worker': resolve(ROOT, 'web/core-worker.js') },
  outdir: DIST,
  bundle: true,
  format: 'esm',
  platform: 'browser',
  target: 'es2022',
  minify: process.env.TVF_NO_MINIFY ? false : true,
  sourcemap: true,
  legalComments: 'linked',
  loader: { '.css': 'text' }, // the element's stylesheet, adopted by its shadow root
  logLevel: 'warning',
});

cpSync(resolve(ROOT, 'public'), DIST, { recursive: true });

const wasmDir = resolve(ROOT, 'build-wasm');
// The plain core, and the core with a helper thread that cross-origin-isolated pages load instead
// (web/core-client.js); package.json keeps the pthread worker script CommonJS for node.
const coreFiles = ['tvf_core.mjs', 'tvf_core.wasm'];
const threadedFiles = ['tvf_core_threads.mjs', 'tvf_core_threads.wasm', 'tvf_core_threads.worker.js', 'package.json'];
if (coreFiles.every((f) => existsSync(resolve(wasmDir, f)))) {
  mkdirSync(resolve(DIST, 'wasm'), { recursive: true });
  for (const f of coreFiles) copyFileSync(resolve(wasmDir, f), resolve(DIST, 'wasm', f));
  if (threadedFiles.every((f) => existsSync(resolve(wasmDir, f))))
    for (const f of threadedFiles) copyFileSync(resolve(wasmDir, f), resolve(DIST, 'wasm', f));
  else console.warn('build-web: build-wasm/tvf_core_threads.* not found; isolated pages will run the plain core');
} else {
  console.warn(
    'build-web: build-wasm/tvf_core.{mjs,wasm} not found; run `npm run build:wasm` (the page needs the core)',
  );
}

const model = makeDefaultModel(resolve(DIST, 'models/bunny.glb'));
console.log(
  `build-web: dist/ ready in ${(performance.now() - t0).toFixed(0)} ms ` +
    `(default model ${model.vertices} vertices, ${model.faces} faces)`,
);
