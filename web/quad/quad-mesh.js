// SPDX-License-Identifier: GPL-2.0-or-later
// What the page derives from a quad mesh as the core returns it (core/quad/quad_remesh.h: positions, 3 per
// vertex; polygons in CSR, faceStart and faceVertices, counter-clockwise): its edges, the valence of its
// vertices, normals to lift the wireframe off the surface, and a triangulated copy for the GLB. Pure functions
// of the arrays, no DOM and no three.js, so that the node tests run them as the page does. Imports
// geometry/mesh-geometry.js's normalizeEach3 (the normals' last step).
import { normalizeEach3 } from '../geometry/mesh-geometry.js';

export const faceCount = ({ faceStart }) => Math.max(0, faceStart.length - 1);
export const vertexCount = ({ positions }) => positions.length / 3;

// The mesh's undirected edges, each once, as vertex pairs (lower index first), ordered by (lower, higher): a
// Uint32Array, as WebGL takes an index (the view draws its lines with it as it is).
export function uniqueEdges({ positions, faceStart, faceVertices }) {
  // Keys in one typed array, sorted in place: no Set or per-edge array left to the main thread's collector.
  const nV = positions.length / 3, keys = new Float64Array(faceVertices.length);
  for (let f = 0, at = 0; f + 1 < faceStart.length; f++) {
    const s = faceStart[f], n = faceStart[f + 1] - s;
    for (let k = 0; k < n; k++) {
      const a = faceVertices[s + k], b = faceVertices[s + ((k + 1) % n)];
      keys[at++] = a < b ? a * nV + b : b * nV + a; // exact below 9e7 vertices (nV² < 2^53)
    }
  }
  keys.sort();
  let count = 0;
  for (let k = 0; k < keys.length; k++) if (k === 0 || keys[k] !== keys[k - 1]) count++;
  const out = new Uint32Array(2 * count);
  for (let k = 0, at = 0; k < keys.length; k++) {
    if (k > 0 && keys[k] === keys[k - 1]) continue;
    out[at++] = Math.floor(keys[k] / nV);
    out[at++] = keys[k] % nV;
  }
  return out;
}

// Edges at each vertex: the valence a quad mesh's regular interior vertex has four of.
export function valences(mesh, edges = uniqueEdges(mesh)) {
  const v = new Int32Array(vertexCount(mesh));
  for (let k = 0; k < edges.length; k++) v[edges[k]]++;
  return v;
}

// Per vertex, the sum of its polygons' Newell normals (area-weighted), normalized: the direction the wireframe
// is lifted along. A polygon's Newell normal is its vector area, well defined for a non-planar quad.
export function vertexNormals({ positions: p, faceStart, faceVertices }) {
  const out = new Float64Array(p.length);
  for (let f = 0; f + 1 < faceStart.length; f++) {
    const s = faceStart[f], n = faceStart[f + 1] - s;
    let nx = 0, ny = 0, nz = 0;
    for (let k = 0; k < n; k++) {
      const a = 3 * faceVertices[s + k], b = 3 * faceVertices[s + ((k + 1) % n)];
      nx += (p[a + 1] - p[b + 1]) * (p[a + 2] + p[b + 2]);
      ny += (p[a + 2] - p[b + 2]) * (p[a] + p[b]);
      nz += (p[a] - p[b]) * (p[a + 1] + p[b + 1]);
    }
    for (let k = 0; k < n; k++) {
      const v = 3 * faceVertices[s + k];
      out[v] += nx;
      out[v + 1] += ny;
      out[v + 2] += nz;
    }
  }
  return normalizeEach3(out);
}

// The mean length of the mesh's edges (0 for none).
export function meanEdgeLength(mesh, edges = uniqueEdges(mesh)) {
  const p = mesh.positions;
  let sum = 0;
  for (let k = 0; k < edges.length; k += 2) {
    const a = 3 * edges[k], b = 3 * edges[k + 1];
    sum += Math.hypot(p[a] - p[b], p[a + 1] - p[b + 1], p[a + 2] - p[b + 2]);
  }
  return edges.length ? sum / (edges.length / 2) : 0;
}

const distance2 = (p, a, b) => (p[3 * a] - p[3 * b]) ** 2 + (p[3 * a + 1] - p[3 * b + 1]) ** 2 +
  (p[3 * a + 2] - p[3 * b + 2]) ** 2;

// Triangles (3 vertex indices each, the polygons' orientation kept): a quad split along its shorter diagonal,
// which keeps the two halves closer to the surface it approximates; any other polygon fanned from its first
// corner (the core's extraction leaves few, and they are small).
export function triangulate({ positions, faceStart, faceVertices }) {
  let count = 0;
  for (let f = 0; f + 1 < faceStart.length; f++) count += Math.max(0, faceStart[f + 1] - faceStart[f] - 2);
  const out = new Uint32Array(3 * count);
  let t = 0;
  for (let f = 0; f + 1 < faceStart.length; f++) {
    const s = faceStart[f], n = faceStart[f + 1] - s, c = faceVertices.subarray(s, s + n);
    if (n === 4 && distance2(positions, c[1], c[3]) < distance2(positions, c[0], c[2])) {
      out.set([c[0], c[1], c[3], c[1], c[2], c[3]], t);
      t += 6;
      continue;
    }
    for (let k = 1; k + 1 < n; k++) {
      out.set([c[0], c[k], c[k + 1]], t);
      t += 3;
    }
  }
  return out;
}

// The remesh target the core takes (optionsJson, core/quad/quad_remesh.h QuadRemeshOptions): exactly one of
// {edgeLength: L > 0} or {quads: N, a whole number ≥ 1}. Throws naming what is wrong; `what` prefixes the message.
export function remeshTarget(options, what = 'remesh') {
  if (options === null || typeof options !== 'object') throw new Error(`${what}: options must be an object`);
  const unknown = Object.keys(options).filter((k) => k !== 'edgeLength' && k !== 'quads');
  if (unknown.length) throw new Error(`${what}: unknown option ${unknown.join(', ')} (edgeLength or quads)`);
  const hasLength = options.edgeLength !== undefined, hasQuads = options.quads !== undefined;
  if (hasLength === hasQuads) throw new Error(`${what}: give either edgeLength or quads`);
  if (hasLength) {
    const L = options.edgeLength;
    if (!(typeof L === 'number' && L > 0 && Number.isFinite(L)))
      throw new Error(`${what}: edgeLength must be a positive length in the model's units (got ${L})`);
    return { edgeLength: L };
  }
  const N = options.quads;
  if (!(Number.isInteger(N) && N >= 1)) throw new Error(`${what}: quads must be a whole number ≥ 1 (got ${N})`);
  return { quads: N };
}
