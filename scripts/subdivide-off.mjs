#!/usr/bin/env node
// SPDX-License-Identifier: GPL-2.0-or-later
// subdivide-off.mjs IN.off OUT.off [--levels N]: 1-to-4 midpoint subdivision of a triangle mesh in OFF format
// (polygons are fan-triangulated first). Each level multiplies the edge count by about 4 (E' = 2E + 3F).
// Used by scripts/fetch-meshes.sh to make a ~1M-edge benchmark mesh; new vertices are edge midpoints, so the
// surface stays exactly the same piecewise-flat shape.
import { readFileSync, writeFileSync } from 'node:fs';

function readOff(path) {
  const text = readFileSync(path, 'latin1');
  const tokens = text.replace(/#[^\n]*/g, ' ').split(/\s+/).filter(Boolean);
  let k = 0;
  const header = tokens[k++];
  if (!/^[CN]*OFF$/.test(header)) throw new Error(`${path}: not an OFF file (header '${header}')`);
  const nv = Number(tokens[k++]);
  const nf = Number(tokens[k++]);
  k++; // edge count, unused
  const perVertex = header === 'OFF' ? 3 : header.includes('C') ? 7 : 6; // COFF (rgba) / NOFF: ignore extras
  const positions = new Float64Array(3 * nv);
  for (let v = 0; v < nv; ++v) {
    for (let c = 0; c < 3; ++c) positions[3 * v + c] = Number(tokens[k + c]);
    k += perVertex;
  }
  const tris = [];
  for (let f = 0; f < nf; ++f) {
    const n = Number(tokens[k++]);
    const idx = [];
    for (let j = 0; j < n; ++j) idx.push(Number(tokens[k++]));
    for (let j = 1; j + 1 < n; ++j) tris.push(idx[0], idx[j], idx[j + 1]);
    // skip optional per-face colour values up to the next face line: OFF has none in the meshes we use
  }
  return { positions, triangles: Int32Array.from(tris) };
}

function subdivide({ positions, triangles }) {
  const nv = positions.length / 3;
  const nf = triangles.length / 3;
  const mid = new Map();
  const out = [];
  for (let v = 0; v < nv; ++v) out.push(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]);
  let next = nv;
  const midpoint = (a, b) => {
    const key = a < b ? a * nv + b : b * nv + a;
    let m = mid.get(key);
    if (m === undefined) {
      m = next++;
      mid.set(key, m);
      for (let c = 0; c < 3; ++c) out.push(0.5 * (positions[3 * a + c] + positions[3 * b + c]));
    }
    return m;
  };
  const tris = new Int32Array(12 * nf);
  for (let f = 0; f < nf; ++f) {
    const a = triangles[3 * f], b = triangles[3 * f + 1], c = triangles[3 * f + 2];
    const ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
    tris.set([a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca], 12 * f);
  }
  return { positions: Float64Array.from(out), triangles: tris };
}

function writeOff(path, { positions, triangles }) {
  const nv = positions.length / 3, nf = triangles.length / 3;
  const lines = [`OFF`, `${nv} ${nf} 0`];
  for (let v = 0; v < nv; ++v) lines.push(`${positions[3 * v]} ${positions[3 * v + 1]} ${positions[3 * v + 2]}`);
  for (let f = 0; f < nf; ++f) lines.push(`3 ${triangles[3 * f]} ${triangles[3 * f + 1]} ${triangles[3 * f + 2]}`);
  writeFileSync(path, lines.join('\n') + '\n');
}

const args = process.argv.slice(2);
const li = args.indexOf('--levels');
const levels = li >= 0 ? Number(args.splice(li, 2)[1]) : 1;
if (args.length !== 2 || !(levels >= 1)) {
  console.error('usage: subdivide-off.mjs IN.off OUT.off [--levels N]');
  process.exit(2);
}
let mesh = readOff(args[0]);
for (let l = 0; l < levels; ++l) mesh = subdivide(mesh);
writeOff(args[1], mesh);
const nf = mesh.triangles.length / 3;
console.log(`subdivide-off: ${args[1]}: ${mesh.positions.length / 3} vertices, ${nf} faces (~${(3 * nf) / 2} edges if closed)`);
