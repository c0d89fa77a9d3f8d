// Page entry: ties the core worker, the three.js view, the tools and the panels together, and exposes the
// same operations as window.tvf (docs/js-api.md) for tests and embedding pages.
//
// The core runs in a module worker (core-worker.js); every edit is one request that ends with a solve and a
// snapshot (field arrays, singularities, stats, the design), which the page keeps so that reads stay
// synchronous. Constraints carry page ids ("uids") that survive a delete and its undo, although the core
// hands out a fresh id when it re-adds the constraint.
import { CoreProxy } from './core-proxy.js';
import { baseName, downloadJson, loadAutosave, modelKey, readJsonFile, saveAutosave } from './documents.js';
import { History, describe as describeEntry } from './history.js';
import { ACCEPT, readModel } from './model-files.js';
import { traceStreamlines } from './streamlines.js';
import { Surface } from './surface.js';
import { ToolController } from './tools.js';
import { bindUi } from './ui.js';
import { Viewer, arrowDensityFor } from './viewer.js';
import { setupSynthesis } from './synthesis/index.js'; // texture synthesis: window.tvf additions + "Texture" panel

// An arrow per face stops being readable (and software rendering stops being quick) beyond this many.
const MAX_DEFAULT_ARROWS = 20_000;
// Weight 1e4 keeps strokes within ~0.4% of the drawn direction (paper, Sec. 6.1) while the rank-1 updates
// stay well conditioned.
export const DEFAULT_WEIGHT = 1e4;
const DEFAULT_MODEL = 'models/bunny.glb';
const BASE = new URL('./', import.meta.url);

const state = {
  proxy: null,
  viewer: null,
  ui: null,
  tools: null,
  history: null,
  modelName: '',
  modelKey: '',
  modelSource: null, // {bytes, format}: what a restarted core reloads
  loadsPending: 0, // model loads asked for and not finished: tool input meanwhile is refused
  info: null,
  surface: null,
  field: null, // {faceVectors, vertexVectors, oneForm, singularities, stats} of the last completed change
  design: { boundary: 'free', gamma: 0, constraints: [] }, // the core's document, verbatim
  specByCore: new Map(), // core id → spec (design format)
  coreOrder: [], // core ids in the core's order (that of design.constraints)
  constraints: new Map(), // uid → core id
  nextUid: 1,
  selected: null,
  views: null,
  densityAuto: false, // the arrow density was lowered for a large mesh, not chosen by the user
  fieldVersion: 0,
  streamlineCache: null, // {version, spacing, surface, lines}
  arrowsAhead: false, // the arrows already show the field of the edit in flight (worker's early message)
  earlyFrame: null, // resolves when those arrows were on screen
  perf: {},
};

// Every mutation runs alone and in call order: the worker's state and the page's copies move together.
let queue = Promise.resolve();
function exclusive(fn) {
  const run = queue.then(fn);
  queue = run.catch(() => {});
  return run;
}

function requireReady() {
  if (!state.proxy || !state.info || !state.field) throw new Error('tvf is not ready yet; await tvf.ready first');
}

const PROGRESS_LABELS = {
  loadMesh: 'Loading and factoring…',
  setBoundary: 'Refactoring…',
  setGamma: 'Refactoring…',
  applyDesign: 'Applying the design…',
  fieldJson: 'Exporting…',
};

