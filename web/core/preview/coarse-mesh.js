// A coarse stand-in for a big mesh, for the preview core (preview.js): meshoptimizer's quadric simplifier
// (edge collapses, borders locked), then the repairs the core's topology checks need (collapses can pinch an
// edge between four faces or a vertex between two fans): the offending faces are dropped, which leaves small
// holes the preview does not mind. The coarse vertices are a subset of the fine ones (`fineVertex`), which is
// what surface-map.js maps through.
//
// Owns nothing across calls. Imports meshoptimizer only.
import { MeshoptSimplifier } from 'meshoptimizer';

// Enough faces that the preview's field looks like the exact one at a glance, few enough that the coarse
// system factors in well under a second and a stroke's update and solve take a few milliseconds.
export const COARSE_FACES = 40_000;
// Meshes over this many times the target are first clustered down to it (coarseMesh).
const CLUSTER_ABOVE = 5;

// positions: Float64Array (3 per vertex), triangles: Int32Array (3 per face). Returns {positions (Float64Array),
// triangles (Int32Array, coarse vertex indices), fineVertex (Int32Array: coarse vertex → fine vertex), ms}.
// At most COARSE_FACES, and a quarter of the mesh (a preview forced on a small mesh is still coarser).
export async function coarseMesh(positions, triangles) {
  await MeshoptSimplifier.ready;
  const t0 = performance.now();
  const nF = triangles.length / 3;
  const targetFaces = Math.min(COARSE_FACES, Math.ceil(nF / 4));
  // The engine's bulk conversions (Float32Array.from walks an iterator).
  const P32 = new Float32Array(positions);
  let indices = new Uint32Array(triangles);
  if (nF > CLUSTER_ABOVE * targetFaces) {
    // Vertex clustering down to a few times the target, then the quadric collapses: at 832k faces 0.47 s in
    // place of 1.13–1.6 s (node), the coarse mesh's error 6.2e-4 of the extent in place of 5.2e-4. Clustering
    // keeps fine vertices as the collapses do, so the map's premise holds; what it pinches, the repairs drop.
    [indices] = MeshoptSimplifier.simplifySloppy(indices, P32, 3, null, 3 * CLUSTER_ABOVE * targetFaces, 1);
  }
  if (indices.length / 3 > targetFaces) {
    // Error 1 (relative to the mesh's extent): the face count decides, not the error.
    [indices] = MeshoptSimplifier.simplify(indices, P32, 3, 3 * targetFaces, 1, ['LockBorder']);
  }
  const kept = repairTopology(indices, positions);
  return { ...compact(positions, kept), ms: performance.now() - t0 };
}

// Drops faces until every edge has one or two faces, at most one per direction, and every vertex one fan.
function repairTopology(indices, positions) {
  const nV = positions.length / 3;
  let faces = dropDegenerate(indices, positions);
  for (let round = 0; round < 8; round++) {
    const bad = new Set([...facesOnBadEdges(faces, nV), ...facesOnPinchedVertices(faces, nV)]);
    if (bad.size === 0) break;
    faces = faces.filter((_, k) => !bad.has(Math.floor(k / 3)));
  }
  return faces;
}

// A collapse can leave three vertices in a line (exactly so on a subdivided mesh, whose midpoints lie on the
// coarse edges); such faces, and slivers near them, go. The core's test is area ≤ 1e-12 × the longest edge²;
// this keeps well clear of it.
function dropDegenerate(indices, P) {
  const out = [];
  for (let f = 0; f < indices.length / 3; f++) {
    const a = 3 * indices[3 * f], b = 3 * indices[3 * f + 1], c = 3 * indices[3 * f + 2];
    if (a === b || b === c || a === c) continue;
    const u = [P[b] - P[a], P[b + 1] - P[a + 1], P[b + 2] - P[a + 2]];
    const w = [P[c] - P[a], P[c + 1] - P[a + 1], P[c + 2] - P[a + 2]];
    const v = [w[0] - u[0], w[1] - u[1], w[2] - u[2]];
    const n = Math.hypot(u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]);
    const longest = Math.max(
      u[0] ** 2 + u[1] ** 2 + u[2] ** 2,
      w[0] ** 2 + w[1] ** 2 + w[2] ** 2,
      v[0] ** 2 + v[1] ** 2 + v[2] ** 2,
    );
    if (n > 1e-6 * longest) out.push(a / 3, b / 3, c / 3);
  }
  return out;
}

