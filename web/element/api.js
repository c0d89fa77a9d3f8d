// The designer's public JavaScript API (docs/js-api.md, docs/embedding.md): every method of a
// <tangent-field-designer> element, as functions of its Designer (designer.js; `d.session` is the model).
// The element installs them on its prototype; the app page's window.tvf is its element, so the same
// functions serve both. Each method's types and description are declared in declaration.js, from which
// `npm run gen:api` writes custom-elements.json, types/element.d.ts and docs/js-api.md's summary; a method added
// here, or to TEXTURE_METHODS, goes there too (tests/node/api-declaration.test.mjs fails otherwise).
import { DEFAULT_WEIGHT } from '../session/session.js';
import { edgeSpec, pointSpec, strokeSpec, vectorSpec } from '../session/specs.js';
import { cameraState, setCameraState } from '../views/camera.js';
import { captureScreenshot } from '../views/screenshot.js';

// Synchronous reads: copies of what the session holds after the last completed change.
const read =
  (fn) =>
  (d, ...args) => {
    d.session.requireReady();
    return fn(d, d.session, ...args);
  };
const add = (d, spec) => d.session.addConstraint(spec);
// A worker read-out of the session's current field (an op taking the field's version first); called in the
// session's queue, where no edit can change the field before it answers.
async function workerRead(d, op, ...args) {
  if (d.session.field?.stats?.preview) await d.session.settled(); // the exact core reads its own field only
  const value = (await d.session.proxy.call(op, [d.session.field.version, ...args])).value;
  if (value == null) throw new Error(`${op}: the core's field is not the page's (version ${d.session.field.version})`);
  return value;
}