// One request to the worker; the snapshot it returns (also with a failure) becomes the page's state.
async function call(op, args = [], transfer = []) {
  const end = state.ui.startProgress(PROGRESS_LABELS[op] ?? 'Updating…');
  const t0 = performance.now();
  const renders0 = state.viewer.renderCount;
  let earlyFrame = null;
  // The new arrows go on screen as soon as the worker has solved; reads (tvf.faceVectors() ...) still show the
  // previous change until the whole snapshot is in.
  const onEarly = ({ faceVectors }) => {
    if (!state.surface || faceVectors.length !== 3 * state.surface.nF) return;
    state.viewer.arrows.setField(faceVectors);
    state.arrowsAhead = true;
    // Queued, not drawn now: when the rest of the snapshot follows within a frame, one render shows both.
    earlyFrame = state.viewer.nextRenderShown();
    state.viewer.requestRender();
  };
  try {
    const reply = await state.proxy.call(op, args, transfer, onEarly);
    const t1 = performance.now();
    // Frames the page drew while the worker computed: the page never waits for the core.
    state.perf.lastOp = {
      op,
      workerMs: reply.workerMs,
      workerParts: reply.timing,
      roundTripMs: t1 - t0,
      sentAt: t0,
      receivedAt: t1,
      framesDrawnMeanwhile: state.viewer.renderCount - renders0,
    };
    state.earlyFrame = earlyFrame;
    if (reply.snapshot) applySnapshot(reply.snapshot);
    return reply;
  } catch (err) {
    state.arrowsAhead = false; // whatever was drawn early, the next refresh draws what the core holds
    if (err.reply?.snapshot) applySnapshot(err.reply.snapshot);
    throw err;
  } finally {
    end();
  }
}

function applySnapshot(snap) {
  const { faceVectors, vertexVectors, oneForm, singularities, stats, design, ids } = snap;
  state.field = { faceVectors, vertexVectors, oneForm, singularities, stats };
  state.fieldVersion++;
  state.design = design;
  state.specByCore = new Map(ids.map((id, k) => [id, design.constraints[k]]));
  state.coreOrder = ids;
  for (const [uid, coreId] of state.constraints) if (!state.specByCore.has(coreId)) state.constraints.delete(uid);
  if (state.selected != null && !state.constraints.has(state.selected)) state.selected = null;
}

// Core constraints no page id points at (a loaded design, an autosave) get fresh ids in the core's order.
function adoptUnmapped() {
  const mapped = new Set(state.constraints.values());
  for (const coreId of state.coreOrder ?? []) if (!mapped.has(coreId)) state.constraints.set(state.nextUid++, coreId);
}

// After a document replaced the core's list: give its constraints the page ids `uids` (same order).
function mapDocument(uids) {
  state.constraints.clear();
  const ids = state.coreOrder ?? [];
  if (uids && uids.length === ids.length) uids.forEach((uid, k) => state.constraints.set(uid, ids[k]));
  adoptUnmapped();
}

function uidsInCoreOrder() {
  const byCore = new Map([...state.constraints].map(([uid, coreId]) => [coreId, uid]));
  return (state.coreOrder ?? []).map((id) => byCore.get(id));
}

function coreIdOf(uid) {
  const coreId = state.constraints.get(Number(uid));
  if (coreId === undefined) throw new Error(`no constraint with id ${uid}`);
  return coreId;
}

function specOf(uid) {
  return state.specByCore.get(coreIdOf(uid));
}

function constraintList() {
  return [...state.constraints.keys()].sort((a, b) => a - b).map((uid) => ({ id: uid, ...structuredClone(specOf(uid)) }));
}

function settings() {
  return { boundary: state.design.boundary ?? 'free', gamma: state.design.gamma ?? 0 };
}

// ------------------------------------------------------------------------------------------ drawing

function streamlineSpacing() {
  return state.surface.radius * (0.01 + 0.008 * (state.views?.streamlineSpacing ?? 5));
}

// Traced lazily and cached per field version and spacing: the view and tvf.streamlines() share them.
function currentStreamlines() {
  const spacing = streamlineSpacing();
  const c = state.streamlineCache;
  if (c && c.version === state.fieldVersion && c.spacing === spacing && c.surface === state.surface) return c.lines;
  const t0 = performance.now();
  const lines = traceStreamlines(state.surface, state.field.vertexVectors, { spacing, lift: 0.03 * state.surface.meanEdge });
  state.perf.streamlinesMs = performance.now() - t0;
  state.streamlineCache = { version: state.fieldVersion, spacing, surface: state.surface, lines };
  return lines;
}