// The faces (a flat list of corners) grouped per vertex, as CSR: start (nV + 1), list (face indices).
function facesPerVertex(faces, nV) {
  const start = new Int32Array(nV + 1);
  for (const v of faces) start[v + 1]++;
  for (let v = 0; v < nV; v++) start[v + 1] += start[v];
  const list = new Int32Array(faces.length);
  const fill = start.slice(0, nV);
  for (let k = 0; k < faces.length; k++) list[fill[faces[k]]++] = (k / 3) | 0;
  return { start, list };
}

// Faces on an edge with more than two faces, or two running the same way (flat arrays: a Map keyed by vertex
// pairs took most of a second at 60k faces). Each edge is found from its lower vertex's faces.
function facesOnBadEdges(faces, nV) {
  const { start, list } = facesPerVertex(faces, nV);
  const bad = [];
  const hi = [], face = [], forward = [];
  for (let v = 0; v < nV; v++) {
    hi.length = face.length = forward.length = 0;
    for (let k = start[v]; k < start[v + 1]; k++) {
      const f = list[k];
      for (let c = 0; c < 3; c++) {
        const a = faces[3 * f + c], b = faces[3 * f + ((c + 1) % 3)];
        if (Math.min(a, b) !== v) continue;
        hi.push(Math.max(a, b));
        face.push(f);
        forward.push(a < b);
      }
    }
    for (let i = 0; i < hi.length; i++) {
      let count = 0, fwd = 0;
      for (let j = 0; j < hi.length; j++) if (hi[j] === hi[i]) count++, (fwd += forward[j] ? 1 : 0);
      if (count > 2 || fwd === 2 || (count === 2 && fwd !== 1)) bad.push(face[i]);
    }
  }
  return bad;
}

// A vertex whose faces form more than one fan (connected through edges at the vertex) pinches the surface:
// all but its largest fan go.
function facesOnPinchedVertices(faces, nV) {
  const { start, list } = facesPerVertex(faces, nV);
  const out = [];
  for (let v = 0; v < nV; v++) {
    if (start[v + 1] - start[v] < 2) continue;
    const fans = fansAround(v, list.subarray(start[v], start[v + 1]), faces);
    if (fans.length < 2) continue;
    fans.sort((a, b) => b.length - a.length);
    for (const fan of fans.slice(1)) out.push(...fan);
  }
  return out;
}

function fansAround(v, around, faces) {
  const parent = Array.from(around, (_, i) => i);
  const find = (i) => (parent[i] === i ? i : (parent[i] = find(parent[i])));
  const byNeighbour = new Map();
  around.forEach((f, i) => {
    for (let c = 0; c < 3; c++) {
      const w = faces[3 * f + c];
      if (w === v) continue;
      const j = byNeighbour.get(w);
      if (j === undefined) byNeighbour.set(w, i);
      else parent[find(i)] = find(j);
    }
  });
  const groups = new Map();
  around.forEach((f, i) => {
    const r = find(i);
    if (!groups.has(r)) groups.set(r, []);
    groups.get(r).push(f);
  });
  return [...groups.values()];
}

function compact(positions, faces) {
  const map = new Map();
  const fineVertex = [];
  const triangles = new Int32Array(faces.length);
  faces.forEach((v, k) => {
    let c = map.get(v);
    if (c === undefined) {
      c = fineVertex.length;
      map.set(v, c);
      fineVertex.push(v);
    }
    triangles[k] = c;
  });
  const P = new Float64Array(3 * fineVertex.length);
  fineVertex.forEach((v, c) => P.set(positions.subarray(3 * v, 3 * v + 3), 3 * c));
  return { positions: P, triangles, fineVertex: Int32Array.from(fineVertex) };
}

// The coarse mesh as OFF text, the format every core reads.
export function offBytes({ positions, triangles }) {
  const lines = [`OFF\n${positions.length / 3} ${triangles.length / 3} 0`];
  for (let v = 0; v < positions.length; v += 3) lines.push(`${positions[v]} ${positions[v + 1]} ${positions[v + 2]}`);
  for (let f = 0; f < triangles.length; f += 3) lines.push(`3 ${triangles[f]} ${triangles[f + 1]} ${triangles[f + 2]}`);
  return new TextEncoder().encode(lines.join('\n') + '\n');
}
