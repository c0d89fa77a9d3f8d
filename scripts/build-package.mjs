#!/usr/bin/env node
// Builds the installable package's files in lib/ (npm pack runs this as prepack, after the wasm core):
//   lib/tangent-field-designer.js  exports['.']: defines <tangent-field-designer>, exports the class
//   lib/element.js                 exports['./element']: the class and define(tagName?), no side effects
//   lib/chunk-*.js                 code both share (the element, three.js)
//   lib/core-worker.js             the core's module worker (one file: it may be started from a blob: URL)
//   lib/wasm/tvf_core.{mjs,wasm}   the core
//   lib/wasm/tvf_core_threads.{mjs,wasm,worker.js}   the core with a helper thread (cross-origin-isolated
//                                  pages; package.json there keeps the worker script CommonJS under node)
// Every file is self-contained ES2022 with no bare imports: it loads in a browser as it is.
import { copyFileSync, existsSync, mkdirSync, rmSync } from 'node:fs';
import { dirname, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import * as esbuild from 'esbuild';

const ROOT = resolve(dirname(fileURLToPath(import.meta.url)), '..');
const LIB = resolve(ROOT, 'lib');
const common = {
  bundle: true,
  format: 'esm',
  platform: 'browser',
  target: 'es2022',
  minify: true,
  legalComments: 'linked',
  loader: { '.css': 'text' },
  logLevel: 'warning',
};

const coreFiles = ['tvf_core.mjs', 'tvf_core.wasm', 'tvf_core_threads.mjs', 'tvf_core_threads.wasm',
  'tvf_core_threads.worker.js', 'package.json'].map((f) => resolve(ROOT, 'build-wasm', f));
if (!coreFiles.every(existsSync)) {
  console.error('build-package: build-wasm/tvf_core{,_threads}.* not found; run `npm run build:wasm` first');
  process.exit(1);
}
rmSync(LIB, { recursive: true, force: true });
mkdirSync(resolve(LIB, 'wasm'), { recursive: true });

await esbuild.build({
  ...common,
  entryPoints: { 'tangent-field-designer': resolve(ROOT, 'web/index.js'), element: resolve(ROOT, 'web/element-entry.js') },
  outdir: LIB,
  splitting: true,
  chunkNames: 'chunk-[hash]',
});
await esbuild.build({ ...common, entryPoints: { 'core-worker': resolve(ROOT, 'web/core/core-worker.js') }, outdir: LIB });
for (const f of coreFiles) copyFileSync(f, resolve(LIB, 'wasm', f.split('/').pop()));
console.log('build-package: lib/ ready');
