// Thin wrapper over the embind Designer of the wasm core (dist/wasm/tvf_core.mjs).
// The core reports failures as strings (or -1 plus lastError()); this wrapper turns them into Errors so the
// page has one error path. Views the core returns point into wasm memory and die at the next mutating call
// or memory growth, so everything handed out is a copy (slice(): one memcpy into a buffer of its own, which
// the worker can then transfer).

export class CoreError extends Error {
  constructor(message) {
    super(message);
    this.name = 'CoreError';
  }
}

// A C++ exception or a wasm trap escaping embind arrives as a number or a RuntimeError, neither readable.
function describe(err) {
  if (err instanceof Error) return err.message || String(err);
  if (typeof err === 'number') return 'internal error in the core (uncaught C++ exception)';
  return String(err);
}

// "what: message", unless the core already named the operation itself.
function prefixed(what, message) {
  return message.startsWith(`${what}:`) ? message : `${what}: ${message}`;
}

function guard(what, fn) {
  try {
    return fn();
  } catch (err) {
    throw new CoreError(prefixed(what, describe(err)));
  }
}

// Embind turns null into 0 and a missing number into NaN before the core can see it: arguments are checked
// here, in the core's words, before they cross.
function requireNumber(what, x) {
  if (typeof x !== 'number') {
    const got = x === null ? 'null' : x === undefined ? 'nothing' : typeof x;
    throw new CoreError(`${what} must be a number (got ${got})`);
  }
  return x;
}


// The calls that return an object report a failure as the error message instead.
function checkObject(what, result) {
  if (typeof result === 'string') throw new CoreError(prefixed(what, result || 'rejected by the core'));
  return result;
}

function check(what, result) {
  if (typeof result === 'string' && result !== '') throw new CoreError(prefixed(what, result));
  return result;
}

// The core with a helper thread for each solve's backward substitution (tvf_core_threads.mjs) needs shared
// memory, which a page has only when it is cross-origin isolated (COOP/COEP, as `npm start` serves the app);
// any other page, and an isolated one where the threaded core fails to start (its worker script on another
// origin, say), runs the plain core: the same results, bit for bit, one thread.
export async function loadCore(baseUrl) {
  if (globalThis.crossOriginIsolated === true && typeof SharedArrayBuffer === 'function') {
    try {
      return await loadModule(baseUrl, 'tvf_core_threads');
    } catch (err) {
      const fallback = await loadModule(baseUrl, 'tvf_core');
      fallback.threadsUnavailable = describe(err);
      return fallback;
    }
  }
  return loadModule(baseUrl, 'tvf_core');
}

async function loadModule(baseUrl, name) {
  const moduleUrl = new URL(`wasm/${name}.mjs`, baseUrl).href;
  let factory;
  try {
    // A computed specifier keeps the bundler from trying to inline the emscripten module.
    factory = (await import(moduleUrl)).default;
  } catch (err) {
    throw new CoreError(
      `could not load the field-design core from ${moduleUrl} (${describe(err)}); ` +
        'build it with `npm run build:wasm && npm run build:web`',
    );
  }
  const Module = await factory({ locateFile: (path) => new URL(path, moduleUrl).href });
  return new CoreClient(Module);
}

const sliceOf = (view) => view.slice();

export class CoreClient {
  constructor(Module) {
    this.Module = Module;
    this.threadsUnavailable = null; // why an isolated page runs the plain core, if it does
    this.designer = new Module.Designer();
    this.hasMesh = false;
  }

  // V8 first runs wasm on its baseline tier (2-3x slower); the core's warmUp() exercises the factor/update/solve
  // paths on a small sphere so the user's first real factorization runs optimized code. Returns ms, or -1.
  warmUp(levels = 3, rounds = 2) {
    try {
      return this.Module.warmUp(levels, rounds);
    } catch {
      return -1; // an optimization only: never fail start-up over it
    }
  }

  // bytes: Uint8Array; format: 'glb' | 'gltf' | 'obj' | 'off' | 'ply' | '' (sniff). On failure the core
  // keeps its previous mesh and this throws with the core's message.
  loadMesh(bytes, format) {
    check('load', guard('load', () => this.designer.loadMesh(bytes, format)));
    this.hasMesh = true;
  }

