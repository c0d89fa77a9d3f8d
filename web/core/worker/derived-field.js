// What the worker derives from one version of its field, each on first request and kept until the next
// version replaces this object (snapshot.js, after every solve): the magnitude scale sent with the field, the
// streamlines (keyed by their options) and the Hodge parts (field-parts.js). Nothing else in the worker keeps
// derived field data; the mesh's Surface, which the streamlines are traced on, is per mesh (state.js).
// The page keeps its own derived-field object per version on its side of the boundary.
import { magnitudeScale } from '../../geometry/magnitudes.js';
import { traceStreamlines } from '../../geometry/streamlines.js';
import { FieldParts } from '../field-parts.js';

// Traces kept per version: one per part of the Hodge views ('whole', 'exact', 'coexact', 'harmonic'); a fifth
// set of options (a new spacing) pushes out the oldest.
const KEPT_TRACES = 4;

export class DerivedField {
  // version: the field's (0 before the first solve); core(): the worker's CoreClient now; surface(): the mesh's.
  constructor(version, core, surface) {
    this.version = version;
    this.core = core;
    this.surface = surface;
    this.scale = null;
    this.parts = null;
    this.traces = new Map(); // `${spacing} ${lift} ${component}` -> Float32Array polylines
  }

  // The scale of the field's magnitudes (geometry/magnitudes.js), here rather than on the page's thread.
  // vertexVectors: this version's, which the snapshot has in hand.
  magnitudeScale(vertexVectors) {
    this.scale ??= magnitudeScale(vertexVectors);
    return this.scale;
  }

  // The Hodge decomposition and its parts' vectors.
  hodge() {
    this.parts ??= new FieldParts(this.core());
    return this.parts;
  }

  // The streamlines at these options (geometry/streamlines.js): the kept polylines themselves, which the
  // caller copies before handing them over. component: 'whole' (the field) or a Hodge part, whose vertex
  // vectors are traced instead.
  streamlines(spacing, lift, component) {
    const key = `${spacing} ${lift} ${component}`;
    let lines = this.traces.get(key);
    if (!lines) {
      const core = this.core();
      const field = component === 'whole'
        ? { vertexVectors: core.vertexVectors(), faceVectors: core.faceVectors() }
        : this.hodge().component(component);
      // An N-field's corners are matched to its face representatives before they are interpolated.
      const options = { spacing, lift, symmetry: core.symmetry(), faceVectors: field.faceVectors };
      lines = traceStreamlines(this.surface(), field.vertexVectors, options);
      if (this.traces.size >= KEPT_TRACES) this.traces.delete(this.traces.keys().next().value);
      this.traces.set(key, lines);
    }
    return lines;
  }
}
