// SPDX-License-Identifier: GPL-2.0-or-later
// Quad meshes from the designed cross field, as one designer composes them: the controller (controller.js), whose
// calls the element makes (docs/js-api.md, "Quad meshes"), the wireframe over the model (quad-view.js), the
// "Quad mesh" panel, and each run on a worker of its own (run.js). The designer hands in the viewer, the asset
// base of core-worker.js, and what the field and the model are now. Imports its own folder.
import { QuadController } from './controller.js';
import { mountQuadPanel } from './panel.js';
import { QuadView } from './quad-view.js';
import { startQuadRun } from './run.js';

// viewer: the page's Viewer (null: nothing drawn); panel: the side panel's container, or null; assetBase: the
// folder of core-worker.js and wasm/; area(): the model's surface area; the rest as QuadController takes them.
// Returns the controller (remesh(), cancel(), state(), exportObj(), exportGlb(): the element's calls,
// element/api.js; fieldChanged(), modelChanged(), dispose()).
export function setupQuad({ viewer = null, panel = null, assetBase, area = () => 0, onError = () => {}, ...deps }) {
  const controller = new QuadController({
    ...deps,
    view: viewer ? new QuadView(viewer) : null,
    startRun: (input, options, onProgress) => startQuadRun(assetBase, input, options, onProgress),
  });
  if (panel) {
    const ui = mountQuadPanel(controller, panel, { area, onError });
    const notify = controller.onChange;
    controller.onChange = () => {
      notify();
      ui.refresh();
    };
    const dispose = controller.dispose.bind(controller);
    controller.dispose = () => {
      dispose();
      ui.dispose();
    };
  }
  return controller;
}
