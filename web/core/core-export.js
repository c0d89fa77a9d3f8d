// Worker side of the exports (docs/export.md): the wasm FieldExporter (wasm/export_bindings.cpp) over the welded
// mesh the core already holds (handed over once per model, on the first export: the model file is not parsed
// again). Of a glTF/GLB file only its document is kept, so a GLB keeps the model's own glTF and a field-only
// export matches `tvf export` byte for byte. One per worker, i.e. per <tangent-field-designer> element.
import { CoreError } from './core-error.js';

// What only a line or cross field can be exported as (the export panel offers it for N ≥ 2 alone).
const RAW_FIELD_REFUSAL =
  'a cross-field file (raw field) holds line and cross fields; this is a vector field: choose Line or Cross';

// QuadWild's .rosy holds a cross field; the page's words for the other N.
const ROSY_REFUSAL = (n) =>
  `a QuadWild .rosy file holds a cross field (symmetry 4); this is a ${FIELD_NAMES[n] ?? `${n}-direction field`}` +
  ': choose Cross';
const FIELD_NAMES = { 1: 'vector field', 2: 'line field', 4: 'cross field' };

const isGltf = (format) => format === 'glb' || format === 'gltf';

export class CoreExport {
  // core: the worker's CoreClient (its Designer holds the mesh).
  constructor(core) {
    this.core = core;
    this.Module = core.Module;
    this.source = null; // {bytes, format} of a glTF/GLB model: the document a GLB export keeps
    this.exporter = null; // made on the first export: most sessions never export
  }

  // The core just loaded this file: the exporter's mesh is now stale. Only a glTF/GLB file's bytes are kept.
  modelLoaded(bytes, format) {
    this.exporter?.delete();
    this.exporter = null;
    const f = (format || sniffFormat(bytes)).toLowerCase().replace(/^\./, '');
    this.source = isGltf(f) ? { bytes: bytes.slice(), format: f } : null;
  }

  // The design a GLB written by this project carries in its extras, or null.
  embeddedDesign(bytes) {
    return JSON.parse(this.Module.embeddedDesignJson(bytes));
  }

  #loaded() {
    if (this.exporter) return this.exporter;
    if (!this.core.hasMesh) throw new CoreError('export: no model loaded');
    const d = this.core.designer;
    const exporter = new this.Module.FieldExporter();
    // Copies first: the views point into wasm memory, which the exporter's own allocations may move.
    const mesh = [d.positions().slice(), d.triangles().slice(), d.cornerUVs().slice(), d.sourceToWelded().slice()];
    let error = exporter.setMesh(...mesh);
    if (!error && this.source) error = exporter.setSource(this.source.bytes, this.source.format);
    if (error) {
      exporter.delete();
      throw new CoreError(`export: ${error}`);
    }
    this.exporter = exporter;
    return exporter;
  }

  // '' when the model's own UVs are the flow map's atlas, else why not (then one is generated).
  atlasNote() {
    return this.#loaded().atlasNote();
  }

  // field: {oneForm} of a vector field, or {faceDirections, symmetry} of a direction field (one unit
  // representative per face; the core combs them per chart of the atlas).
  flowMapPng(field, options) {
    const exporter = this.#loaded();
    const png = field.faceDirections
      ? exporter.directionFlowMapPng(field.faceDirections, field.symmetry, JSON.stringify(options))
      : exporter.flowMapPng(field.oneForm, JSON.stringify(options));
    if (!png) throw new CoreError(`export: ${exporter.lastError()}`);
    return png;
  }

  // texture: null, or {png: Uint8Array, cornerUVs: Float32Array (6 per face)}: the synthesized texture and its
  // atlas, embedded as base colour; its UVs then index the flow map too.
  glb(field, design, options, texture = null) {
    const exporter = this.#loaded();
    const text = design ? JSON.stringify(design) : '';
    const glb = field.faceDirections
      ? exporter.directionGlb(field.faceDirections, field.symmetry, text, JSON.stringify(options), texture)
      : exporter.glb(field.oneForm, text, JSON.stringify(options), texture);
    if (!glb) throw new CoreError(`export: ${exporter.lastError()}`);
    return glb;
  }

  // Directional's raw field text (all N directions per face, io/raw_field.h) of a line or cross field.
  rawField(field) {
    const exporter = this.#loaded();
    const text = exporter.rawField(field.faceDirections, field.symmetry);
    if (!text) throw new CoreError(`export: ${exporter.lastError()}`);
    return text;
  }

  // The quad meshers' files (docs/export.md) by the core's writers, from the read-outs `tvf export
  // --sing/--rosy/--sharp` writes them from: the same bytes.
  // singularities: [{vertex, index}, ...], every one the field has.
  singFile(symmetry, singularities) {
    return this.#text('.sing', (x) => x.singFile(symmetry, JSON.stringify(singularities)));
  }

  rosyFile(field) {
    if (field.symmetry !== 4) throw new CoreError(ROSY_REFUSAL(field.symmetry));
    return this.#text('.rosy', (x) => x.rosyFile(field.faceDirections, field.symmetry));
  }

  // featureEdges: the Designer's edge indices of the features in use.
  sharpFile(featureEdges) {
    return this.#text('.sharp', (x) => x.sharpFile(featureEdges));
  }

  // A .sing file read: {symmetry, singularities: [{vertex, index}]}; throws the reader's refusal (naming the line).
  readSing(text) {
    const read = JSON.parse(this.Module.readSingJson(String(text)));
    if (read.error) throw new CoreError(read.error);
    return read;
  }

  #text(what, write) {
    const exporter = this.#loaded();
    const out = write(exporter);
    if (!out) throw new CoreError(`export ${what}: ${exporter.lastError()}`);
    return out;
  }
}

