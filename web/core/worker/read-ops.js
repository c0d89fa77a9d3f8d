// The worker's read-outs of its current field (dispatch.js files them as `onMesh`: no solve, no snapshot).
// The derived ones name the field version they are for and answer null when the field has changed since the
// page asked (it asks again for the new one); each is derived once per version (derived-field.js).
// Imports nothing beyond the worker's own modules.
import { Transfer } from './transfer.js';

export function readOps(state) {
  // The derived data of field `forVersion`, or null when that is no longer the current field.
  const fieldAt = (forVersion) => (forVersion === state.field.version ? state.field : null);

  const onMesh = {
    fieldJson() {
      return state.core.fieldJson();
    },

    // The streamlines of field `forVersion` at `spacing` (geometry/streamlines.js, off the page's thread):
    // Float32Array polylines, transferred. component: 'whole' (the field) or a part of its Hodge decomposition
    // ('exact' | 'coexact' | 'harmonic'; see `component`), whose vertex vectors are traced instead.
    streamlines(forVersion, spacing, lift, component = 'whole') {
      const field = fieldAt(forVersion);
      if (!field) return null;
      // Copies: the kept lines stay with the field version for the next request at the same options.
      const lines = field.streamlines(spacing, lift, component).map((l) => l.slice());
      return new Transfer(lines, lines.map((l) => l.buffer));
    },

    // The Hodge decomposition (Eq. 3) of field `forVersion` (field-parts.js): all of it, transferred; only the
    // shares ({energyShares, decomposeMs}: the Views panel's line); one part ('whole' | 'exact' | 'coexact' |
    // 'harmonic') as {oneForm, faceVectors, vertexVectors}, transferred.
    hodge(forVersion) {
      const field = fieldAt(forVersion);
      return field && Transfer.of(field.hodge().hodgeReply());
    },

    hodgeShares(forVersion) {
      const field = fieldAt(forVersion);
      return field && field.hodge().sharesReply();
    },

    component(forVersion, name) {
      const field = fieldAt(forVersion);
      return field && Transfer.of(field.hodge().componentReply(name));
    },

    // What the core itself holds now, each read-out derived by the core (not the page's copies): the tests'
    // reference for the page's lazily derived and incrementally kept read-outs.
    read() {
      const { core } = state;
      const value = {
        version: state.field.version,
        oneForm: core.oneForm(),
        faceVectors: core.faceVectors(),
        vertexVectors: core.vertexVectors(),
        singularities: core.singularities(),
        design: JSON.parse(core.designJson()),
      };
      return new Transfer(value, [value.oneForm.buffer, value.faceVectors.buffer, value.vertexVectors.buffer]);
    },
  };

  return { onMesh };
}
