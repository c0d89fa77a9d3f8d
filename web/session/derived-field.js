// One field version on the page and everything derived from it, each computed (or asked of the worker) on first
// request and kept here: the face vectors and the one-form of a preview (geometry/vertex-field.js), the magnitude
// scale (geometry/magnitudes.js), the singularities, the parts of the Hodge decomposition c = dα + δβ + h and
// their energy shares (the worker's), and the streamlines of the whole field or of a part. Nothing else on the
// page keeps them: the session holds the current DerivedField (session.field), the views read from it, and a
// new version is a new object, so nothing needs a key. A field outliving its mesh (a failed load puts the
// previous mesh back under it) starts its mesh-bound values over.
//
// Owns one field's arrays and what is derived from them. May import geometry/.
import { magnitudeScale } from '../geometry/magnitudes.js';
import { findSingularities } from '../geometry/singularities.js';
import { traceStreamlines } from '../geometry/streamlines.js';
import { faceVectorsOfVertexField, oneFormOfVertexField } from '../geometry/vertex-field.js';

export class DerivedField {
  #surfaceOf;
  #surface = null; // the mesh the values below were made on
  #scale;
  #singularities = null;
  #parts = new Map(); // component → {value (null until it came), promise}
  #energyShares = null; // {value, promise}
  #streamlines = new Map(); // `${component} ${spacing}` → lines

  // snapshot: the worker's reply ({version (the worker's), symmetry (N: 1 vector, 2 line, 4 cross; for N ≥ 2 the
  // vectors are unit representatives), faceVectors, vertexVectors, oneForm, scale, stats, singularities (the
  // core's, flagged `prescribed`, when the design prescribes some; else null), featureEdges (the feature edges'
  // vertex pairs, flat; absent from a preview)}); a preview's faceVectors (of a vector field) and oneForm are
  // null until required. surfaceOf(): the session's mesh now.
  constructor(snapshot, surfaceOf) {
    const { version, symmetry, faceVectors, vertexVectors, oneForm, scale, stats } = snapshot;
    this.version = version;
    this.symmetry = symmetry;
    // The arrays as the worker sent them (a derived one is put here when made): they go back to the worker
    // when a newer field replaces this one (session.changed).
    this.faceVectors = faceVectors;
    this.vertexVectors = vertexVectors;
    this.oneForm = oneForm;
    this.stats = stats;
    this.featureEdges = snapshot.featureEdges ?? null;
    this.#singularities = snapshot.singularities ?? null;
    this.#scale = scale ?? null;
    this.#surfaceOf = surfaceOf;
  }

  #mesh() {
    const surface = this.#surfaceOf();
    if (surface !== this.#surface) {
      this.#surface = surface;
      this.#parts.clear();
      this.#energyShares = null;
      this.#streamlines.clear();
    }
    return surface;
  }

  // ---- arrays

  requireVertexVectors() {
    return this.vertexVectors;
  }

  // A preview carries its vertex vectors alone (and an N-field's face representatives): these two are derived
  // from them when something reads them.
  requireFaceVectors() {
    this.faceVectors ??= faceVectorsOfVertexField(this.#surfaceOf(), this.vertexVectors);
    return this.faceVectors;
  }

  requireOneForm() {
    this.oneForm ??= oneFormOfVertexField(this.#surfaceOf(), this.vertexVectors, this.symmetry);
    return this.oneForm;
  }

  // One magnitude scale ({max, top}) for the arrows, the surface colours and the legend; the worker makes it
  // with the field, else it is made here.
  requireMagnitudes() {
    this.#scale ??= magnitudeScale(this.vertexVectors);
    return this.#scale;
  }

  // [{vertex, index, prescribed}]: the core's when it sent them (it knows which the design prescribes), else
  // found here ([{vertex, index}]: none prescribed).
  requireSingularities() {
    this.#singularities ??= findSingularities(this.#surfaceOf(), this.requireFaceVectors(), this.symmetry);
    return this.#singularities;
  }

  // ---- the Hodge decomposition, made by the worker

  // The part `name` ('exact' | 'coexact' | 'harmonic': {faceVectors, vertexVectors, oneForm, scale}, in the
  // whole field's magnitude scale, so that the parts compare with it and with each other), or null until it came.
  hodgePart(name) {
    this.#mesh();
    return this.#parts.get(name)?.value ?? null;
  }

  // Asks for the part once (ask(): a promise of the worker's arrays, or of null for a field it no longer
  // holds); resolves with the part, or null. A request that failed or came back empty is asked again next time.
  requireHodgePart(name, ask) {
    this.#mesh();
    const parts = this.#parts;
    if (!parts.has(name)) {
      const entry = { value: null, promise: null };
      entry.promise = this.#kept(ask(), () => parts.delete(name), (v) => {
        const scale = this.requireMagnitudes();
        entry.value = { faceVectors: v.faceVectors, vertexVectors: v.vertexVectors, oneForm: v.oneForm, scale };
        return entry.value;
      });
      parts.set(name, entry);
    }
    return parts.get(name).promise;
  }

  // The energy shares of the three parts ({exact, coexact, harmonic}), or null until they came.
  energyShares() {
    this.#mesh();
    return this.#energyShares?.value ?? null;
  }

  // As requireHodgePart, for ask(): a promise of {energyShares, …}; resolves with what the worker sent.
  requireEnergyShares(ask) {
    this.#mesh();
    if (!this.#energyShares) {
      const entry = { value: null, promise: null };
      entry.promise = this.#kept(ask(), () => (this.#energyShares = null), (v) => {
        entry.value = v.energyShares;
        return v;
      });
      this.#energyShares = entry;
    }
    return this.#energyShares.promise;
  }

  // A worker's reply kept by keep(value) once it came, and forgotten by drop() when it failed or was empty.
  #kept(promise, drop, keep) {
    return promise.then(
      (value) => {
        if (value) return keep(value);
        drop();
        return null;
      },
      (err) => {
        drop();
        throw err;
      },
    );
  }

  // ---- streamlines

  // The lines of the component drawn at `spacing` ({component, spacing}), or null when none were made yet.
  streamlines({ component, spacing }) {
    this.#mesh();
    return this.#streamlines.get(`${component} ${spacing}`) ?? null;
  }

  // Lines the worker traced for this field ({component, spacing}).
  keepStreamlines({ component, spacing }, lines) {
    this.#mesh();
    this.#streamlines.set(`${component} ${spacing}`, lines);
  }

  // The lines of the component at that spacing: those kept, else traced here and kept.
  requireStreamlines(options) {
    const known = this.streamlines(options);
    if (known) return known;
    const lines = this.traceStreamlines(options);
    this.#streamlines.set(`${options.component} ${options.spacing}`, lines);
    return lines;
  }

  // Traces the component on the page now, whatever is kept ({component, spacing, lift}). An N-field's corners are
  // matched to its face representatives before they are interpolated, as in the worker.
  traceStreamlines({ component, spacing, lift }) {
    const arrays = component === 'whole' ? this : this.hodgePart(component);
    const options = { spacing, lift, symmetry: this.symmetry, faceVectors: arrays.faceVectors };
    return traceStreamlines(this.#mesh(), arrays.vertexVectors, options);
  }
}