let streamlineTimer = 0;
function scheduleStreamlines() {
  clearTimeout(streamlineTimer);
  if (!state.views.streamlines) {
    state.viewer.streamlines.setLines([]);
    return;
  }
  // After the frame that shows the arrows: tracing takes tens of ms and must not delay that frame.
  streamlineTimer = setTimeout(() => {
    state.viewer.streamlines.setLines(currentStreamlines());
    state.viewer.requestRender();
  }, 0);
}

// Pushes the current field, constraints and settings to the view and the panels; draws synchronously.
function refresh() {
  const { viewer, ui, field, views } = state;
  const t0 = performance.now();
  // Drawn already from the worker's early message: the same numbers.
  if (!state.arrowsAhead) viewer.arrows.setField(field.faceVectors);
  state.arrowsAhead = false;
  const max = viewer.setVertexField(field.vertexVectors);
  ui.setLegend(views.colorMap ? max : null);
  viewer.singularities.setSingularities(field.singularities);
  viewer.handles.setConstraints([...state.constraints.keys()].map((uid) => ({ uid, spec: specOf(uid) })));
  viewer.handles.setSelected(state.selected);
  ui.setConstraints(constraintList(), state.selected);
  ui.setSettings(settings());
  ui.setStatus({ name: state.modelName, info: state.info, stats: field.stats });
  refreshHistory();
  const t1 = performance.now();
  viewer.renderNow();
  state.perf.refresh = { updateViewsMs: t1 - t0, renderMs: performance.now() - t1 };
  scheduleStreamlines();
  state.synthesis?.fieldChanged(); // texture synthesis: resynthesize when the field changed (no-op otherwise)
}

function refreshHistory() {
  const h = state.history;
  state.ui.setHistory({
    canUndo: !!h.peekUndo(),
    canRedo: !!h.peekRedo(),
    undoLabel: describeEntry(h.peekUndo()),
    redoLabel: describeEntry(h.peekRedo()),
  });
}

function applyViews(views) {
  state.views = { ...state.views, ...views };
  const v = state.views, viewer = state.viewer;
  viewer.arrows.setOptions({ visible: v.arrows, density: v.arrowDensity, scaled: v.arrowsScaled });
  viewer.setColorMap(v.colorMap);
  viewer.singularities.setVisible(v.singularities);
  if (state.field) {
    state.ui.setLegend(v.colorMap ? viewer.vertexFieldMax : null);
    scheduleStreamlines();
  }
  viewer.requestRender();
}

// After every completed edit: redraw, and keep the autosave in step with the core.
function afterEdit() {
  adoptUnmapped();
  refresh();
  saveAutosave(state.modelKey, state.design);
}

// ------------------------------------------------------------------------------------------ models

async function loadModel(src, opts = {}) {
  state.loadsPending++;
  return exclusive(async () => {
    let model;
    try {
      model = await readModel(src, opts);
    } catch (err) {
      throw new Error(`Could not load model: ${err.message}`);
    }
    const key = modelKey(model.name, model.bytes);
    const saved = opts.restore === false ? null : loadAutosave(key);
    const bytes = model.bytes.slice(); // its own buffer, transferred to the worker
    const source = { bytes: model.bytes, format: model.format };
    let reply;
    try {
      reply = await call('loadMesh', [bytes, model.format, settings(), saved?.design ?? null], [bytes.buffer]);
    } catch (err) {
      // The core kept its previous mesh and everything on it.
      if (state.info) refresh();
      throw new Error(`Could not load ${model.name}: ${err.message.replace(/^load: /, '')}`);
    }
    const tApply = performance.now();
    const { info, settingsError, restoreError } = reply.value;
    const { positions, triangles, edges } = reply.mesh;
    state.surface = new Surface(positions, triangles, edges);
    state.info = info;
    state.modelName = model.name;
    state.modelKey = key;
    state.modelSource = source;
    state.selected = null;
    state.streamlineCache = null;
    mapDocument(null);
    state.history.clear();
    state.viewer.setMesh(state.surface);
    // Texture synthesis: the model's UVs (6 per face, or none) and a fresh atlas for the new mesh.
    state.cornerUVs = reply.mesh.cornerUVs?.length ? reply.mesh.cornerUVs : null;
    state.meshSerial = (state.meshSerial ?? 0) + 1;
    state.synthesis?.modelChanged();
    state.ui.setHasBoundary(info.boundaryLoops > 0);
    // On a large mesh "one arrow per face" becomes a sparser default; a density the user chose stays.
    if (state.densityAuto || state.views.arrowDensity === 10) {
      const level = state.surface.nF > MAX_DEFAULT_ARROWS ? arrowDensityFor(state.surface, MAX_DEFAULT_ARROWS) : 10;
      state.densityAuto = level !== 10;
      if (level !== state.views.arrowDensity) {
        state.ui.setViews({ arrowDensity: level });
        applyViews(state.ui.views());
      }
    }
    refresh();
    // Main-thread cost of taking a new mesh on (adjacency, BVH, buffers, first draw): the one pause left.
    state.perf.meshSetupMs = performance.now() - tApply;
    if (restoreError) state.ui.flash(`The autosaved design could not be restored: ${restoreError}`, 6000);
    else if (saved?.design && state.constraints.size) {
      state.ui.flash(`Restored the autosaved design (${state.constraints.size} constraints).`);
    }
    if (settingsError) state.ui.showError(`The boundary/γ settings did not apply to ${model.name}: ${settingsError}`);
    return structuredClone(info);
  }).finally(() => state.loadsPending--);
}

