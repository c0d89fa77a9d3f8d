#!/usr/bin/env node
// Builds the installable package's files in lib/ (npm pack runs this as prepack, after the wasm core).
// Two builds of the element sit side by side in lib/, so that both find the same worker and core next to them:
//
//   The peer build (the package's default): three.js and three-mesh-bvh are peer dependencies, left as bare
//   imports ('three', 'three/addons/…', 'three-mesh-bvh') for the consumer's bundler or import map to resolve,
//   so a page that already uses three loads one copy of it.
//     lib/tangent-field-designer.js    exports['.']: defines <tangent-field-designer>, exports the class
//     lib/element.js                   exports['./element']: the class and define(tagName?), no side effects
//     lib/chunk-*.js                   code both share (the element)
//
//   The standalone build (script tags, CDNs): self-contained, three.js and three-mesh-bvh inside, no bare imports.
//     lib/tangent-field-designer.standalone.js   exports['./standalone']: as lib/tangent-field-designer.js
//     lib/element.standalone.js                  exports['./standalone/element']: as lib/element.js
//     lib/standalone-chunk-*.js                  code both share (the element, three.js, three-mesh-bvh)
//
//   Both use:
//     lib/core-worker.js               the core's module worker (one file: it may be started from a blob: URL;
//                                      it uses no three.js)
//     lib/wasm/tvf_core.{mjs,wasm}     the core
//     lib/wasm/tvf_core_threads.{mjs,wasm,worker.js}   the core with a helper thread (cross-origin-isolated
//                                      pages; package.json there keeps the worker script CommonJS under node)
// Every file is ES2022; only the peer build's entries and chunks have bare imports, and only of the peers.
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
  metafile: true,
};
// The peer dependencies (package.json "peerDependencies") and their subpaths: web/ imports 'three',
// 'three/addons/*' (three's own export of examples/jsm/*) and 'three-mesh-bvh'.
const PEERS = ['three', 'three-mesh-bvh'];
const peerExternal = PEERS.flatMap((p) => [p, `${p}/*`]);
const isPeerInput = (path) => PEERS.some((p) => path.includes(`node_modules/${p}/`));

const coreFiles = ['tvf_core.mjs', 'tvf_core.wasm', 'tvf_core_threads.mjs', 'tvf_core_threads.wasm',
  'tvf_core_threads.worker.js', 'package.json'].map((f) => resolve(ROOT, 'build-wasm', f));
if (!coreFiles.every(existsSync)) {
  console.error('build-package: build-wasm/tvf_core{,_threads}.* not found; run `npm run build:wasm` first');
  process.exit(1);
}
rmSync(LIB, { recursive: true, force: true });
mkdirSync(resolve(LIB, 'wasm'), { recursive: true });

const entries = (suffix) => ({
  [`tangent-field-designer${suffix}`]: resolve(ROOT, 'web/index.js'),
  [`element${suffix}`]: resolve(ROOT, 'web/element-entry.js'),
});
const peer = await esbuild.build({
  ...common,
  entryPoints: entries(''),
  outdir: LIB,
  splitting: true,
  chunkNames: 'chunk-[hash]',
  external: peerExternal,
});
const standalone = await esbuild.build({
  ...common,
  entryPoints: entries('.standalone'),
  outdir: LIB,
  splitting: true,
  chunkNames: 'standalone-chunk-[hash]',
});
const worker = await esbuild.build({
  ...common,
  entryPoints: { 'core-worker': resolve(ROOT, 'web/core-worker.js') },
  outdir: LIB,
});

// The peer build must not carry a copy of a peer, and the standalone one must not import anything.
const fail = (msg) => {
  console.error(`build-package: ${msg}`);
  process.exit(1);
};
const bundled = (result) => Object.keys(result.metafile.inputs).filter(isPeerInput);
if (bundled(peer).length) fail(`the peer build bundled ${bundled(peer)[0]}`);
// The worker is a realm of its own (no import map reaches it, and no copy there meets the page's three): it
// bundles the parts of three and three-mesh-bvh it builds the page's ray-casting BVH with
// (web/geometry/mesh-bvh-transfer.js), and nothing else of the peers.
const BVH_PARTS = /node_modules\/(three\/build\/three\.(core|module)\.js|three-mesh-bvh\/)/;
const workerPeers = bundled(worker).filter((f) => !BVH_PARTS.test(f));
if (workerPeers.length) {
  fail(`core-worker.js bundled ${workerPeers[0]} (the worker uses three only to build the BVH)`);
}
for (const [file, out] of Object.entries({ ...standalone.metafile.outputs, ...worker.metafile.outputs })) {
  const bare = (out.imports || []).find((i) => i.external);
  if (bare) fail(`${file} imports ${bare.path}`);
}
for (const [file, out] of Object.entries(peer.metafile.outputs)) {
  const isPeer = (path) => PEERS.some((p) => path === p || path.startsWith(`${p}/`));
  const other = (out.imports || []).find((i) => i.external && !isPeer(i.path));
  if (other) fail(`${file} imports ${other.path}, which is not a peer dependency`);
}

for (const f of coreFiles) copyFileSync(f, resolve(LIB, 'wasm', f.split('/').pop()));
const size = (result) =>
  Object.entries(result.metafile.outputs)
    .filter(([f]) => f.endsWith('.js'))
    .reduce((n, [, o]) => n + o.bytes, 0);
console.log(
  `build-package: lib/ ready (peer build ${size(peer)} bytes, standalone ${size(standalone)} bytes, ` +
    `worker ${size(worker)} bytes of JS)`,
);
