// The designer's public JavaScript API (docs/js-api.md, docs/embedding.md): every method of a
// <tangent-field-designer> element, as functions of its session. The element installs them on its prototype;
// the app page's window.tvf is its element, so the same functions serve both.
import { cameraState, setCameraState } from './camera.js';
import { captureScreenshot } from './screenshot.js';
import { DEFAULT_WEIGHT } from './session.js';
import { edgeSpec, pointSpec, strokeSpec, vectorSpec } from './specs.js';

// Synchronous reads: copies of what the session holds after the last completed change.
const read = (fn) => (s, ...args) => (s.requireReady(), fn(s, ...args));

export const api = {
  loadModel: (s, src, opts) => s.loadModel(src, opts),
  info: read((s) => structuredClone(s.info)),
  mesh: read((s) => ({ positions: s.surface.positions.slice(), triangles: s.surface.triangles.slice() })),
  edges: read((s) => s.surface.edges.slice()),

  addStroke: (s, points, { strength = 1, weight = DEFAULT_WEIGHT } = {}) => s.addConstraint(() => strokeSpec(s, points, { strength, weight })),
  addVector: (s, face, vector, { weight = DEFAULT_WEIGHT } = {}) => s.addConstraint(() => vectorSpec(s, face, vector, { weight })),
  addEdge: (s, edge, value, { weight = DEFAULT_WEIGHT } = {}) => s.addConstraint(() => edgeSpec(s, edge, value, { weight })),
  addSource: (s, vertex, { strength = 1 } = {}) => s.addConstraint(() => pointSpec(s, 'source', vertex, strength)),
  addSink: (s, vertex, { strength = 1 } = {}) => s.addConstraint(() => pointSpec(s, 'sink', vertex, strength)),
  addVortex: (s, face, { strength = 1 } = {}) => s.addConstraint(() => pointSpec(s, 'vortex', face, strength)),
  remove: (s, id) => s.remove(id),
  setWeight: (s, id, w) => s.setParameter('weight', id, w),
  setStrength: (s, id, v) => s.setParameter('strength', id, v),
  constraints: (s) => s.constraintList(),
  setBoundary: (s, bc) => s.setSetting('boundary', bc),
  setGamma: (s, gamma) => s.setSetting('gamma', gamma),
  settings: (s) => structuredClone(s.settings()),

  undo: (s) => s.step(false),
  redo: (s) => s.step(true),
  history: (s) => s.history.labels(),

  saveDesign: read((s) => structuredClone(s.design)),
  frame: read((s, view = 'home') => s.viewer.frame(view)),
  camera: (s) => cameraState(s.viewer),
  // A PNG Blob of the view at {width, height} pixels (default: the canvas), {transparent} background.
  screenshot: (s, options) => (s.requireReady(), captureScreenshot(s.viewer, options)),
  setCamera: (s, state) => setCameraState(s.viewer, state),
  hasUnsavedEdits: (s) => s.hasUnsavedEdits(),
  // options.ignoreFingerprint: apply a design saved for another mesh anyway.
  loadDesign: (s, design, options) =>
    s.replaceDesign(design, 'load design', options).catch((err) => {
      throw s.fail('design', err);
    }),
  exportField: (s) => s.exportField().then((text) => JSON.parse(text)),
  // docs/export.md: Uint8Arrays with the same bytes as `tvf export` for this model file and field.
  exportFlowMap: (s, options) => s.exports.exportFlowMap(options),
  exportGlb: (s, options) => s.exports.exportGlb(options),
  exportOptions: (s) => s.exports.exportOptions(),
  setExportOptions: (s, options) => s.exports.setExportOptions(options),
  materialPreview: (s, preset) => s.exports.materialPreview(preset),
  materialPreviewInfo: (s) => s.exports.materialPreviewInfo(),

  faceVectors: read((s) => s.field.faceVectors.slice()),
  vertexVectors: read((s) => s.field.vertexVectors.slice()),
  oneForm: read((s) => s.field.oneForm.slice()),
  singularities: read((s) => structuredClone(s.currentSingularities())),
  stats: read((s) => structuredClone(s.field.stats)),

  select: (s, id) => s.select(id),
  selected: (s) => s.selected,
  views: (s) => ({ ...s.views }),
  setViews: (s, views) => s.setViews(views),
  streamlines: read((s) => s.currentStreamlines().map((l) => Array.from(l))),
  // The arrows as drawn (the instances on the GPU): anchor and vector (model units) of each.
  // The direction cues drawn on the streamlines: each chevron's tip and the middle of its back.
  streamlineCues: read((s) => s.viewer.streamlines.cues.map(({ tip, back }) => ({ tip, back }))),
  strokeCues: read((s) => s.viewer.handles.cues()),
  singularityMarkers: read((s) => s.viewer.singularities.drawn()),
  arrowInstances: read((s) => {
    const { anchors, vectors } = s.viewer.arrows.drawn();
    return { anchors: Array.from(anchors), vectors: Array.from(vectors) };
  }),
  perf: (s) => structuredClone(s.perf),
  projectToScreen: read((s, xyz) => s.viewer.projectToScreen(Array.from(xyz))),
  pick: read((s, clientX, clientY) => s.viewer.pick(clientX, clientY)),

  // Autosave versions (IndexedDB, docs/js-api.md): newest first; restore one as an undoable design change.
  autosaveVersions: (s) => s.autosaveVersions(),
  restoreAutosave: (s, id) => s.restoreAutosave(id),
  autosaveIdle: (s) => s.autosaveIdle().then(() => true),

  // Supervision (docs/js-api.md): stop the operation in flight; how often the core was replaced and why.
  cancel: (s) => Promise.resolve(s.cancel()),
  supervision: (s) => s.supervision(),
  // What a crash of the core's worker does, on purpose (tests, demonstrations); a memory limit for the factor
  // (0: the wasm address space left) so tests need no multi-million-edge mesh.
  debugTerminateCore: (s) => s.proxy?.terminateForTest(),
  debugHangCore: (s, ms) => s.proxy?.hangForTest(ms),
  debugTrapCore: (s) => s.exclusive(() => s.proxy.call('trapForTest')),
  debugSetFactorMemoryLimit: (s, bytes) => s.exclusive(() => s.proxy.call('setFactorMemoryLimit', [bytes])).then(() => true),
  // The tests' references for what the page derives lazily or keeps incrementally: the core's own read-outs
  // ({oneForm, faceVectors, vertexVectors, singularities, design}, derived by the core now), and streamlines traced on the
  // page now for the current field and spacing (whatever the view's cache, traced in the worker, holds).
  debugCoreReadout: (s) => s.exclusive(async () => (s.requireReady(), (await s.proxy.call('read')).value)),
  debugTraceStreamlines: read((s) => s.traceStreamlinesHere().map((l) => Array.from(l))),
};

// The texture-synthesis calls (web/synthesis/index.js installs them on the session's synthesis controller).
export const TEXTURE_METHODS = [
  'setExemplar',
  'synthesize',
  'exportTexturePNG',
  'exportGLB',
  'synthesisStats',
  'clearTexture',
  'exemplarInfo',
  'synthesisReadback',
  'synthesisIdle',
  'synthesisProgress',
  'setTextureAutoUpdate',
  'synthesisBench',
];