// ------------------------------------------------------------------------------------------ supervision
// The proxy replaced a dead, trapped or cancelled worker: the current model and design go to the new one,
// the page's constraint ids are mapped onto the new core ids (history stays valid), and the user is told.
async function reviveCore({ kind, detail, call: send }) {
  const t0 = performance.now();
  if (!state.modelSource) return;
  const uids = uidsInCoreOrder();
  const bytes = state.modelSource.bytes.slice();
  const reply = await send('loadMesh', [bytes, state.modelSource.format, settings(), state.design], [bytes.buffer]);
  state.arrowsAhead = false;
  applySnapshot(reply.snapshot);
  mapDocument(uids);
  refresh();
  state.perf.lastRestart = { kind, detail, restoreMs: performance.now() - t0, constraints: state.constraints.size };
  state.ui.flash(
    kind === 'cancelled'
      ? 'Cancelled. The design is as it was before.'
      : `The core stopped (${detail}) and was restarted; your model and design are back.`,
    6000,
  );
}

// Tool input is bound to the model it was made on: while a load is pending it is refused, and an edit that
// reaches the core after the model changed is dropped rather than applied to the new model.
function boundToModel(flash) {
  if (state.loadsPending > 0) {
    flash('A model is loading: the edit was not applied.', 3000);
    return null;
  }
  return state.meshSerial;
}

// ------------------------------------------------------------------------------------------ edits

// Number(null), Number('') and Number(false) are 0: a missing value must not become face 0 or weight 0.
function numeric(x) {
  return x === null || x === undefined || x === '' || typeof x === 'boolean' ? NaN : Number(x);
}

function finite(x, what) {
  const v = numeric(x);
  if (!Number.isFinite(v)) throw new Error(`${what} must be a finite number (got ${x})`);
  return v;
}

function index(x, what, count) {
  const v = numeric(x);
  if (!Number.isInteger(v) || v < 0 || v >= count) throw new Error(`${what} ${x} is out of range (0…${count - 1})`);
  return v;
}

function validatePoints(points) {
  if (!Array.isArray(points) || points.length < 2) throw new Error('a stroke needs at least 2 points');
  const nF = state.info.faces;
  return points.map((p, k) => {
    const face = numeric(p?.face);
    const bary = Array.from(p?.bary ?? [], numeric);
    if (!Number.isInteger(face) || face < 0 || face >= nF) throw new Error(`stroke point ${k}: face ${p?.face} out of range`);
    if (bary.length !== 3 || !bary.every(Number.isFinite)) throw new Error(`stroke point ${k}: bary must be 3 finite numbers`);
    return { face, bary };
  });
}

function vec3(v, what) {
  const a = Array.from(v ?? [], numeric);
  if (a.length !== 3 || !a.every(Number.isFinite)) throw new Error(`${what} must be 3 finite numbers`);
  return a;
}