  // The whole model change at once (mesh, settings {boundary, gamma, symmetry, curvatureAlignment}, an autosaved
  // design or null), factored and solved before it replaces the current model; on any failure the current model
  // stays as it was.
  // Returns {settingsError, restoreError} (null or the reason that part was dropped).
  loadModel(bytes, format, settings = null, design = null) {
    const settingsJson = settings ? JSON.stringify(settings) : '';
    const designJson = design ? JSON.stringify(design) : '';
    const out = JSON.parse(guard('load', () => this.designer.loadModel(bytes, format, settingsJson, designJson)));
    if (!out.ok) throw new CoreError(prefixed('load', out.error));
    this.hasMesh = true;
    return { settingsError: out.settingsError, restoreError: out.restoreError };
  }

  // loadModel in steps (worker/load-ops.js, open-steps.js; big meshes): readModel parses the file ({vertices,
  // faces}) and parsedMesh copies its positions and triangles, so that a preview can start on them; openParsed
  // checks and configures it as the next model, aside ({settingsError, restoreError}); pendingInfo/pendingMesh/
  // pendingDesign read it; commitModel factors, solves and makes it current ({restoreError}: a design the solve
  // could not take). Any failure leaves the current model as it was.
  readModel(bytes, format) {
    const out = JSON.parse(guard('load', () => this.designer.readModel(bytes, format)));
    if (!out.ok) throw new CoreError(prefixed('load', out.error));
    return { vertices: out.vertices, faces: out.faces };
  }

  parsedMesh() {
    return { positions: this.designer.parsedPositions().slice(), triangles: this.designer.parsedTriangles().slice() };
  }

  openParsed(settings = null, design = null) {
    const settingsJson = settings ? JSON.stringify(settings) : '';
    const designJson = design ? JSON.stringify(design) : '';
    const out = JSON.parse(guard('load', () => this.designer.openParsed(settingsJson, designJson)));
    if (!out.ok) throw new CoreError(prefixed('load', out.error));
    return { settingsError: out.settingsError, restoreError: out.restoreError };
  }

  commitModel() {
    const out = JSON.parse(guard('load', () => this.designer.commitModel()));
    if (!out.ok) throw new CoreError(prefixed('load', out.error));
    this.hasMesh = true;
    return { restoreError: out.restoreError };
  }

  pendingInfo() {
    return JSON.parse(guard('info', () => this.designer.pendingInfoJson()));
  }

  pendingDesign() {
    return JSON.parse(guard('design', () => this.designer.pendingDesignJson()));
  }

  // Copies (transferable) of the opened model's welded mesh.
  pendingMesh() {
    const d = this.designer;
    return {
      positions: d.pendingPositions().slice(),
      triangles: d.pendingTriangles().slice(),
      edges: d.pendingEdges().slice(),
    };
  }

  // bytes: a fixed limit for the factor's memory; 0: what is left of the wasm address space (default).
  setFactorMemoryLimit(bytes) {
    check('memory limit', guard('memory limit', () => this.designer.setFactorMemoryLimit(bytes)));
  }

  gamma() {
    return guard('gamma', () => this.designer.gamma());
  }

  info() {
    return JSON.parse(guard('info', () => this.designer.infoJson()));
  }

  setBoundary(bc) {
    // 'free' | 'tangential' | 'normal' | {angle}: the core takes the JSON value, quotes included.
    const json = JSON.stringify(bc);
    check('boundary', guard('boundary', () => this.designer.setBoundaryJson(json)));
  }

  setGamma(gamma) {
    requireNumber('gamma', gamma);
    // setGamma returns nothing, or an error string in a stricter build.
    check('gamma', guard('gamma', () => this.designer.setGamma(gamma)));
  }

  symmetry() {
    return guard('symmetry', () => this.designer.symmetry());
  }

  // n: 1 a vector field, 2 a line field, 4 a cross field (the core takes 1..6, and refuses N ≥ 2 while a source,
  // sink, vortex or edge constraint is in the design). Embind would truncate 2.5 to 2 unseen: checked here.
  setSymmetry(n) {
    if (!Number.isInteger(n)) {
      const got = typeof n === 'number' ? String(n) : n == null ? 'nothing' : JSON.stringify(n);
      throw new CoreError(`symmetry must be a whole number from 1 to 6 (got ${got})`);
    }
    check('symmetry', guard('symmetry', () => this.designer.setSymmetry(n)));
  }

  curvatureAlignment() {
    return guard('curvature alignment', () => this.designer.curvatureAlignment());
  }

  // s ≥ 0 (0: off): how strongly the field is pulled towards the principal curvature directions; for even N only.
  setCurvatureAlignment(s) {
    requireNumber('curvature alignment', s);
    check('curvature alignment', guard('curvature alignment', () => this.designer.setCurvatureAlignment(s)));
  }

