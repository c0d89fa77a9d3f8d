// Page entry: ties the wasm core, the three.js view, the stroke tool and the toolbar together, and exposes
// the same operations as window.tvf (docs/js-api.md) for tests and embedding pages.
import { loadCore } from './core-client.js';
import { ACCEPT, readModel } from './model-files.js';
import { StrokeTool } from './stroke-tool.js';
import { Viewer } from './viewer.js';
import { bindUi } from './ui.js';

// Weight 1e4 keeps strokes within ~0.4% of the drawn direction (paper, Sec. 6.1) while the rank-1 updates
// stay well conditioned.
export const DEFAULT_WEIGHT = 1e4;
const DEFAULT_MODEL = 'models/bunny.glb';
const BASE = new URL('./', import.meta.url);

const state = {
  core: null,
  viewer: null,
  ui: null,
  modelName: '',
  info: null,
  constraints: new Map(), // id → {id, type, points, strength, weight}
  // Kept by the page, not only the core: a newly loaded mesh gets a fresh core designer with defaults, and
  // the toolbar still shows the user's choice.
  settings: { boundary: 'free', gamma: 0 },
};

// Core calls are synchronous, but loads await file reads: one queue keeps every mutation whole and ordered.
let queue = Promise.resolve();
function exclusive(fn) {
  const run = queue.then(fn);
  queue = run.catch(() => {});
  return run;
}

function requireReady() {
  if (!state.core || !state.info) throw new Error('tvf is not ready yet; await tvf.ready first');
}

// Lets the status text paint before a long synchronous call; rAF alone would stall in a hidden tab.
function nextPaint() {
  return new Promise((resolve) => {
    const t = setTimeout(resolve, 50);
    requestAnimationFrame(() => setTimeout(() => (clearTimeout(t), resolve()), 0));
  });
}

function refreshField() {
  state.viewer.setField(state.core.faceVectors());
  state.ui.setStatus(state);
}

async function loadModel(src, opts) {
  return exclusive(async () => {
    let model;
    try {
      model = await readModel(src, opts);
    } catch (err) {
      throw new Error(`Could not load model: ${err.message}`);
    }
    state.ui.setBusy(`Loading ${model.name}…`);
    await nextPaint();
    try {
      state.core.loadMesh(model.bytes, model.format);
    } catch (err) {
      // The core kept its previous mesh; the view still shows it, so nothing else to undo.
      state.ui.setBusy(null);
      state.ui.setStatus(state);
      throw new Error(`Could not load ${model.name}: ${err.message.replace(/^load: /, '')}`);
    }
    state.constraints.clear();
    state.modelName = model.name;
    state.info = state.core.info();
    try {
      applySettings();
      state.core.factor();
      state.core.solve();
    } finally {
      const { positions, triangles } = state.core.mesh();
      state.viewer.setMesh(positions, triangles);
      state.ui.setConstraints([...state.constraints.values()]);
      state.ui.setBusy(null);
    }
    refreshField();
    return state.info;
  });
}

function applySettings() {
  const { boundary, gamma } = state.settings;
  try {
    if (boundary !== 'free') state.core.setBoundary(boundary);
    if (gamma !== 0) state.core.setGamma(gamma);
  } catch (err) {
    state.settings = { boundary: 'free', gamma: 0 };
    state.ui.setSettings(state.settings);
    throw err;
  }
}

function validatePoints(points) {
  if (!Array.isArray(points) || points.length < 2) throw new Error('a stroke needs at least 2 points');
  const nF = state.info.faces;
  return points.map((p, k) => {
    const face = Number(p?.face);
    const bary = Array.from(p?.bary ?? [], Number);
    if (!Number.isInteger(face) || face < 0 || face >= nF) throw new Error(`stroke point ${k}: face ${p?.face} out of range`);
    if (bary.length !== 3 || !bary.every(Number.isFinite)) throw new Error(`stroke point ${k}: bary must be 3 finite numbers`);
    return { face, bary };
  });
}

function addStroke(points, { strength = 1, weight = DEFAULT_WEIGHT } = {}) {
  return exclusive(() => {
    requireReady();
    const pts = validatePoints(points);
    const id = state.core.addStroke(pts, strength, weight);
    state.constraints.set(id, { id, type: 'stroke', points: pts, strength, weight });
    try {
      state.core.solve();
    } finally {
      state.ui.setConstraints([...state.constraints.values()]);
      refreshField();
    }
    return id;
  });
}