// Adds one constraint (design-format spec) and records it; resolves with its page id.
function addConstraint(makeSpec, meshSerial = undefined) {
  return exclusive(async () => {
    requireReady();
    if (meshSerial !== undefined && meshSerial !== state.meshSerial)
      throw new Error('the model changed before this edit reached the core; it was not applied');
    const spec = makeSpec();
    const reply = await call('add', [spec]);
    const uid = state.nextUid++;
    state.constraints.set(uid, reply.value);
    state.history.push({ kind: 'add', uid, spec: structuredClone(specOf(uid)) });
    afterEdit();
    return uid;
  });
}

const faceIndex = (f) => index(f, 'face', state.info.faces);
const vertexIndex = (v) => index(v, 'vertex', state.info.vertices);

const addStroke = (points, { strength = 1, weight = DEFAULT_WEIGHT, meshSerial } = {}) =>
  addConstraint(() => ({
    type: 'stroke',
    points: validatePoints(points),
    strength: finite(strength, 'strength'),
    weight: finite(weight, 'weight'),
  }), meshSerial);
const addVector = (face, vector, { weight = DEFAULT_WEIGHT, meshSerial } = {}) =>
  addConstraint(() => ({ type: 'vector', face: faceIndex(face), vector: vec3(vector, 'vector'), weight: finite(weight, 'weight') }), meshSerial);
const addEdge = (edge, value, { weight = DEFAULT_WEIGHT } = {}) =>
  addConstraint(() => {
    const [i, j] = Array.from(edge ?? [], numeric);
    return { type: 'edge', edge: [vertexIndex(i), vertexIndex(j)], value: finite(value, 'value'), weight: finite(weight, 'weight') };
  });
const addPoint = (type, vertex, strength, meshSerial) =>
  addConstraint(() => ({ type, vertex: vertexIndex(vertex), strength: finite(strength, 'strength') }), meshSerial);
const addSource = (vertex, { strength = 1 } = {}) => addPoint('source', vertex, strength);
const addSink = (vertex, { strength = 1 } = {}) => addPoint('sink', vertex, strength);
const addVortex = (face, { strength = 1, meshSerial } = {}) =>
  addConstraint(() => ({ type: 'vortex', face: faceIndex(face), strength: finite(strength, 'strength') }), meshSerial);

function remove(uid) {
  return exclusive(async () => {
    requireReady();
    const spec = structuredClone(specOf(uid));
    await call('remove', [coreIdOf(uid)]);
    state.constraints.delete(Number(uid));
    state.history.push({ kind: 'remove', uid: Number(uid), spec });
    afterEdit();
    return true;
  });
}

// Weight and strength changes are recorded with the value they replace.
function setParameter(kind, uid, value) {
  return exclusive(async () => {
    requireReady();
    const v = finite(value, kind);
    const from = specOf(uid)[kind];
    if (from === undefined) throw new Error(`a ${specOf(uid).type} has no ${kind}`);
    await call(kind === 'weight' ? 'setWeight' : 'setStrength', [coreIdOf(uid), v]);
    if (from !== v) state.history.push({ kind, uid: Number(uid), from, to: v });
    afterEdit();
    return true;
  });
}

function normaliseBoundary(bc) {
  if (typeof bc === 'string') return bc;
  if (bc && typeof bc === 'object') return structuredClone(bc);
  throw new Error(`boundary must be 'free', 'tangential', 'normal' or {angle} (got ${JSON.stringify(bc)})`);
}

function setBoundary(bc) {
  return exclusive(async () => {
    requireReady();
    const to = normaliseBoundary(bc);
    const from = structuredClone(settings().boundary);
    try {
      await call('setBoundary', [to]);
    } finally {
      state.ui.setSettings(settings()); // shows what the core holds, also after a refusal
    }
    state.history.push({ kind: 'boundary', from, to: structuredClone(settings().boundary) });
    afterEdit();
  });
}

