// What an edit's reply carries after its solve (dispatch.js): the field arrays the views need, copied out of
// the wasm heap (a memcpy each, into spares where the page has handed some back) and transferred; the stats;
// and the design as a change to the page's copy (the constraints the edit touched and the id order) rather
// than the whole document; the edges the field follows as features. Everything else is derived when it is read
// or shown: the singularities on the page (the core's own with prescribed ones: fieldTopology), the streamlines
// and Hodge parts here on request (read-ops.js), the whole document on request (`read`).
// Imports nothing beyond the worker's state.

// changed: core ids whose design entry the op set (null: the whole document, after a load, a setting, a design,
// or an edit taken back). timing receives where the time goes. A preview worker answers with its preview field
// on the fine mesh instead (preview/preview.js).
export function snapshot(state, changed, timing = {}) {
  if (state.preview) return state.preview.snapshot(state.spares, timing, changed);
  return exactSnapshot(state, changed, timing);
}

// `symmetry`: the field's N (faceVectors and vertexVectors are then unit representatives, one of the N
// directions: web/views/). The vertex vectors are derived here because the default arrow view interpolates
// them, and the magnitude scale with them (derived-field.js).
function exactSnapshot(state, changed, timing) {
  const { core, spares } = state;
  let t = performance.now();
  const lap = (key) => {
    const now = performance.now();
    timing[key] = now - t;
    t = now;
  };
  const field = state.nextField();
  const counts = { reused: 0 };
  const copy = (view) => spares.copyOut(view, counts);
  const faceVectors = core.faceVectors(copy);
  const oneForm = core.oneForm(copy);
  lap('copyMs');
  const vertexVectors = core.vertexVectors(copy);
  lap('deriveMs');
  timing.reusedArrays = counts.reused;
  const ids = core.constraintIds();
  // specs: every constraint's in the ids' order (the document lists the prescribed singularities apart).
  const design = changed
    ? { ids, changed: changed.filter((id) => ids.includes(id)).map((id) => [id, core.constraint(id)]) }
    : { ids, document: JSON.parse(core.designJson()), specs: core.constraintSpecs() };
  lap('designMs');
  // heapBytes: the wasm memory, which never shrinks: the peak so far.
  const stats = { ...core.stats(), preview: false, heapBytes: core.Module.HEAP8.buffer.byteLength };
  lap('statsMs');
  const { singularities, featureEdges } = fieldTopology(core, stats);
  lap('topologyMs');
  return {
    version: field.version,
    symmetry: core.symmetry(),
    faceVectors,
    vertexVectors,
    oneForm,
    scale: field.magnitudeScale(vertexVectors),
    stats,
    design,
    singularities,
    featureEdges,
    transfer: [faceVectors.buffer, vertexVectors.buffer, oneForm.buffer].concat(
      featureEdges.length ? [featureEdges.buffer] : [],
    ),
  };
}

// With prescribed singularities the core's own read-out ([{vertex, index, prescribed}]), which knows which
// indices the design prescribes (the page finds a field's singularities itself otherwise: null); and the edges
// the field follows as features, as vertex pairs (flat Int32Array, empty when none).
function fieldTopology(core, stats) {
  const singularities = stats.singularityMode && stats.singularityMode !== 'none' ? core.singularities() : null;
  const featureEdges = stats.featureEdges > 0 ? core.featureEdgePairs() : new Int32Array(0);
  return { singularities, featureEdges };
}
