// SPDX-License-Identifier: GPL-2.0-or-later
// The quad remeshing's worker op, composed by web/core-worker.js like every group, but served by a worker of its
// own (run.js starts a second core-worker.js for each remesh): a remesh takes seconds to minutes, and on the
// element's core worker it would hold every edit behind it. Here the core's quadRemesh (wasm/quad_bindings.cpp,
// core/quad/quad_remesh.h) runs on the mesh and cross field the page sends, its stages go to the page as
// `progress` messages, and the polygon mesh comes back with its arrays transferred. Cancelling is the page's
// terminate() of this worker, so the progress callback never says stop. What the wireframe needs (the edges, the
// valences, the vertex normals; quad-mesh.js) is derived here too, off the page's thread (20 ms under node for
// armadillo-sub2's 20,000 quads). Imports the core worker's Transfer and CoreError, and quad-mesh.js.
import { CoreError } from '../core/core-error.js';
import { Transfer } from '../core/worker/transfer.js';
import { uniqueEdges, valences, vertexNormals } from './quad-mesh.js';

// state: the worker's (core/worker/state.js), whose `init` loaded the module.
export function quadOps(state) {
  const anytime = {
    // positions (Float64Array, 3 per vertex), triangles (Int32Array, 3 per face), faceDirections (Float64Array,
    // one unit representative of the cross field per face), options ({edgeLength} | {quads}, plus symmetry).
    // Replies {positions, faceStart, faceVertices, irregular, stats, derived: {edges, valence, normals}}; a refusal
    // rejects with the core's words.
    quadRemesh(positions, triangles, faceDirections, options) {
      const Module = state.core?.Module;
      if (typeof Module?.quadRemesh !== 'function')
        throw new CoreError('this build of the core has no quad remeshing: rebuild it (npm run build:wasm)');
      const progress = (stage, fraction) => {
        state.progress({ stage: String(stage), fraction: Number(fraction) });
        return true;
      };
      const out = Module.quadRemesh(positions, triangles, faceDirections, JSON.stringify(options), progress);
      if (out.error) throw new CoreError(out.error);
      const value = {
        positions: out.positions,
        faceStart: out.faceStart,
        faceVertices: out.faceVertices,
        irregular: out.irregular,
        stats: JSON.parse(out.statsJson),
      };
      const edges = uniqueEdges(value);
      value.derived = { edges, valence: valences(value, edges), normals: vertexNormals(value) };
      const list = ['positions', 'faceStart', 'faceVertices', 'irregular'].map((k) => value[k].buffer);
      list.push(...Object.values(value.derived).map((a) => a.buffer));
      return new Transfer(value, list);
    },
  };
  return { anytime };
}
