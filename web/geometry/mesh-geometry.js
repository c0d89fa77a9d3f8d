// Per-face geometry and the edge→face maps of a triangle mesh, in one place for the views, the tools and the
// texture synthesis. Flat typed arrays, face f = triangles[3f..3f+2]; local edge k of a face runs from corner
// k to corner k+1.

// Unit normals (3 per face; [0, 0, 1] for a degenerate face). Scalars only in the loops here and below: they
// run once per face of 800k-face scans, where a small array per face cost seconds of GC. (The page's surface
// sums the areas with its other per-face pass, and reads a face's centroid from the positions when wanted.)
export function faceNormals(positions, triangles) {
  const P = positions, T = triangles, nF = T.length / 3;
  const normals = new Float64Array(3 * nF);
  for (let f = 0; f < nF; f++) {
    const a = 3 * T[3 * f], b = 3 * T[3 * f + 1], c = 3 * T[3 * f + 2];
    const ux = P[b] - P[a], uy = P[b + 1] - P[a + 1], uz = P[b + 2] - P[a + 2];
    const wx = P[c] - P[a], wy = P[c + 1] - P[a + 1], wz = P[c + 2] - P[a + 2];
    const nx = uy * wz - uz * wy, ny = uz * wx - ux * wz, nz = ux * wy - uy * wx;
    const l = Math.sqrt(nx * nx + ny * ny + nz * nz);
    if (l > 0) {
      normals[3 * f] = nx / l;
      normals[3 * f + 1] = ny / l;
      normals[3 * f + 2] = nz / l;
    }
    else normals[3 * f + 2] = 1;
  }
  return normals;
}

// Edge → face map as half-edge pairing: neighbour[3f+k] = 3g+kk when local edge k of face f is local edge kk
// of face g, -1 on a boundary (or a non-manifold edge's third face). Half-edges are grouped by their lower
// vertex (a counting sort, no hash map: a Map keyed by vertex pairs took ~2 s at 800k faces) and paired with
// the next one of the same upper vertex in face order, as they come.
export function halfEdgeNeighbours(triangles, nV) {
  const T = triangles, nH = T.length;
  const neighbour = new Int32Array(nH).fill(-1);
  const lower = (h) => Math.min(T[h], T[h - (h % 3) + ((h % 3) + 1) % 3]);
  const upper = (h) => Math.max(T[h], T[h - (h % 3) + ((h % 3) + 1) % 3]);
  const start = new Int32Array(nV + 1);
  for (let h = 0; h < nH; h++) start[lower(h) + 1]++;
  for (let v = 0; v < nV; v++) start[v + 1] += start[v];
  const list = new Int32Array(nH);
  const fill = start.slice(0, nV);
  for (let h = 0; h < nH; h++) list[fill[lower(h)]++] = h;
  for (let v = 0; v < nV; v++) {
    const end = start[v + 1];
    for (let i = start[v]; i < end; i++) {
      const h = list[i];
      if (neighbour[h] !== -1) continue;
      const w = upper(h);
      for (let j = i + 1; j < end; j++) {
        const g = list[j];
        if (neighbour[g] !== -1 || upper(g) !== w) continue;
        neighbour[h] = g;
        neighbour[g] = h;
        break;
      }
    }
  }
  return neighbour;
}

// Faces around each vertex (CSR: faces of v are vertexFaces[start[v] .. start[v+1]]).
export function vertexFaceMap(triangles, nV) {
  const T = triangles;
  const start = new Int32Array(nV + 1);
  for (let t = 0; t < T.length; t++) start[T[t] + 1]++;
  for (let v = 0; v < nV; v++) start[v + 1] += start[v];
  const faces = new Int32Array(T.length);
  const fill = start.slice(0, nV);
  for (let t = 0; t < T.length; t++) faces[fill[T[t]]++] = Math.floor(t / 3);
  return { start, faces };
}

// Area-weighted unit vertex normals, straight from the positions (each face's cross product is twice its area
// times its normal): the preview's map needs no face arrays (three of them, normals, areas and centroids, took
// it 0.3-0.5 s at 832k faces).
export function vertexNormals(positions, triangles) {
  const P = positions, T = triangles;
  const out = new Float64Array(positions.length);
  for (let f = 0; f < T.length / 3; f++) {
    const a = 3 * T[3 * f], b = 3 * T[3 * f + 1], c = 3 * T[3 * f + 2];
    const ux = P[b] - P[a], uy = P[b + 1] - P[a + 1], uz = P[b + 2] - P[a + 2];
    const wx = P[c] - P[a], wy = P[c + 1] - P[a + 1], wz = P[c + 2] - P[a + 2];
    const nx = uy * wz - uz * wy, ny = uz * wx - ux * wz, nz = ux * wy - uy * wx;
    out[a] += nx;
    out[a + 1] += ny;
    out[a + 2] += nz;
    out[b] += nx;
    out[b + 1] += ny;
    out[b + 2] += nz;
    out[c] += nx;
    out[c + 1] += ny;
    out[c + 2] += nz;
  }
  return normalizeEach3(out);
}

// Each 3-vector of a flat array (out[3k..3k+2]) scaled to unit length in place (a zero one left as it is);
// returns out. The vertex normals' last step here and in quad/quad-mesh.js.
export function normalizeEach3(out) {
  for (let v = 0; v < out.length; v += 3) {
    const l = Math.hypot(out[v], out[v + 1], out[v + 2]) || 1;
    out[v] /= l;
    out[v + 1] /= l;
    out[v + 2] /= l;
  }
  return out;
}

// 2π less the corner angles around each vertex (meaningful on interior vertices), as the core's geometry.
export function angleDefects(positions, triangles, nV) {
  const P = positions, T = triangles, nF = T.length / 3;
  const defect = new Float64Array(nV).fill(2 * Math.PI);
  for (let f = 0; f < nF; f++) {
    for (let c = 0; c < 3; c++) {
      const o = 3 * T[3 * f + c], p = 3 * T[3 * f + ((c + 1) % 3)], q = 3 * T[3 * f + ((c + 2) % 3)];
      const ux = P[p] - P[o], uy = P[p + 1] - P[o + 1], uz = P[p + 2] - P[o + 2];
      const vx = P[q] - P[o], vy = P[q + 1] - P[o + 1], vz = P[q + 2] - P[o + 2];
      const cross = Math.hypot(uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx);
      defect[T[3 * f + c]] -= Math.atan2(cross, ux * vx + uy * vy + uz * vz);
    }
  }
  return defect;
}
