#!/usr/bin/env node
// Writes dist/models/bunny.glb from the npm `bunny` package (the Stanford bunny, low resolution).
// The GLB is written by hand so the page's default model needs no converter and no committed binary.
// Run directly or import { makeDefaultModel } from build-web.mjs.
import { mkdirSync, writeFileSync } from 'node:fs';
import { dirname, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import bunny from 'bunny';

const ROOT = resolve(dirname(fileURLToPath(import.meta.url)), '..');

// The core rejects inconsistently oriented meshes, so check orientation here rather than find out in the
// browser: every directed edge must occur at most once (two faces sharing an edge traverse it oppositely).
// Returns a list of problems; empty means consistent.
function orientationProblems(cells) {
  const seen = new Set();
  const problems = [];
  cells.forEach(([a, b, c], f) => {
    if (a === b || b === c || c === a) problems.push(`face ${f} is degenerate (${a}, ${b}, ${c})`);
    for (const [i, j] of [[a, b], [b, c], [c, a]]) {
      const key = `${i},${j}`;
      if (seen.has(key)) problems.push(`directed edge ${i}->${j} used twice (face ${f})`);
      seen.add(key);
    }
  });
  return problems;
}

// Sum of signed tetrahedron volumes against the origin: positive when normals point outward. On a mesh
// with holes this is still a reliable sign for a mostly closed scan like the bunny.
function signedVolume(positions, cells) {
  let v = 0;
  for (const [a, b, c] of cells) {
    const [px, py, pz] = positions[a];
    const [qx, qy, qz] = positions[b];
    const [rx, ry, rz] = positions[c];
    v += px * (qy * rz - qz * ry) - py * (qx * rz - qz * rx) + pz * (qx * ry - qy * rx);
  }
  return v / 6;
}

// glTF 2.0 binary container: 12-byte header, JSON chunk (space padded), BIN chunk (zero padded).
export function encodeGlb(positions /* Float32Array */, indices /* Uint32Array */, name = 'mesh') {
  const min = [Infinity, Infinity, Infinity];
  const max = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < positions.length; i += 3) {
    for (let k = 0; k < 3; k++) {
      min[k] = Math.min(min[k], positions[i + k]);
      max[k] = Math.max(max[k], positions[i + k]);
    }
  }
  const posBytes = positions.byteLength;
  const idxBytes = indices.byteLength; // both multiples of 4, so the index view starts aligned
  const gltf = {
    asset: { version: '2.0', generator: 'tangent-field-designer make-default-model.mjs' },
    scene: 0,
    scenes: [{ nodes: [0] }],
    nodes: [{ mesh: 0, name }],
    meshes: [{ name, primitives: [{ attributes: { POSITION: 0 }, indices: 1, mode: 4 }] }],
    accessors: [
      { bufferView: 0, componentType: 5126, count: positions.length / 3, type: 'VEC3', min, max },
      { bufferView: 1, componentType: 5125, count: indices.length, type: 'SCALAR' },
    ],
    bufferViews: [
      { buffer: 0, byteOffset: 0, byteLength: posBytes, target: 34962 },
      { buffer: 0, byteOffset: posBytes, byteLength: idxBytes, target: 34963 },
    ],
    buffers: [{ byteLength: posBytes + idxBytes }],
  };
  const pad4 = (n) => (n + 3) & ~3;
  const jsonRaw = Buffer.from(JSON.stringify(gltf), 'utf8');
  const jsonLen = pad4(jsonRaw.length);
  const binLen = pad4(posBytes + idxBytes);
  const total = 12 + 8 + jsonLen + 8 + binLen;
  const out = Buffer.alloc(total, 0);
  out.writeUInt32LE(0x46546c67, 0); // 'glTF'
  out.writeUInt32LE(2, 4);
  out.writeUInt32LE(total, 8);
  out.writeUInt32LE(jsonLen, 12);
  out.writeUInt32LE(0x4e4f534a, 16); // 'JSON'
  jsonRaw.copy(out, 20);
  out.fill(0x20, 20 + jsonRaw.length, 20 + jsonLen);
  let o = 20 + jsonLen;
  out.writeUInt32LE(binLen, o);
  out.writeUInt32LE(0x004e4942, o + 4); // 'BIN\0'
  o += 8;
  Buffer.from(positions.buffer, positions.byteOffset, posBytes).copy(out, o);
  Buffer.from(indices.buffer, indices.byteOffset, idxBytes).copy(out, o + posBytes);
  return out;
}

export function makeDefaultModel(outPath = resolve(ROOT, 'dist/models/bunny.glb')) {
  const { positions, cells } = bunny;
  const problems = orientationProblems(cells);
  if (problems.length) {
    throw new Error(`bunny mesh is not consistently oriented: ${problems.slice(0, 3).join('; ')}`);
  }
  let tris = cells;
  if (signedVolume(positions, cells) < 0) tris = cells.map(([a, b, c]) => [a, c, b]);

  // Centre on the bounding box and scale the longest side to 1, so the camera setup fits every model alike.
  const min = [Infinity, Infinity, Infinity];
  const max = [-Infinity, -Infinity, -Infinity];
  for (const p of positions) {
    for (let k = 0; k < 3; k++) {
      min[k] = Math.min(min[k], p[k]);
      max[k] = Math.max(max[k], p[k]);
    }
  }
  const centre = min.map((m, k) => (m + max[k]) / 2);
  const scale = 1 / Math.max(...max.map((m, k) => m - min[k]));
  const pos = new Float32Array(positions.length * 3);
  positions.forEach((p, i) => {
    for (let k = 0; k < 3; k++) pos[3 * i + k] = (p[k] - centre[k]) * scale;
  });
  const idx = Uint32Array.from(tris.flat());

  mkdirSync(dirname(outPath), { recursive: true });
  const glb = encodeGlb(pos, idx, 'bunny');
  writeFileSync(outPath, glb);
  return { path: outPath, vertices: positions.length, faces: tris.length, bytes: glb.length };
}

if (process.argv[1] && resolve(process.argv[1]) === fileURLToPath(import.meta.url)) {
  const r = makeDefaultModel(process.argv[2] ? resolve(process.argv[2]) : undefined);
  console.log(`wrote ${r.path}: ${r.vertices} vertices, ${r.faces} faces, ${r.bytes} bytes`);
}
