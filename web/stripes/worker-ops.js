// SPDX-License-Identifier: GPL-2.0-or-later
// The stripe pattern's worker op, served by the element's core worker (web/core-worker.js composes it with the
// core's ops; core/worker/dispatch.js files it as `onMesh`): the core's pattern of one field version, laid out
// per corner for the page's non-indexed stripe geometry, so that the page's thread only hands it to the GPU.
// After each edit (dispatch.js afterEdit) it makes the pattern the page will ask for, while the page draws the
// field; a note (`stripesUnfollow`) stops that when the page no longer shows the stripes.
// Imports the core worker's Transfer.
import { Transfer } from '../core/worker/transfer.js';

// The core's arrays (families × 3 per face, family-major; families per face) as two per-corner attributes:
// phase (2 per corner: the first family's phase, the second's or 0) and branch (2 per corner: each family's
// branch index n, the same at the face's three corners).
export function cornerAttributes({ families, cornerPhase, branchIndex }) {
  const nF = branchIndex.length / families;
  const phase = new Float32Array(6 * nF), branch = new Int8Array(6 * nF);
  for (let family = 0; family < families; family++) {
    const p = cornerPhase.subarray(3 * nF * family), b = branchIndex.subarray(nF * family);
    for (let f = 0; f < nF; f++)
      for (let k = 0; k < 3; k++) {
        phase[6 * f + 2 * k + family] = p[3 * f + k];
        branch[6 * f + 2 * k + family] = b[f];
      }
  }
  return { phase, branch };
}

// The pattern of the current field's `component` with `options`, as the page takes it; {zeroField: true} for a
// field that is zero everywhere (a new model's vector field before its first edit, a Hodge part it lacks), which
// has no direction for stripes to follow (its pattern would be one flat colour; core/design/design_stripes.h
// fieldIsZero, by which `tvf export --stripes` refuses it).
function pattern(state, component, options) {
  const t0 = performance.now();
  const part = component && component !== 'whole' ? state.field.hodge().component(component) : null;
  const vectors = part?.vertexVectors ?? null;
  if (!(vectors ?? state.core.vertexVectors((view) => view)).some((x) => x !== 0)) return { zeroField: true };
  const stats = state.core.computeStripes(vectors, options, state.interruption());
  if (!stats) return { interrupted: true };
  const { phase, branch } = cornerAttributes(state.core.stripeArrays());
  const workerMs = performance.now() - t0;
  const value = { families: stats.families, phase, branch, stats: { ...stats, workerMs } };
  return new Transfer(value, [phase.buffer, branch.buffer]);
}

// state: the core worker's (core/worker/state.js).
export function stripeOps(state) {
  // What the page draws, made ahead after each edit: the whole field's stripes with the options of its last
  // request (an edit's local update), until the page says it no longer shows them. ahead: that pattern, until asked.
  let follow = null, ahead = null;
  const keyOf = (component, options) => JSON.stringify([component, options]);
  const onMesh = {
    // The pattern of field `forVersion` (null once that is no longer the current field: the page asks again),
    // of its `component` ('whole' or a Hodge part: the field the views draw), with `options`
    // (core/design/design_stripes.h). Replies {families, phase, branch, stats}, the arrays transferred; or
    // {interrupted: true} when a request the page sent after this one came while it ran (the core's steps told
    // so by state.interruption()): the page asks again once that request is served.
    stripes(forVersion, component, options) {
      if (forVersion !== state.field.version) return null;
      const following = { ...options };
      delete following.localUpdate; // a settling request's whole pattern: the next edit's is a local update again
      follow = component === 'whole' ? { key: keyOf(component, following), mesh: state.meshSerial } : null;
      const made = ahead;
      ahead = null;
      if (made?.version === forVersion && made.mesh === state.meshSerial && made.key === keyOf(component, options)) {
        made.value.value.stats.madeAhead = true;
        return made.value;
      }
      return pattern(state, component, options);
    },
  };
  const notes = {
    // The page no longer shows the stripes (or another model came): none made ahead.
    stripesUnfollow() {
      follow = ahead = null;
    },
  };
  const afterEdit = () => {
    ahead = null;
    if (!follow || follow.mesh !== state.meshSerial || !state.core?.hasMesh) return;
    const [component, options] = JSON.parse(follow.key);
    let value;
    try {
      value = pattern(state, component, options);
    } catch {
      return; // options the edit made wrong (a cross field's one-family profile): the page's own request says so
    }
    if (value instanceof Transfer) ahead = { version: state.field.version, mesh: follow.mesh, key: follow.key, value };
  };
  return { onMesh, notes, afterEdit };
}