function setGamma(gamma) {
  return exclusive(async () => {
    requireReady();
    if (!(Number.isFinite(gamma) && gamma >= 0)) {
      state.ui.setSettings(settings());
      throw new Error(`gamma must be a number ≥ 0 (got ${gamma})`);
    }
    const from = settings().gamma;
    try {
      await call('setGamma', [gamma]);
    } finally {
      state.ui.setSettings(settings());
    }
    state.history.push({ kind: 'gamma', from, to: gamma });
    afterEdit();
  });
}

// Replaces the whole design (boundary, γ, constraints) with a document, as `tvf design` would read it.
function replaceDesign(design, label) {
  return exclusive(async () => {
    requireReady();
    if (!design || typeof design !== 'object' || Array.isArray(design)) throw new Error('a design must be a JSON object');
    const before = { design: structuredClone(state.design), uids: uidsInCoreOrder() };
    try {
      await call('applyDesign', [design]);
    } catch (err) {
      mapDocument(before.uids); // the core put the previous design back, under fresh core ids
      refresh();
      throw err;
    }
    mapDocument(null);
    state.selected = null;
    const after = { design: structuredClone(state.design), uids: uidsInCoreOrder() };
    state.history.push({ kind: 'design', label, before, after });
    afterEdit();
  });
}

const loadDesign = (design) => replaceDesign(design, 'load design');
const clearConstraints = () => replaceDesign({ ...settings(), constraints: [] }, 'clear');

// ------------------------------------------------------------------------------------------ undo / redo

// Applies one history entry forwards (redo) or backwards (undo) as the inverse factor update.
async function replay(entry, forward) {
  switch (entry.kind) {
    case 'add':
    case 'remove': {
      const present = (entry.kind === 'add') === forward;
      if (present) {
        const reply = await call('readd', [entry.spec]);
        state.constraints.set(entry.uid, reply.value);
      } else {
        await call('remove', [coreIdOf(entry.uid)]);
        state.constraints.delete(entry.uid);
      }
      return;
    }
    case 'weight':
      return void (await call('setWeight', [coreIdOf(entry.uid), forward ? entry.to : entry.from]));
    case 'strength':
      return void (await call('setStrength', [coreIdOf(entry.uid), forward ? entry.to : entry.from]));
    case 'boundary':
      return void (await call('setBoundary', [forward ? entry.to : entry.from]));
    case 'gamma':
      return void (await call('setGamma', [forward ? entry.to : entry.from]));
    case 'design': {
      const target = forward ? entry.after : entry.before;
      const other = forward ? entry.before : entry.after;
      try {
        await call('applyDesign', [target.design]);
      } catch (err) {
        mapDocument(other.uids);
        throw err;
      }
      mapDocument(target.uids);
      return;
    }
    default:
      throw new Error(`cannot replay ${entry.kind}`);
  }
}

function step(forward) {
  return exclusive(async () => {
    requireReady();
    const h = state.history;
    const entry = forward ? h.peekRedo() : h.peekUndo();
    if (!entry) return false;
    try {
      await replay(entry, forward);
    } finally {
      if (state.selected != null && !state.constraints.has(state.selected)) state.selected = null;
    }
    if (forward) h.didRedo();
    else h.didUndo();
    afterEdit();
    return true;
  });
}

// ------------------------------------------------------------------------------------------ exports

function exportField() {
  return exclusive(async () => {
    requireReady();
    return (await call('fieldJson')).value;
  });
}

function saveDesignFile() {
  requireReady();
  downloadJson(`${baseName(state.modelName)}.design.json`, JSON.stringify(state.design, null, 1));
}

async function exportFieldFile() {
  const text = await exportField();
  downloadJson(`${baseName(state.modelName)}.field.json`, text);
}

// ------------------------------------------------------------------------------------------ UI wiring

// Surfaces any failure of a UI-started action in the banner; the API variants reject instead. The panels
// are redrawn from the state so an input the core refused shows the value in force again.
function report(promise) {
  return promise.catch((err) => {
    state.ui.showError(err.message);
    if (state.field && state.surface) refresh();
  });
}