// The loader's sniffing (io/mesh_io.h formatFromBytes), for a file opened with no format named: only whether
// it is glTF matters here.
function sniffFormat(bytes) {
  const b = bytes instanceof Uint8Array ? bytes : new Uint8Array(bytes);
  if (b[0] === 0x67 && b[1] === 0x6c && b[2] === 0x54 && b[3] === 0x46) return 'glb';
  for (const c of b.subarray(0, 64)) {
    if (c === 0x7b) return 'gltf'; // '{'
    if (c !== 0x20 && c !== 0x09 && c !== 0x0a && c !== 0x0d && c !== 0xef && c !== 0xbb && c !== 0xbf) return '';
  }
  return '';
}

// The worker's export ops (worker/dispatch.js files them as `onMesh`): the same bytes as `tvf export` for this
// model file (docs/export.md), of the field and design the core holds now.
export function exportOps(state) {
  // What the exports read of the field: a vector field's one-form, or the directions of a line or cross field
  // (or of a unit vector field with prescribed singularities, which has no one-form).
  const field = () => {
    const symmetry = state.core.symmetry();
    const oneForm = symmetry > 1 ? null : state.core.oneForm();
    if (!oneForm || oneForm.length === 0) return { symmetry, faceDirections: state.core.faceVectors() };
    return { symmetry, oneForm };
  };
  const design = () => JSON.parse(state.core.designJson());

  const onMesh = {
    exportAtlasNote() {
      return state.coreExport.atlasNote();
    },

    exportFlowMap(options) {
      return state.coreExport.flowMapPng(field(), options);
    },

    // texture: null, {png, cornerUVs} (the synthesized texture), or {stripes: {profile, light, dark}}: the core's
    // current stripe pattern (client/stripe-calls.js, the one the page shows) baked in (web/export/index.js).
    exportGlb(options, texture) {
      const baked = texture?.stripes ? { stripes: { ...texture.stripes, ...state.core.stripeArrays() } } : texture;
      return state.coreExport.glb(field(), design(), options, baked);
    },

    // A line or cross field as Directional's raw field text (docs/export.md).
    exportRawField() {
      const f = field();
      if (f.symmetry < 2) throw new CoreError(RAW_FIELD_REFUSAL);
      return state.coreExport.rawField(f);
    },

    // Directional's .sing: every singularity of the field, prescribed or placed by it (as tvf export --sing).
    exportSing() {
      const list = state.core.singularities().map(({ vertex, index }) => ({ vertex, index }));
      return state.coreExport.singFile(state.core.symmetry(), list);
    },

    // QuadWild's .rosy (a cross field only) and .sharp (the feature edges in use).
    exportRosy() {
      const symmetry = state.core.symmetry();
      return state.coreExport.rosyFile({ symmetry, faceDirections: symmetry === 4 ? state.core.faceVectors() : null });
    },

    exportSharp() {
      return state.coreExport.sharpFile(state.core.featureEdges());
    },

    // A .sing file's text read by the core: {symmetry, singularities}; nothing changes.
    readSing(text) {
      return state.coreExport.readSing(text);
    },
  };
  return { onMesh };
}
