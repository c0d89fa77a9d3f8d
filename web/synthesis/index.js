// SPDX-License-Identifier: GPL-2.0-or-later
// Field-guided texture synthesis on the page, as one designer composes it: the controller (controller.js) with
// its calls on the element (docs/js-api.md, "Texture synthesis"), the "Texture" panel, and the benchmark on the
// app page. The designer hands in a small adapter (getModel, computeAtlas, analyzeExemplar, downloadGlb); the
// GLB itself is the export's (export/index.js), which takes the texture from exportTexture().
import { baseName } from '../session/documents.js';
import { formatBench } from './bench.js';
import { SynthesisController } from './controller.js';
import { mountSynthesisPanel } from './panel.js';

export { prepareAtlasAhead, prepareProgramsAhead } from './atlas-ahead.js';

// Adds the texture-synthesis calls to window.tvf (docs/js-api.md). `deps` as for SynthesisController.
export function installSynthesis(tvf, deps) {
  const c = new SynthesisController(deps);
  Object.assign(tvf, {
    setExemplar: (src, opts) => c.setExemplar(src, opts),
    synthesize: (opts) => c.synthesize(opts),
    exportTexturePNG: (opts) => c.exportTexturePNG(opts),
    synthesisStats: () => c.synthesisStats(),
    clearTexture: () => c.clearTexture(),
    exemplarInfo: () => c.exemplarInfo(),
    synthesisReadback: () => c.readback(),
    synthesisIdle: () => c.whenIdle(),
    synthesisProgress: () => (c.progress ? { ...c.progress } : null),
    setTextureAutoUpdate: (on) => c.setAutoUpdate(on),
    synthesisBench: (opts) => c.bench(opts),
  });
  return c;
}

// ?bench=1[&sizes=256,512] on the app page: once it is ready, runs the benchmark, shows it over the view and
// leaves the result in window.tvfBench (scripts/bench-web.mjs reads it from there).
function scheduleBench(tvf, controller, viewport) {
  const params = new URLSearchParams(globalThis.location?.search ?? '');
  if (params.get('bench') !== '1') return;
  const sizes = (params.get('sizes') || '256,512,1024').split(',').map(Number).filter((n) => n > 0);
  // A microtask: tvf.ready is assigned once the page's start-up code returns.
  Promise.resolve()
    .then(() => tvf.ready)
    .then(() => controller.bench({ sizes }))
    .then((result) => {
      window.tvfBench = result;
      const pre = document.createElement('pre');
      pre.id = 'synthesis-bench';
      pre.style.cssText =
        'position:absolute;left:220px;bottom:40px;z-index:10;background:#000c;color:#dfe;padding:8px;' +
        'font:12px monospace;white-space:pre-wrap;max-width:70vw';
      pre.textContent = formatBench(result);
      viewport?.append(pre);
      console.log(pre.textContent);
    })
    .catch((err) => {
      window.tvfBench = { error: err?.message || String(err) };
    });
}

// Everything a designer needs in one call: the texture calls added to `api` (the element forwards its texture
// methods there), plus the "Texture" panel in `panel` (e.g. the side panel) when given, and the benchmark when
// `bench` (the app page; `ready` is the element). downloadGlb(): the one GLB export's download (the panel's GLB
// button). Returns the controller (fieldChanged(), modelChanged(), exportTexture(), dispose()).
export function setupSynthesis(api, { panel = null, bench = null, downloadGlb = null, ...deps }) {
  const controller = installSynthesis(api, deps);
  if (bench) scheduleBench(bench, controller, panel?.parentElement);
  if (panel) {
    const modelName = () => baseName(deps.getModel()?.name);
    const view = mountSynthesisPanel(controller, panel, { onError: deps.onError, modelName, downloadGlb });
    const notify = controller.onChange;
    controller.onChange = () => {
      notify();
      view.refresh();
    };
  }
  return controller;
}