// Time from a user action to the frame that shows its result (reported through tvf.perf()).
async function timed(name, t0, promise) {
  const result = await promise;
  // refresh() has drawn synchronously; the next animation frame puts it on screen.
  const shown = await new Promise((resolve) => requestAnimationFrame(() => resolve(performance.now())));
  const op = state.perf.lastOp ?? {};
  const arrowsShown = await state.earlyFrame;
  state.perf[name] = {
    arrowsOnScreenMs: arrowsShown ? arrowsShown - t0 : undefined,
    toFrameMs: shown - t0,
    workerMs: op.workerMs,
    workerParts: op.workerParts,
    roundTripMs: op.roundTripMs,
    refresh: state.perf.refresh,
  };
  return result;
}

function select(uid) {
  state.selected = uid != null && state.constraints.has(Number(uid)) ? Number(uid) : null;
  state.viewer.handles.setSelected(state.selected);
  state.ui.setConstraints(constraintList(), state.selected);
  state.viewer.requestRender();
}

function toolActions() {
  const { ui, viewer } = state;
  return {
    flash: (text, ms) => ui.flash(text, ms),
    onStroke: (points) => {
      const t0 = performance.now();
      const meshSerial = boundToModel(ui.flash);
      if (meshSerial === null) return void viewer.clearStroke();
      const { strength, weight } = ui.toolOptions();
      report(timed('stroke', t0, addStroke(points, { strength, weight, meshSerial }))).finally(() => {
        if (!state.tools.tools.stroke.drawing) viewer.clearStroke();
      });
    },
    onVector: (face, vector) => {
      const t0 = performance.now();
      const meshSerial = boundToModel(ui.flash);
      if (meshSerial === null) return;
      report(timed('vector', t0, addVector(face, vector, { weight: ui.toolOptions().weight, meshSerial })));
    },
    onPlace: (kind, hit) => {
      const t0 = performance.now();
      const meshSerial = boundToModel(ui.flash);
      if (meshSerial === null) return;
      const { strength, orientation } = ui.toolOptions();
      const op =
        kind === 'vortex'
          ? addVortex(hit.face, { strength: orientation === 'cw' ? -strength : strength, meshSerial })
          : addPoint(kind, state.surface.nearestCorner(hit.face, hit.point), strength, meshSerial);
      report(timed(kind, t0, op));
    },
    onSelect: select,
  };
}

function uiActions() {
  return {
    accept: ACCEPT,
    onOpen: (file, companions) => report(loadModel(file, { companions })),
    onLoadDesign: (file) => report(readJsonFile(file).then((design) => loadDesign(design))),
    onSaveDesign: () => {
      try {
        saveDesignFile();
      } catch (err) {
        state.ui.showError(err.message);
      }
    },
    onExportField: () => report(exportFieldFile()),
    onTool: (tool) => state.tools?.setTool(tool),
    onUndo: () => report(timed('undo', performance.now(), step(false))),
    onRedo: () => report(timed('redo', performance.now(), step(true))),
    onBoundary: (bc) => report(setBoundary(bc)),
    onGamma: (g) => report(setGamma(g)),
    onViews: (views) => {
      if (views.arrowDensity !== state.views.arrowDensity) state.densityAuto = false;
      applyViews(views);
    },
    onSelect: select,
    onRemove: (uid) => report(timed('delete', performance.now(), remove(uid))),
    onEditWeight: (uid, w) => report(setParameter('weight', uid, w)),
    onEditStrength: (uid, s) => report(setParameter('strength', uid, s)),
    onClear: () => state.constraints.size && report(clearConstraints()),
    onCancel: () => state.proxy?.cancel(),
  };
}

// ------------------------------------------------------------------------------------------ window.tvf

const read = (fn) => () => (requireReady(), fn());