export const api = {
  loadModel: (d, src, opts) => d.session.loadModel(src, opts),
  info: read((d, s) => structuredClone(s.info)),
  mesh: read((d, s) => ({ positions: s.surface.positions.slice(), triangles: s.surface.triangles.slice() })),
  edges: read((d, s) => s.surface.edges.slice()),

  addStroke: (d, points, { strength = 1, weight = DEFAULT_WEIGHT } = {}) =>
    add(d, strokeSpec(points, { strength, weight })),
  addVector: (d, face, vector, { weight = DEFAULT_WEIGHT } = {}) => add(d, vectorSpec(face, vector, { weight })),
  addEdge: (d, edge, value, { weight = DEFAULT_WEIGHT } = {}) => add(d, edgeSpec(edge, value, { weight })),
  addSource: (d, vertex, { strength = 1 } = {}) => add(d, pointSpec('source', vertex, strength)),
  addSink: (d, vertex, { strength = 1 } = {}) => add(d, pointSpec('sink', vertex, strength)),
  addVortex: (d, face, { strength = 1 } = {}) => add(d, pointSpec('vortex', face, strength)),
  remove: (d, id) => d.session.remove(id),
  setWeight: (d, id, w) => d.session.setParameter('weight', id, w),
  setStrength: (d, id, v) => d.session.setParameter('strength', id, v),
  addSingularity: (d, vertex, index) => d.session.topology.addSingularity(vertex, index),
  moveSingularity: (d, id, vertex) => d.session.topology.moveSingularity(id, vertex),
  removeSingularity: (d, id) => d.session.topology.removeSingularity(id),
  setFeatures: (d, features) => d.session.topology.setFeatures(features),
  setExactSingularities: (d, exact) => d.session.topology.setExactSingularities(exact),
  loadSing: (d, text) => d.session.topology.addSingFile(text),
  features: read((d, s) => s.topology.features()),
  constraints: (d) => d.session.constraintList(),
  setBoundary: (d, bc) => d.session.setSetting('boundary', bc),
  setGamma: (d, gamma) => d.session.setSetting('gamma', gamma),
  // Resolves with the constraints the new N could not keep and removed in the same step (undo restores them).
  setSymmetry: (d, n) => d.session.setSetting('symmetry', n),
  setCurvatureAlignment: (d, strength) => d.session.setSetting('curvatureAlignment', strength),
  settings: (d) => structuredClone(d.session.settings()),

  undo: (d) => d.session.step(false),
  redo: (d) => d.session.step(true),
  history: (d) => d.session.history.labels(),

  saveDesign: read((d, s) => structuredClone(s.design)),
  frame: read((d, s, view = 'home') => d.viewer.frame(view)),
  camera: (d) => cameraState(d.viewer),
  // A PNG Blob of the view at {width, height} pixels (default: the canvas), {transparent} background.
  screenshot: (d, options) => {
    d.session.requireReady();
    return captureScreenshot(d.viewer, options);
  },
  setCamera: (d, state) => setCameraState(d.viewer, state),
  hasUnsavedEdits: (d) => d.session.hasUnsavedEdits(),
  // options.ignoreFingerprint: apply a design saved for another mesh anyway.
  loadDesign: (d, design, options) =>
    d.session.replaceDesign(design, 'load design', options).catch((err) => {
      throw d.session.fail('design', err);
    }),
  exportField: (d) => d.session.exportField().then((text) => JSON.parse(text)),
  // docs/export.md: Uint8Arrays with the same bytes as `tvf export` for this model file and field; the GLB also
  // carries the synthesized texture when one is shown (options.texture).
  exportFlowMap: (d, options) => d.exports.exportFlowMap(options),
  exportGlb: (d, options) => d.exports.exportGlb(options),
  exportRawField: (d) => d.exports.exportRawField(),
  exportSing: (d) => d.exports.exportSing(),
  exportRosy: (d) => d.exports.exportRosy(),
  exportSharp: (d) => d.exports.exportSharp(),
  exportOptions: (d) => d.exports.exportOptions(),
  setExportOptions: (d, options) => d.exports.setExportOptions(options),
  materialPreview: (d, preset) => d.exports.materialPreview(preset),
  materialPreviewInfo: (d) => d.exports.materialPreviewInfo(),

  faceVectors: read((d, s) => s.fieldArray('faceVectors').slice()),
  vertexVectors: read((d, s) => s.field.vertexVectors.slice()),
  oneForm: read((d, s) => s.fieldArray('oneForm').slice()),
  singularities: read((d, s) => structuredClone(s.currentSingularities())),
  singularitySummary: read((d, s) => s.topology.summary()),
  stats: read((d, s) => structuredClone(s.field.stats)),
  settled: (d) => d.session.settled(),
  // The Hodge decomposition of the current field (docs/js-api.md): made by the worker on the first request for a
  // field and kept there until the next solve. In the queue, so it is the field that the edits before it made.
  hodge: (d) =>
    d.session.exclusive(async () => {
      d.session.requireReady();
      const { exact, coexact, harmonic, potential0, potential2, energyShares, innerProduct, metric, decomposeMs } =
        await workerRead(d, 'hodge');
      return { exact, coexact, harmonic, potential0, potential2, energyShares, innerProduct, metric, decomposeMs };
    }),

  select: (d, id) => d.session.select(id),
  selected: (d) => d.session.selected,
  views: (d) => ({ ...d.viewSync.views }),
  setViews: (d, views) => d.viewSync.set(views),
  // Stripe patterns (web/stripes/, docs/js-api.md): the options, shown or not, and the pattern's stats.
  setStripes: (d, opts) => d.stripes.setStripes(opts),
  stripes: (d) => d.stripes.state(),
  stripesIdle: (d, options) => d.stripes.whenIdle(options),
  // Quad meshes (web/quad/, docs/js-api.md): no edit, no history entry; each run on a worker of its own.
  remesh: async (d, options) => {
    d.session.requireReady();
    return d.quad.remesh(options);
  },
  cancelRemesh: (d) => d.quad.cancel(),
  quadMesh: (d) => d.quad.state(),
  exportQuadObj: (d) => d.quad.exportObj(),
  exportQuadGlb: (d) => d.quad.exportGlb(),
  streamlines: read((d) => d.viewSync.currentStreamlines().map((l) => Array.from(l))),
  // The direction cues drawn on the streamlines: each chevron's tip and the middle of its back.
  streamlineCues: read((d) => d.viewer.streamlines.cues.map(({ tip, back }) => ({ tip, back }))),
  strokeCues: read((d) => d.viewer.handles.cues()),
  singularityMarkers: read((d) => d.viewer.singularities.drawn()),
  // The arrows as drawn (the instances on the GPU): anchor and vector (model units) of each.
  arrowInstances: read((d) => {
    const { anchors, vectors } = d.viewer.arrows.drawn();
    return { anchors: Array.from(anchors), vectors: Array.from(vectors) };
  }),
  perf: (d) => structuredClone(d.session.perf),
  projectToScreen: read((d, s, xyz) => d.viewer.projectToScreen(Array.from(xyz))),
  pick: read((d, s, clientX, clientY) => d.viewer.pick(clientX, clientY)),

  // Autosave versions (IndexedDB, docs/js-api.md): newest first; restore one as an undoable design change.
  autosaveVersions: (d) => d.session.autosave.versions(),
  restoreAutosave: (d, id) => d.session.autosave.restore(id),
  autosaveIdle: (d) => d.session.autosave.idle().then(() => true),

  // Supervision (docs/js-api.md): stop the operation in flight; how often the core was replaced and why.
  cancel: (d) => Promise.resolve(d.session.cancel()),
  supervision: (d) => d.session.supervision(),
  // What a crash of the core's worker does, on purpose (tests, demonstrations); a memory limit for the factor
  // (0: the wasm address space left) so tests need no multi-million-edge mesh.
  debugDelayExact: (d, ms) => {
    d.session.debugExactDelayMs = ms;
  },
  debugTextureFollowMs: (d, ms) => {
    d.synthesis.followMs = ms ?? undefined;
  },
  debugStripesFollowMs: (d, ms) => {
    d.stripes.followMs = ms ?? undefined;
  },
  debugTerminateCore: (d) => d.session.proxy?.terminateForTest(),
  debugHangCore: (d, ms) => d.session.proxy?.hangForTest(ms),
  debugTrapCore: (d) => d.session.exclusive(() => d.session.proxy.call('trapForTest')),
  debugSetFactorMemoryLimit: (d, bytes) =>
    d.session.exclusive(() => d.session.proxy.call('setFactorMemoryLimit', [bytes])).then(() => true),
  // The tests' references for what the page derives lazily or keeps incrementally: the core's own read-outs
  // ({oneForm, faceVectors, vertexVectors, singularities, design}, derived by the core now), and streamlines
  // traced on the page now for the current field and spacing (whatever the view's cache, traced in the worker,
  // holds).
  debugCoreReadout: (d) =>
    d.session.exclusive(async () => {
      d.session.requireReady();
      return (await d.session.proxy.call('read')).value;
    }),
  debugTraceStreamlines: read((d) => d.viewSync.traceStreamlinesHere().map((l) => Array.from(l))),
  debugGlPrograms: (d) => d.viewer.renderer.info.programs.length,
  // From now on, the time of every frame the view draws, pushed onto the array returned (in the page).
  debugRecordFrames: (d) => (d.viewer.frameLog = []),
  // The big-surface layer (views/surface-layer.js) from minFaces faces on (when given), and its counts.
  debugSurfaceLayer: (d, minFaces) => {
    const layer = d.viewer.surfaceLayer;
    if (minFaces != null) {
      layer.minFaces = minFaces;
      layer.invalidate();
      d.viewer.renderNow();
    }
    return {
      minFaces: layer.minFaces,
      drawn: layer.drawn,
      copied: layer.copied,
      rect: layer.rect && { ...layer.rect },
    };
  },
  // The worker's `component` op for the current field: {oneForm, faceVectors, vertexVectors} of 'whole' |
  // 'exact' | 'coexact' | 'harmonic'.
  debugComponent: (d, name) =>
    d.session.exclusive(() => {
      d.session.requireReady();
      return workerRead(d, 'component', name);
    }),
};

// The texture-synthesis calls (web/synthesis/index.js installs them on the designer's synthesis controller).
export const TEXTURE_METHODS = [
  'setExemplar',
  'synthesize',
  'exportTexturePNG',
  'synthesisStats',
  'clearTexture',
  'exemplarInfo',
  'synthesisReadback',
  'synthesisIdle',
  'synthesisProgress',
  'setTextureAutoUpdate',
  'synthesisBench',
];