  factor() {
    check('factor', guard('factor', () => this.designer.factor()));
  }

  solve() {
    check('solve', guard('solve', () => this.designer.solve()));
  }

  // An added constraint's update held beside the factor, the solve applying it (Designer::setDeferredUpdates),
  // until applyDeferredUpdates() puts it into the factor: the worker does that after its reply has gone.
  setDeferredUpdates(defer) {
    check('deferred updates', guard('deferred updates', () => this.designer.setDeferredUpdates(!!defer)));
  }

  applyDeferredUpdates() {
    check('update', guard('update', () => this.designer.applyDeferredUpdates()));
  }

  #id(what, id) {
    if (typeof id !== 'number' || id < 0) {
      const msg = guard(what, () => this.designer.lastError()) || 'rejected by the core';
      throw new CoreError(prefixed(what, msg));
    }
    return id;
  }

  // One constraint in the design format (docs/design-format.md): the only way constraints enter the core,
  // parsed by the same code as design files (new ones, and exact re-adds for undo).
  addConstraintJson(spec) {
    const json = JSON.stringify(spec);
    return this.#id('constraint', guard('constraint', () => this.designer.addConstraintJson(json)));
  }

  // Core ids in the order of designJson().constraints.
  constraintIds() {
    return JSON.parse(guard('constraints', () => this.designer.constraintIdsJson()));
  }

  remove(id) {
    requireNumber('remove: id', id);
    const ok = guard('remove', () => this.designer.remove(id));
    if (!ok) throw new CoreError(prefixed('remove', this.#lastError() || `no constraint with id ${id}`));
  }

  setWeight(id, weight) {
    requireNumber('weight: id', id);
    requireNumber('weight', weight);
    const ok = guard('weight', () => this.designer.setWeight(id, weight));
    if (!ok) throw new CoreError(prefixed('weight', this.#lastError() || `cannot reweight constraint ${id}`));
  }

  setStrength(id, strength) {
    requireNumber('strength: id', id);
    requireNumber('strength', strength);
    const ok = guard('strength', () => this.designer.setStrength(id, strength));
    if (!ok) throw new CoreError(prefixed('strength', this.#lastError() || `cannot change the strength of ${id}`));
  }

  #lastError() {
    try {
      return this.designer.lastError();
    } catch {
      return '';
    }
  }

  mesh() {
    return guard('mesh', () => ({
      positions: this.designer.positions().slice(),
      triangles: this.designer.triangles().slice(),
    }));
  }

  // The field arrays, copied out of the wasm heap by `copy(view)` (a fresh array by default; the worker
  // passes one that refills a spare).
  faceVectors(copy = sliceOf) {
    return guard('faceVectors', () => copy(this.designer.faceVectors()));
  }

  vertexVectors(copy = sliceOf) {
    return guard('vertexVectors', () => copy(this.designer.vertexVectors()));
  }

  oneForm(copy = sliceOf) {
    return guard('oneForm', () => copy(this.designer.oneForm()));
  }

  edges() {
    return guard('edges', () => this.designer.edges().slice());
  }

  fieldJson() {
    return guard('field', () => this.designer.fieldJson());
  }

  // The Hodge decomposition (Eq. 3) of the current field, computed now by the core (two Poisson solves):
  // {exact, coexact, harmonic, metric (Float64Array per edge, oneForm's order), potential0 (per vertex),
  // potential2 (per face), metricName, milliseconds, energyShares: {exact, coexact, harmonic}}; arrays of their own.
  hodge() {
    return checkObject('hodge', guard('hodge', () => this.designer.hodge()));
  }

  // Face and vertex vectors of a 1-form (Float64Array per edge, oneForm's order) by the core's own
  // reconstruction, the one the field's read-outs come from: {faceVectors, vertexVectors}, arrays of their own.
  reconstruct(oneForm) {
    return checkObject('reconstruct', guard('reconstruct', () => this.designer.reconstruct(oneForm)));
  }

  stats() {
    return JSON.parse(guard('stats', () => this.designer.statsJson()));
  }

  singularities() {
    return JSON.parse(guard('singularities', () => this.designer.singularitiesJson()));
  }

  // One constraint in the design format, or null when there is no constraint `id`.
  constraint(id) {
    requireNumber('constraint: id', id);
    return JSON.parse(guard('constraint', () => this.designer.constraintJson(id)));
  }

  designJson() {
    return guard('design', () => this.designer.designJson());
  }

  applyDesignJson(json) {
    check('design', guard('design', () => this.designer.applyDesignJson(json)));
  }
}