const tvf = {
  ready: null,
  DEFAULT_WEIGHT,
  loadModel: (src, opts) => loadModel(src, opts),
  info: read(() => structuredClone(state.info)),
  mesh: read(() => ({ positions: state.surface.positions.slice(), triangles: state.surface.triangles.slice() })),
  edges: read(() => state.surface.edges.slice()),
  addStroke,
  addVector,
  addEdge,
  addSource,
  addSink,
  addVortex,
  remove: (id) => remove(id),
  setWeight: (id, w) => setParameter('weight', id, w),
  setStrength: (id, s) => setParameter('strength', id, s),
  constraints: () => constraintList(),
  setBoundary,
  setGamma,
  settings: () => structuredClone(settings()),
  undo: () => step(false),
  redo: () => step(true),
  history: () => state.history.labels(),
  saveDesign: read(() => structuredClone(state.design)),
  loadDesign,
  exportField: () => exportField().then((text) => JSON.parse(text)),
  faceVectors: read(() => state.field.faceVectors.slice()),
  vertexVectors: read(() => state.field.vertexVectors.slice()),
  oneForm: read(() => state.field.oneForm.slice()),
  singularities: read(() => structuredClone(state.field.singularities)),
  stats: read(() => structuredClone(state.field.stats)),
  select: (id) => select(id),
  selected: () => state.selected,
  views: () => ({ ...state.views }),
  setViews: (views) => {
    state.ui.setViews(views);
    applyViews(state.ui.views());
    return { ...state.views };
  },
  streamlines: read(() => currentStreamlines().map((l) => Array.from(l))),
  perf: () => structuredClone(state.perf),
  projectToScreen: (xyz) => (requireReady(), state.viewer.projectToScreen(Array.from(xyz))),
  // Stops the operation in flight (a huge stroke, a factorization): the core is replaced and the design as it
  // was before that operation comes back. Resolves true when something was cancelled.
  cancel: () => Promise.resolve(state.proxy?.cancel() ?? false),
  supervision: () => ({ restarts: state.proxy?.restarts ?? 0, lastFailure: structuredClone(state.proxy?.lastFailure ?? null) }),
  // What a crash of the core's worker does, on purpose (tests, demonstrations).
  debug: {
    terminateCore: () => state.proxy?.terminateForTest(),
    setFactorMemoryLimit: (bytes) => exclusive(() => state.proxy.call('setFactorMemoryLimit', [bytes])).then(() => true),
  },
  pick: (clientX, clientY) => (requireReady(), state.viewer.pick(clientX, clientY)),
};
window.tvf = tvf;

async function start() {
  const container = document.getElementById('viewport');
  state.viewer = new Viewer(container);
  state.history = new History(() => state.ui && refreshHistory());
  state.ui = bindUi(uiActions());
  state.tools = new ToolController(state.viewer, container, toolActions());
  state.views = state.ui.views();
  applyViews(state.views);
  // ---- texture synthesis (web/synthesis/, docs/texture-synthesis.md): begin
  state.synthesis = setupSynthesis(tvf, {
    baseUrl: BASE,
    viewer: state.viewer,
    panel: document.getElementById('side-panel'),
    onError: (err) => state.ui.showError(err?.message || String(err)),
    getModel: () =>
      state.surface && state.field
        ? { key: `${state.modelKey}#${state.meshSerial}`, name: state.modelName, positions: state.surface.positions, triangles: state.surface.triangles, cornerUVs: state.cornerUVs, vertexVectors: state.field.vertexVectors, fieldVersion: state.fieldVersion }
        : null,
  });
  // ---- texture synthesis: end

  state.proxy = new CoreProxy(new URL('core-worker.js', BASE), {
    onRestart: reviveCore,
    onStatus: (text) => state.ui.flash(text, 4000),
  });
  await state.proxy.call('init');
  await loadModel(new URL(DEFAULT_MODEL, BASE).href);
  // After the first frame, not before: on the small default model warming up costs more than it saves
  // (measured: ~0.3 s to save ~35 ms), but the next, larger model the user opens gets optimized code.
  setTimeout(() => exclusive(() => state.proxy.call('warmUp', [3, 2])).catch(() => {}), 0);
}

tvf.ready = start().catch((err) => {
  const message = err?.message || String(err);
  state.ui?.showError(message);
  throw new Error(message);
});
// The page reports the failure in the banner; keep the console free of an "uncaught" duplicate.
tvf.ready.catch(() => {});