function remove(id) {
  return exclusive(() => {
    requireReady();
    state.core.remove(id);
    state.constraints.delete(id);
    try {
      state.core.solve();
    } finally {
      state.ui.setConstraints([...state.constraints.values()]);
      refreshField();
    }
    return true;
  });
}

function setWeight(id, weight) {
  return exclusive(() => {
    requireReady();
    state.core.setWeight(id, weight);
    const c = state.constraints.get(id);
    if (c) c.weight = weight;
    try {
      state.core.solve();
    } finally {
      state.ui.setConstraints([...state.constraints.values()]);
      refreshField();
    }
    return true;
  });
}

function refactor(change) {
  return exclusive(async () => {
    requireReady();
    try {
      change();
    } finally {
      state.ui.setSettings(state.settings); // shows what the core holds, also after a refusal
    }
    state.ui.setBusy('Factoring…');
    await nextPaint();
    try {
      state.core.factor();
      state.core.solve();
    } finally {
      state.ui.setBusy(null);
    }
    refreshField();
  });
}

// Surfaces any failure of a UI-started action in the banner; the API variants reject instead.
function report(promise) {
  return promise.catch((err) => {
    state.ui.showError(err.message);
    state.ui.setStatus(state);
  });
}

function copy(obj) {
  return JSON.parse(JSON.stringify(obj));
}

const tvf = {
  ready: null,
  DEFAULT_WEIGHT,
  loadModel: (src, opts) => loadModel(src, opts),
  info: () => (requireReady(), copy(state.info)),
  addStroke,
  remove,
  setWeight,
  setBoundary: (bc) =>
    refactor(() => {
      state.core.setBoundary(bc);
      state.settings.boundary = copy(bc);
    }),
  setGamma: (gamma) =>
    refactor(() => {
      if (!(Number.isFinite(gamma) && gamma >= 0)) throw new Error(`gamma must be a number ≥ 0 (got ${gamma})`);
      state.core.setGamma(gamma);
      state.settings.gamma = gamma;
    }),
  settings: () => copy(state.settings),
  faceVectors: () => (requireReady(), state.core.faceVectors()),
  stats: () => (requireReady(), state.core.stats()),
  mesh: () => (requireReady(), state.core.mesh()),
  constraints: () => [...state.constraints.values()].map(copy),
  singularities: () => (requireReady(), state.core.singularities()),
  projectToScreen: (xyz) => (requireReady(), state.viewer.projectToScreen(Array.from(xyz))),
  pick: (clientX, clientY) => (requireReady(), state.viewer.pick(clientX, clientY)),
};
window.tvf = tvf;

async function start() {
  const container = document.getElementById('viewport');
  state.viewer = new Viewer(container);
  state.ui = bindUi({
    accept: ACCEPT,
    onOpen: (file, companions) => report(loadModel(file, { companions })),
    onTool: (tool) => strokeTool.setActive(tool === 'stroke'),
    onRemove: (id) => report(remove(id)),
    onBoundary: (bc) => report(tvf.setBoundary(bc)),
    onGamma: (g) => report(tvf.setGamma(g)),
    onArrows: (visible) => state.viewer.setArrowsVisible(visible),
  });
  const strokeTool = new StrokeTool(
    state.viewer,
    container,
    (points) => report(addStroke(points, state.ui.strokeOptions())),
    () => state.ui.flash('Stroke too short: drag across the surface.'),
  );

  state.ui.setBusy('Loading core…');
  state.core = await loadCore(BASE);
  await loadModel(new URL(DEFAULT_MODEL, BASE).href);
  // After the first frame, not before: on the small default model warming up costs more than it saves
  // (measured: ~0.3 s to save ~35 ms), but the next, larger model the user opens gets optimized code.
  setTimeout(() => exclusive(() => state.core.warmUp(3, 2)), 0);
}

tvf.ready = start().catch((err) => {
  const message = err?.message || String(err);
  state.ui?.setBusy(null);
  state.ui?.showError(message);
  throw new Error(message);
});
// The page reports the failure in the banner; keep the console free of an "uncaught" duplicate.
tvf.ready.catch(() => {});
