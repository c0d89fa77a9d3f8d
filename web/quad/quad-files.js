// SPDX-License-Identifier: GPL-2.0-or-later
// The quad mesh as files: OBJ (its polygons as they are, `f a b c d`, 1-based: what modelling tools and quad
// mesh pipelines read) and GLB (glTF 2.0 has no polygons, so a triangulated copy: each quad split along its
// shorter diagonal, with POSITION, NORMAL and 32-bit indices; a minimal file any glTF viewer opens). Written
// here, on the page, from the arrays the core returned: nothing to ask the worker. Imports its own folder.
import { faceCount, triangulate, vertexCount, vertexNormals } from './quad-mesh.js';

const GLB_MAGIC = 0x46546c67; // 'glTF'
const CHUNK_JSON = 0x4e4f534a;
const CHUNK_BIN = 0x004e4942;
const FLOAT = 5126;
const UNSIGNED_INT = 5125;
const ARRAY_BUFFER = 34962;
const ELEMENT_ARRAY_BUFFER = 34963;
const TRIANGLES = 4;

// mesh: {positions, faceStart, faceVertices}; name: a comment line's model name. Coordinates are written in
// full (the shortest text that reads back to the same double), so the OBJ is the core's mesh exactly.
export function quadObj(mesh, { name = 'model' } = {}) {
  const { positions: p, faceStart, faceVertices } = mesh;
  const nV = vertexCount(mesh), nF = faceCount(mesh);
  const lines = [
    `# quad mesh of ${name.replace(/[\r\n]/g, ' ')} from the tangent-field designer`,
    `# ${nV} vertices, ${nF} faces`,
    `o ${name.replace(/\s+/g, '_') || 'quad_mesh'}`,
  ];
  for (let v = 0; v < nV; v++) lines.push(`v ${p[3 * v]} ${p[3 * v + 1]} ${p[3 * v + 2]}`);
  for (let f = 0; f < nF; f++) {
    const corners = [];
    for (let k = faceStart[f]; k < faceStart[f + 1]; k++) corners.push(faceVertices[k] + 1);
    lines.push(`f ${corners.join(' ')}`);
  }
  return `${lines.join('\n')}\n`;
}

const pad4 = (n) => (n + 3) & ~3;

// The GLB's bytes (an ArrayBuffer). POSITION's min and max are of the float32 values the file holds, as glTF
// requires; a vertex no polygon touches (none in a valid quad mesh) gets the normal +z so every normal is unit.
export function quadGlb(mesh, { name = 'quad mesh' } = {}) {
  const nV = vertexCount(mesh);
  const positions = Float32Array.from(mesh.positions);
  const normals = Float32Array.from(vertexNormals(mesh));
  for (let v = 0; v < nV; v++) {
    if (!normals[3 * v] && !normals[3 * v + 1] && !normals[3 * v + 2]) normals[3 * v + 2] = 1;
  }
  const indices = triangulate(mesh);
  const min = [Infinity, Infinity, Infinity], max = [-Infinity, -Infinity, -Infinity];
  for (let v = 0; v < nV; v++)
    for (let c = 0; c < 3; c++) {
      min[c] = Math.min(min[c], positions[3 * v + c]);
      max[c] = Math.max(max[c], positions[3 * v + c]);
    }
  const views = [positions, normals, indices];
  const offsets = [];
  let binLength = 0;
  for (const a of views) {
    offsets.push(binLength);
    binLength += pad4(a.byteLength);
  }
  const doc = {
    asset: { version: '2.0', generator: 'tangent-field designer (quad mesh)' },
    scene: 0,
    scenes: [{ nodes: [0] }],
    nodes: [{ mesh: 0, name }],
    meshes: [
      {
        name,
        primitives: [{ attributes: { POSITION: 0, NORMAL: 1 }, indices: 2, mode: TRIANGLES }],
        extras: { quadFaces: faceCount(mesh) },
      },
    ],
    accessors: [
      { bufferView: 0, componentType: FLOAT, count: nV, type: 'VEC3', min, max },
      { bufferView: 1, componentType: FLOAT, count: nV, type: 'VEC3' },
      { bufferView: 2, componentType: UNSIGNED_INT, count: indices.length, type: 'SCALAR' },
    ],
    bufferViews: views.map((a, k) => ({
      buffer: 0,
      byteOffset: offsets[k],
      byteLength: a.byteLength,
      target: k < 2 ? ARRAY_BUFFER : ELEMENT_ARRAY_BUFFER,
    })),
    buffers: [{ byteLength: binLength }],
  };
  if (nV === 0) {
    // glTF wants count ≥ 1 and min/max for POSITION: an empty mesh is a scene without one.
    delete doc.nodes[0].mesh;
    for (const k of ['meshes', 'accessors', 'bufferViews', 'buffers']) delete doc[k];
  }
  const json = new TextEncoder().encode(JSON.stringify(doc));
  const jsonLength = pad4(json.length), hasBin = nV > 0;
  const total = 12 + 8 + jsonLength + (hasBin ? 8 + binLength : 0);
  const out = new ArrayBuffer(total), bytes = new Uint8Array(out), view = new DataView(out);
  view.setUint32(0, GLB_MAGIC, true);
  view.setUint32(4, 2, true);
  view.setUint32(8, total, true);
  view.setUint32(12, jsonLength, true);
  view.setUint32(16, CHUNK_JSON, true);
  bytes.set(json, 20);
  bytes.fill(0x20, 20 + json.length, 20 + jsonLength); // the JSON chunk is padded with spaces
  if (hasBin) {
    const at = 20 + jsonLength;
    view.setUint32(at, binLength, true);
    view.setUint32(at + 4, CHUNK_BIN, true);
    views.forEach((a, k) => bytes.set(new Uint8Array(a.buffer, a.byteOffset, a.byteLength), at + 8 + offsets[k]));
  }
  return out;
}
