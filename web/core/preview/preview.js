// The preview core's side of a big model (docs/architecture.md, "Big meshes"): a second worker serves the same
// core on a coarse stand-in of the mesh (coarse-mesh.js), takes every edit the exact core takes, posed on the
// coarse surface (surface-map.js), and answers with the coarse field carried to the fine mesh, in a few
// milliseconds where the exact solve takes hundreds and the first exact factorization many seconds.
//
// The design stays the fine one: the preview keeps each constraint's fine spec under the core id both cores
// give it (they take the same edits in the same order, so their ids agree; an edit the coarse core refuses
// ends the preview, see progressive-core.js), and replies carry the fine design document, never the coarse one.
//
// Owned by the worker's state (worker/preview-ops.js; one per preview worker). Imports geometry/ for the fine
// surface it hands the page.
import { coarseMesh, offBytes } from './coarse-mesh.js';
import { SurfaceMap } from './surface-map.js';
import { magnitudeScale } from '../../geometry/magnitudes.js';

// The coarse mesh of keptParts(): its vertices are fine ones.
function keptCoarse(fine, { coarseTriangles, fineVertex }) {
  const positions = new Float64Array(3 * fineVertex.length);
  fineVertex.forEach((v, c) => positions.set(fine.positions.subarray(3 * v, 3 * v + 3), 3 * c));
  return { positions, triangles: coarseTriangles, fineVertex };
}

export class Preview {
  // The mesh's part, which needs no design: the coarse stand-in and the map. fine: {positions, triangles} as
  // the exact worker read them (Float64Array, Int32Array); kept: keptParts() of a preview of this very mesh (a
  // model opened again: no simplification, no search), or null. Returns what open() takes.
  static async prepare(fine, kept = null) {
    const t0 = performance.now();
    const coarse = kept ? keptCoarse(fine, kept) : await coarseMesh(fine.positions, fine.triangles);
    const t1 = performance.now();
    const map = new SurfaceMap(fine, coarse, kept);
    const coarseFaces = coarse.triangles.length / 3;
    const timings = { simplifyMs: t1 - t0, mapMs: performance.now() - t1, coarseFaces, kept: !!kept };
    return { coarse, map, timings };
  }

  // What depends on the mesh alone in prepare()'s result, for a later prepare() of the same mesh.
  static keptParts({ coarse, map }) {
    return { coarseTriangles: coarse.triangles, fineVertex: coarse.fineVertex, ...map.kept() };
  }

  // core: the worker's CoreClient; prepared: prepare()'s; fineDoc: the exact core's design document of the
  // model (settings, fingerprint, constraints: normalized fine specs); settings as loadModel's.
  static open(core, { coarse, map, timings }, fineDoc, settings) {
    const t0 = performance.now();
    // The coarse core detects no features (design-on-coarse.js): its settings' angle goes as well.
    const coarseSettings = settings && { ...settings, featureAngle: 0 };
    const { restoreError } = core.loadModel(offBytes(coarse), 'off', coarseSettings, map.designOnCoarse(fineDoc));
    // A constraint the coarse surface cannot take would leave the two cores' ids apart: no preview then.
    if (restoreError) throw new Error(`the preview could not take the design: ${restoreError}`);
    const preview = new Preview(core, map, fineDoc);
    preview.timings = { ...timings, coarseSolveMs: performance.now() - t0 };
    return preview;
  }

  constructor(core, map, fineDoc) {
    this.core = core;
    this.map = map;
    this.template = fineDoc;
    this.version = 0;
    this.fineSpecs = new Map();
    this.#adoptDocument(fineDoc);
  }

