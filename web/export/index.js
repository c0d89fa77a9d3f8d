// SPDX-License-Identifier: GPL-2.0-or-later
// Exports of the designed field (docs/export.md) and the material preview, for one designer session: the
// worker's FieldExporter writes the bytes (the same as `tvf export` for a field-only export), this module
// decides what goes into them, downloads them or shows the GLB in the viewer. There is one GLB export
// (exportGlb): the model with the field, its flow map and anisotropy material, the design, and the synthesized
// texture when there is one, all through the core's writer. Wiring surface: setupExport({...}) and the
// controller's fieldChanged() / downloadGlb().
import { downloadBlob } from '../session/documents.js';
import { MATERIAL_PRESETS, MaterialPreview } from '../views/material-preview.js';
import { mountExportPanel } from './panel.js';

// The export options the page starts with (the CLI's defaults, docs/export.md). texture: 'auto' embeds the
// synthesized texture when one is shown, true requires one (the last one made), false leaves it out;
// textureResolution / textureMagnification size its image (default 2 pixels per atlas texel). stripes: 'auto'
// bakes the stripe pattern in the texture's place while it is shown, true requires it shown, false leaves it out.
export const DEFAULT_EXPORT_OPTIONS = {
  size: 1024,
  convention: 'gltf',
  bits: 8,
  strength: 1,
  rotation: 0,
  texture: 'auto',
  stripes: 'auto',
};
// The preview needs no flow map, and its anisotropy texture (normal-mapped models) can be coarser; it shows the
// field's material, not the texture.
const PREVIEW_OPTIONS = { embedFlowMap: false, embedDesign: false, size: 512, texture: false, stripes: false };
// Options that choose the texture here; the rest go to the core's writer.
const TEXTURE_KEYS = ['texture', 'textureResolution', 'textureMagnification', 'stripes'];

// call(op, args): one worker request after the session's pending edits, resolving to its value.
// texture: the synthesis controller (synthesis/controller.js exportTexture()), or null without synthesis;
// stripes: the stripes controller (stripes/controller.js exportStripes()), or null.
export function setupExport({
  viewer, panel, call, modelName, onError, texture = null, stripes = null, symmetry = () => 1,
}) {
  const preview = new MaterialPreview(viewer);
  let options = { ...DEFAULT_EXPORT_OPTIONS };
  let previewPreset = null; // null: preview off
  let refresh = Promise.resolve();

  const exportFlowMap = (opts = {}) => call('exportFlowMap', [coreOptions({ ...options, ...opts })]);

  async function exportGlb(opts = {}) {
    const o = { ...options, ...opts };
    if (![true, false, 'auto'].includes(o.texture))
      throw new Error(`exportGlb: texture must be true, false or 'auto' (got ${JSON.stringify(o.texture)})`);
    if (![true, false, 'auto'].includes(o.stripes))
      throw new Error(`exportGlb: stripes must be true, false or 'auto' (got ${JSON.stringify(o.stripes)})`);
    // The stripes shown are baked by the core into the export's atlas, in the texture's place.
    const pattern = o.stripes === false ? null : await stripes?.exportStripes();
    if (o.stripes === true && !pattern)
      throw new Error('exportGlb: stripes: true needs the stripes shown (setStripes) of a field that is not zero');
    if (pattern) return call('exportGlb', [coreOptions(o), { stripes: pattern }]);
    const image =
      o.texture === false || (!texture && o.texture === 'auto')
        ? null
        : await requireTexture().exportTexture({
            resolution: o.textureResolution,
            magnification: o.textureMagnification,
            required: o.texture === true,
          });
    return call('exportGlb', [coreOptions(o), image]);
  }

  function requireTexture() {
    if (!texture) throw new Error('exportGlb: this designer has no texture synthesis');
    return texture;
  }

  // A line or cross field as Directional's raw field text (the core refuses a vector field with the reason).
  const exportRawField = () => call('exportRawField', []);
  const downloadRawField = () =>
    exportRawField().then((text) => downloadBlob(`${modelName()}.rawfield`, new Blob([text], { type: 'text/plain' })));

  // The quad meshers' files (docs/export.md): Directional's .sing (every singularity of the field), QuadWild's
  // .rosy (a cross field; the worker refuses another N by name) and .sharp (the feature edges in use).
  const exportSing = () => call('exportSing', []);
  const exportRosy = () => call('exportRosy', []);
  const exportSharp = () => call('exportSharp', []);
  const downloadText = (extension, make) =>
    make().then((text) => downloadBlob(`${modelName()}.${extension}`, new Blob([text], { type: 'text/plain' })));

  const downloadGlb = (opts) =>
    exportGlb(opts).then((glb) =>
      downloadBlob(`${modelName()}.field.glb`, new Blob([glb], { type: 'model/gltf-binary' })),
    );

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
        .then((png) =>
          downloadBlob(
            `${modelName()}.flow-${options.convention}-${options.size}.png`,
            new Blob([png], { type: 'image/png' }),
          ),
        )
        .catch(onError),
    onGlb: () => downloadGlb().catch(onError),
    onRawField: () => downloadRawField().catch(onError),
    onSing: () => downloadText('sing', exportSing).catch(onError),
    onRosy: () => downloadText('rosy', exportRosy).catch(onError),
    onSharp: () => downloadText('sharp', exportSharp).catch(onError),
    onPreview: (preset) => materialPreview(preset).catch(onError),
  });

  ui.setSymmetry(symmetry());

  return {
    exportFlowMap,
    exportGlb,
    exportRawField,
    exportSing,
    exportRosy,
    exportSharp,
    downloadGlb,
    materialPreview,
    materialPreviewInfo: () => refresh.then(() => preview.info()),
    exportOptions: () => ({ ...options }),
    setExportOptions: setOptions,
    // The field or the model changed: a visible preview follows.
    fieldChanged: () => {
      ui.setSymmetry(symmetry());
      if (previewPreset) showPreview().catch(onError);
    },
    dispose() {
      previewPreset = null;
      preview.dispose();
      ui.dispose();
    },
  };
}

// The options the core's writer reads (wasm/export_bindings.cpp optionsFrom).
function coreOptions(o) {
  const out = { ...o };
  for (const k of TEXTURE_KEYS) delete out[k];
  return out;
}
