// SPDX-License-Identifier: GPL-2.0-or-later
// --pre-js of tvf_core.mjs. Emscripten 3.1.6's node support assumes CommonJS (`require`, `__dirname`), which an
// ES6 module (EXPORT_ES6, needed here because package.json has "type": "module") does not have, and it would
// try to fetch() the .wasm by a file:// URL, which node's fetch rejects. Under node only, this supplies both
// from the module's URL and reads the .wasm synchronously into Module.wasmBinary unless the caller passed
// wasmBinary or instantiateWasm. Browsers and workers never enter the branch. (`_scriptDir` is the
// import.meta.url that the MODULARIZE wrapper captures; import.meta itself would break 3.1.6's terser pass.)
var require, __dirname;
// The build with pthreads starts its helper threads' workers with the module (its PTHREAD_POOL_SIZE): one
// fewer than the cores (navigator.hardwareConcurrency, or node's), at most 7, or as many as
// createTvfCore({threadHelpers}) asks for. The plain build ignores it.
var tvfThreadHelpers = (function () {
  var cores = 2;
  if (typeof navigator == 'object' && navigator.hardwareConcurrency > 0) cores = navigator.hardwareConcurrency;
  else if (typeof process == 'object' && typeof process.getBuiltinModule == 'function')
    cores = process.getBuiltinModule('os').availableParallelism();
  var asked = Module['threadHelpers'];
  return Math.max(0, Math.min(7, asked === undefined ? cores - 1 : asked | 0));
})();
if (typeof process == 'object' && typeof process.versions == 'object' && typeof process.versions.node == 'string') {
  __dirname = decodeURIComponent(new URL('.', _scriptDir).pathname).replace(/\/$/, '');
  if (typeof process.getBuiltinModule == 'function') {
    // node >= 20.16 / 22.3
    require = process.getBuiltinModule('module').createRequire(_scriptDir);
  } else {
    require = function (name) {
      throw new Error('tvf_core: this node has no process.getBuiltinModule, so the module cannot load "' + name +
                      '" itself; pass {wasmBinary: fs.readFileSync(<path of tvf_core.wasm>)} to createTvfCore()');
    };
  }
  if (!Module['wasmBinary'] && !Module['instantiateWasm'] && typeof process.getBuiltinModule == 'function') {
    // tvf_core.mjs reads tvf_core.wasm, tvf_core_threads.mjs tvf_core_threads.wasm.
    var wasmName = new URL(_scriptDir).pathname.replace(/^.*\//, '').replace(/\.m?js$/, '.wasm');
    var wasmPath = Module['locateFile'] ? Module['locateFile'](wasmName, __dirname + '/') :
                                          new URL(wasmName, _scriptDir).href;
    if (/^file:/.test(wasmPath)) wasmPath = require('url').fileURLToPath(wasmPath);
    if (!/^[a-z][a-z0-9+.-]*:/i.test(wasmPath) || /^[a-z]:[\\/]/i.test(wasmPath))  // a path, not an http(s) URL
      Module['wasmBinary'] = require('fs').readFileSync(wasmPath);
  }
  // The build with pthreads starts its helper's worker with the module. A worker keeps node running, so an
  // idle one is unref'd: a script that is done exits, as it does with the plain build.
  Module['postRun'] = [].concat(Module['postRun'] || [], function () {
    if (typeof PThread == 'undefined') return;
    PThread.unusedWorkers.concat(PThread.runningWorkers).forEach(function (w) {
      if (w.unref) w.unref();
    });
  });
}