  // The fine design's features: its angle (0: none, as a document without one means) and edge edits ({add,
  // remove}), which only the fine document carries; the coarse core runs without features (design-on-coarse.js).
  #adoptFeatures(angle = 0, { add = [], remove = [] } = {}) {
    this.template = { ...this.template, featureAngle: angle, featureEdges: { add, remove } };
    if (!angle) delete this.template.featureAngle;
    if (!add.length && !remove.length) delete this.template.featureEdges;
  }

  // The fine specs of a document the coarse core has just taken whole, under the ids it gave them.
  #adoptDocument(doc) {
    this.#adoptFeatures(doc.featureAngle, doc.featureEdges);
    const ids = this.core.constraintIds();
    const fine = [...doc.constraints, ...(doc.singularities ?? []).map((s) => ({ type: 'singularity', ...s }))];
    this.fineSpecs = new Map(ids.map((id, k) => [id, this.#normal(id, fine[k])]));
  }

  // A fine spec as the exact core keeps it (keys sorted, defaults filled in): the coarse core's own copy of
  // the constraint, which it parsed with the same code, with the fine mesh's location put back.
  #normal(id, fine) {
    const out = { ...this.core.constraint(id) };
    if (fine.type === 'edge') {
      delete out.face;
      delete out.vector;
      Object.assign(out, { type: 'edge', edge: fine.edge, value: fine.value });
    } else for (const key of ['points', 'face', 'vertex']) if (key in fine) out[key] = fine[key];
    return sortedKeys(out);
  }

  // An op's arguments as the coarse core takes them (the ops of worker/edit-ops.js and worker/setting-ops.js).
  argsOnCoarse(op, args) {
    const m = this.map;
    if (op === 'add') return [m.specOnCoarse(args[0])];
    if (op === 'addSingularity') return [this.#vertexOnCoarse(args[0]), args[1]];
    if (op === 'moveSingularity') return [args[0], this.#vertexOnCoarse(args[1])];
    if (op === 'addSingularities') return [args[0].map(([v, k]) => [this.#vertexOnCoarse(v), k])];
    if (op === 'setFeatures') return [{ angle: coarseFeatureAngle(args[0]) }];
    if (op === 'applyDesign') return [m.designOnCoarse(args[0])];
    if (op === 'setSymmetry' && args[1]?.add)
      return [args[0], { ...args[1], add: args[1].add.map((s) => m.specOnCoarse(s)) }];
    return args;
  }

  #vertexOnCoarse(vertex) {
    return this.map.specOnCoarse({ type: 'singularity', vertex }).vertex;
  }

  // After the op succeeded on the coarse core: the fine specs follow.
  afterOp(op, args, result) {
    if (this.#afterTopologyOp(op, args, result)) return;
    if (op === 'add') this.fineSpecs.set(result, this.#normal(result, args[0]));
    else if (op === 'remove') this.fineSpecs.delete(args[0]);
    else if (op === 'setWeight' || op === 'setStrength') {
      const spec = this.fineSpecs.get(args[0]);
      if (spec) this.fineSpecs.set(args[0], this.#normal(args[0], spec));
    } else if (op === 'applyDesign') this.#adoptDocument(args[0]);
    else if (op === 'setSymmetry')
      (args[1]?.add ?? []).forEach((spec, k) => this.fineSpecs.set(result[k], this.#normal(result[k], spec)));
  }

  // The prescribed singularities' and the features' ops; false for any other.
  #afterTopologyOp(op, args, result) {
    const fine = (id, vertex) => this.fineSpecs.set(id, this.#normal(id, { type: 'singularity', vertex }));
    if (op === 'addSingularity') fine(result, args[0]);
    else if (op === 'addSingularities') args[0].forEach(([vertex], k) => fine(result[k], vertex));
    else if (op === 'moveSingularity') fine(args[0], args[1]);
    else if (op === 'removeConstraints') args[0].forEach((id) => this.fineSpecs.delete(id));
    else if (op === 'setFeatures') this.#setFeatures(args[0]);
    else return false;
    return true;
  }

  // A setFeatures op's {angle, add, remove} (any of them; the others keep their values), in the fine design.
  #setFeatures(features = {}) {
    const { featureAngle, featureEdges } = this.template;
    const { angle = featureAngle, add = featureEdges?.add, remove = featureEdges?.remove } = features;
    this.#adoptFeatures(angle, { add, remove });
  }

  // The fine design document: the coarse core's settings, the fine mesh's fingerprint, the fine specs (the
  // prescribed singularities listed apart, as the core writes them). The features are the fine design's, angle
  // and edge edits: the coarse core has none (its mesh has none of those edges, and its decimated creases are
  // not the model's).
  fineDocument(ids) {
    const coarse = JSON.parse(this.core.designJson());
    const specs = ids.map((id) => this.fineSpecs.get(id));
    const singular = specs.filter((spec) => spec.type === 'singularity');
    const doc = { ...coarse, constraints: specs.filter((spec) => spec.type !== 'singularity') };
    for (const key of ['singularities', 'featureAngle', 'featureEdges', 'mesh']) delete doc[key];
    if (singular.length) doc.singularities = singular.map(({ vertex, index }) => ({ vertex, index }));
    for (const key of ['featureAngle', 'featureEdges', 'mesh'])
      if (this.template[key] !== undefined) doc[key] = this.template[key];
    // In the core's key order (the parts are in theirs already).
    return Object.fromEntries(Object.keys(doc).sort().map((key) => [key, doc[key]]));
  }

  // The reply to a mutating op (worker/snapshot.js, in fine terms): the preview field on the fine
  // mesh, the coarse core's stats marked `preview`, the fine specs of the constraints the op set (`changed`:
  // core ids, as worker/snapshot.js takes them; null: the whole fine document). A negative version:
  // the exact worker's read-outs (streamlines, Hodge parts) are never asked for a preview's field. The field
  // goes as its vertex vectors (and an N-field's face representatives, which the views need): the page derives
  // the face vectors and the one-form when read (geometry/vertex-field.js, session.fieldArray).
  snapshot(spares, timing, changed = null) {
    const t0 = performance.now();
    const c = this.core;
    const symmetry = c.symmetry();
    const out = {
      vertexVectors: spares.pop(3 * this.map.nV),
      faceVectors: symmetry > 1 ? spares.pop(3 * this.map.nF) : null,
    };
    const coarseVertexVectors = c.vertexVectors();
    const { faceVectors, vertexVectors } = this.map.fieldOnFine(c.faceVectors(), coarseVertexVectors, symmetry, out);
    // The carried vectors are the coarse ones interpolated and laid into the fine planes: the coarse lengths'
    // scale is theirs to within that, for a tiny fraction of the work.
    const scale = magnitudeScale(coarseVertexVectors);
    const t1 = performance.now();
    timing.transferMs = this.timings.transferMs = t1 - t0;
    const ids = c.constraintIds();
    // Each op's own entries rather than the whole document, which the worker re-read and the page re-applied
    // after every edit, at a cost growing with the design.
    const design = changed
      ? { ids, changed: changed.filter((id) => ids.includes(id)).map((id) => [id, this.fineSpecs.get(id)]) }
      : { ids, document: this.fineDocument(ids), specs: ids.map((id) => this.fineSpecs.get(id)) };
    timing.designMs = performance.now() - t1;
    const stats = {
      ...c.stats(),
      preview: true,
      previewHeapBytes: c.Module.HEAP8.buffer.byteLength,
      previewFaces: this.map.coarse.triangles.length / 3,
      ...this.timings,
    };
    return {
      version: -++this.version,
      symmetry,
      faceVectors,
      vertexVectors,
      oneForm: null,
      scale,
      stats,
      design,
      transfer: faceVectors ? [vertexVectors.buffer, faceVectors.buffer] : [vertexVectors.buffer],
    };
  }
}


// The angle a setFeatures op gives the coarse core: 0 (no features there), or an angle the core refuses (not a
// number of degrees in [0, 180]) as it is, so that the coarse core refuses it by name as the exact one will.
function coarseFeatureAngle(features) {
  const angle = features?.angle ?? 0;
  return typeof angle === 'number' && angle >= 0 && angle <= 180 ? 0 : angle;
}

// JSON values with every object's keys in order, as the core writes them (nlohmann's objects are sorted).
function sortedKeys(value) {
  if (Array.isArray(value)) return value.map(sortedKeys);
  if (value === null || typeof value !== 'object') return value;
  return Object.fromEntries(Object.keys(value).sort().map((key) => [key, sortedKeys(value[key])]));
}
