// Worker side of the exports (docs/export.md): the wasm FieldExporter (wasm/export_bindings.cpp) holding the
// model file as it was opened, so a GLB keeps the model's own glTF and the bytes match `tvf export`.
// One per worker, i.e. per <tangent-field-designer> element.
import { CoreError } from './core-client.js';

export class CoreExport {
  constructor(Module) {
    this.Module = Module;
    this.model = null; // {bytes, format} of the mesh the designer holds
    this.exporter = null; // loaded lazily: most sessions never export
  }

  // The file the designer just loaded (before it is parsed elsewhere): kept for export and embedded designs.
  modelLoaded(bytes, format) {
    this.exporter?.delete();
    this.exporter = null;
    this.model = { bytes: bytes.slice(), format };
  }

  // The design a GLB written by this project carries in its extras, or null.
  embeddedDesign(bytes) {
    return JSON.parse(this.Module.embeddedDesignJson(bytes));
  }

  #loaded() {
    if (!this.model) throw new CoreError('export: no model loaded');
    if (!this.exporter) {
      const exporter = new this.Module.FieldExporter();
      const error = exporter.load(this.model.bytes, this.model.format);
      if (error) {
        exporter.delete();
        throw new CoreError(`export: ${error}`);
      }
      this.exporter = exporter;
    }
    return this.exporter;
  }

  // '' when the model's own UVs are the flow map's atlas, else why not (then one is generated).
  atlasNote() {
    return this.#loaded().atlasNote();
  }

  flowMapPng(oneForm, options) {
    const exporter = this.#loaded();
    const png = exporter.flowMapPng(oneForm, JSON.stringify(options));
    if (!png) throw new CoreError(`export: ${exporter.lastError()}`);
    return png;
  }

  glb(oneForm, design, options, baseColorPng = null) {
    const exporter = this.#loaded();
    const glb = exporter.glb(oneForm, design ? JSON.stringify(design) : '', JSON.stringify(options), baseColorPng);
    if (!glb) throw new CoreError(`export: ${exporter.lastError()}`);
    return glb;
  }
}
