// SPDX-License-Identifier: GPL-2.0-or-later
// Exports of the designed field (docs/export.md) and the material preview, for one designer session: the
// worker's FieldExporter writes the bytes (the same as `tvf export`), this module downloads them or shows the
// GLB in the viewer. Wiring surface: setupExport({...}) and the controller's fieldChanged()/modelChanged().
import { downloadBlob } from '../session/documents.js';
import { MATERIAL_PRESETS, MaterialPreview } from '../views/material-preview.js';
import { mountExportPanel } from './panel.js';

// The export options the page starts with (the CLI's defaults, docs/export.md).
export const DEFAULT_EXPORT_OPTIONS = { size: 1024, convention: 'gltf', bits: 8, strength: 1, rotation: 0 };
// The preview needs no flow map, and its anisotropy texture (normal-mapped models) can be coarser.
const PREVIEW_OPTIONS = { embedFlowMap: false, embedDesign: false, size: 512 };

// call(op, args): one worker request after the session's pending edits, resolving to its value.
export function setupExport({ viewer, panel, call, modelName, onError }) {
  const preview = new MaterialPreview(viewer);
  let options = { ...DEFAULT_EXPORT_OPTIONS };
  let previewPreset = null; // null: preview off
  let refresh = Promise.resolve();

  const exportFlowMap = (opts = {}) => call('exportFlowMap', [{ ...options, ...opts }]);
  const exportGlb = (opts = {}) => call('exportGlb', [{ ...options, ...opts }, null]);

  // Re-export and show; concurrent requests collapse into the latest (MaterialPreview drops stale loads).
  function showPreview() {
    if (!previewPreset) return Promise.resolve();
    const preset = previewPreset;
    refresh = exportGlb(PREVIEW_OPTIONS).then((glb) => (previewPreset ? preview.show(glb, preset) : undefined));
    return refresh;
  }

  async function materialPreview(preset) {
    if (preset != null && !MATERIAL_PRESETS[preset]) {
      throw new Error(`unknown material preset "${preset}" (${Object.keys(MATERIAL_PRESETS).join(', ')})`);
    }
    previewPreset = preset ?? null;
    ui.setPreview(previewPreset);
    if (!previewPreset) return preview.hide();
    if (preview.visible) preview.setPreset(previewPreset);
    return showPreview();
  }

  function setOptions(next) {
    options = { ...options, ...next };
    ui.setOptions(options);
    if (previewPreset && ('strength' in next || 'rotation' in next)) showPreview().catch(onError);
  }

  const ui = mountExportPanel(panel, {
    options,
    presets: Object.keys(MATERIAL_PRESETS),
    onOptions: (next) => setOptions(next),
    onFlowMap: () =>
      exportFlowMap()
        .then((png) => downloadBlob(`${modelName()}.flow-${options.convention}-${options.size}.png`, new Blob([png], { type: 'image/png' })))
        .catch(onError),
    onGlb: () => exportGlb().then((glb) => downloadBlob(`${modelName()}.field.glb`, new Blob([glb], { type: 'model/gltf-binary' }))).catch(onError),
    onPreview: (preset) => materialPreview(preset).catch(onError),
  });

  return {
    exportFlowMap,
    exportGlb,
    materialPreview,
    materialPreviewInfo: () => refresh.then(() => preview.info()),
    exportOptions: () => ({ ...options }),
    setExportOptions: setOptions,
    // The field or the model changed: a visible preview follows.
    fieldChanged: () => {
      if (previewPreset) showPreview().catch(onError);
    },
    dispose() {
      previewPreset = null;
      preview.dispose();
      ui.dispose();
    },
  };
}
