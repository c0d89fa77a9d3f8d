// The preview worker's warm-up: while the exact worker still reads a big model, the preview worker (started
// beside it, progressive-core.js) runs the whole preview once on a generated torus, so that V8 has compiled the
// simplifier's wasm, the surface map and the core's load, factor, update and solve with its optimizing tier
// when the model arrives. Cold, they took about twice as long on the first (and only) preview of the load.
//
// Owned by the preview worker (worker/preview-ops.js). Imports preview.js.
import { Preview } from './preview.js';

// A torus of nu × nv quads, each split in two: {positions (Float64Array), triangles, edges (Int32Array, lower
// vertex first)}. Closed and of genus 1, as good a test of the pipeline as a scan.
export function torus(nu, nv, R = 1, r = 0.4) {
  const positions = new Float64Array(3 * nu * nv);
  const id = (i, j) => ((i + nu) % nu) * nv + ((j + nv) % nv);
  for (let i = 0; i < nu; i++) {
    for (let j = 0; j < nv; j++) {
      const u = (2 * Math.PI * i) / nu, v = (2 * Math.PI * j) / nv;
      const point = [(R + r * Math.cos(v)) * Math.cos(u), (R + r * Math.cos(v)) * Math.sin(u), r * Math.sin(v)];
      positions.set(point, 3 * id(i, j));
    }
  }
  const triangles = new Int32Array(6 * nu * nv);
  const edges = new Int32Array(6 * nu * nv);
  for (let i = 0, t = 0, e = 0; i < nu; i++) {
    for (let j = 0; j < nv; j++) {
      const a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      triangles.set([a, b, c, a, c, d], t);
      t += 6;
      for (const w of [b, c, d]) (edges[e++] = Math.min(a, w)), (edges[e++] = Math.max(a, w));
    }
  }
  return { positions, triangles, edges };
}

// Opens a preview of a 25,600-face torus, carries its field to the fine mesh and runs a stroke's cycle on the
// coarse core (its own warm-up). The core is left holding the torus; the model's preview replaces it.
export async function warmUpPreview(core) {
  const { positions, triangles } = torus(160, 80);
  const preview = Preview.open(core, await Preview.prepare({ positions, triangles }), { constraints: [] }, null);
  core.warmUp(3, 1);
  const out = { vertexVectors: new Float64Array(positions.length), faceVectors: new Float64Array(triangles.length) };
  preview.map.fieldOnFine(core.faceVectors(), core.vertexVectors(), 1, out);
}
