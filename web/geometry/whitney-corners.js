// A vector field's Whitney reconstruction (paper Eq. 4) at the corners of each face: the field its 1-form
// defines is linear over a face, so its three corner values, interpolated by barycentric coordinates, give it
// exactly at every point of the face (the texture's Jacobian pass does that per texel). Its tangential part is
// continuous across edges; its value at the barycentre is the core's face vector.
//
// Owns nothing. Imports nothing.

// The mesh's edges by their lower vertex, to find the edge joining two vertices: {start (nV + 1), upper, id}
// (row v: upper[start[v] .. start[v + 1]) the edges' other vertices, id their indices, or null where the rows
// are the edges in their own order; whitneyCorners adds faceEdges). edges: 2 per edge, lower vertex first. The
// core lists them by lower vertex already (core/mesh/mesh_topology.cpp), and then the rows are one counting
// pass (armadillo-sub2's 1.25M edges in one task of its first texture: 62-82 ms with the rows sorted here).
export function edgeRows(edges, nV) {
  const nE = edges.length / 2;
  const start = new Int32Array(nV + 1);
  let sorted = true;
  for (let e = 0; e < nE; e++) {
    start[edges[2 * e] + 1]++;
    if (e > 0 && edges[2 * e] < edges[2 * e - 2]) sorted = false;
  }
  for (let v = 0; v < nV; v++) start[v + 1] += start[v];
  if (sorted) {
    const upper = new Int32Array(nE);
    for (let e = 0; e < nE; e++) upper[e] = edges[2 * e + 1];
    return { start, upper, id: null };
  }
  const fill = start.slice(0, nV), upper = new Int32Array(nE), id = new Int32Array(nE);
  for (let e = 0; e < nE; e++) {
    const at = fill[edges[2 * e]]++;
    upper[at] = edges[2 * e + 1];
    id[at] = e;
  }
  return { start, upper, id };
}

// The edge from a to b as e + 1 where it runs that way (its lower vertex a), -(e + 1) where it runs the other;
// 0 where there is none.
export function signedEdge({ start, upper, id }, a, b) {
  const lo = a < b ? a : b, hi = a < b ? b : a;
  for (let at = start[lo]; at < start[lo + 1]; at++) {
    if (upper[at] !== hi) continue;
    const e = id ? id[at] : at;
    return a < b ? e + 1 : -(e + 1);
  }
  return 0;
}

// Each face's three signed edges (signedEdge; local edge k from corner k to k + 1), kept in rows.faceEdges and
// looked up for faces f0 .. f1 - 1 where not yet (0): an update's loop then only reads them (bunny00's 75k
// faces: 5 ms a pass once compiled, against 10-14 ms looking them up each time). Returns rows.faceEdges.
function faceEdgesOf(rows, triangles, f0, f1) {
  const FE = (rows.faceEdges ??= new Int32Array(triangles.length));
  for (let h = 3 * f0; h < 3 * f1; h++) {
    if (FE[h] !== 0) continue;
    const a = triangles[h], b = triangles[h % 3 === 2 ? h - 2 : h + 1];
    FE[h] = signedEdge(rows, a, b);
    if (FE[h] === 0) throw new Error(`the edge ${a}-${b} of a face is not among the mesh's edges`);
  }
  return FE;
}

// Faces f0 .. f1 - 1 of the field whose 1-form is `oneForm` (1 per edge, the integral from its lower vertex to
// its upper), at their corners: corner k of face f at out[stride f + (stride / 3) k ...] (x, y, z; stride 9, or
// 12 for RGBA texels). rows: edgeRows(). With w_k the integral along local edge k (corner k to k + 1) and ∇b_k
// the gradient of corner k's barycentric coordinate, the Whitney field at corner k is
// w_k ∇b_(k+1) − w_(k−1) ∇b_(k−1). Returns the sum over the faces of the mean corner length times the area.
export function whitneyCorners(positions, triangles, rows, oneForm, f0, f1, out, stride = 9) {
  const P = positions, T = triangles, step = stride / 3;
  const FE = faceEdgesOf(rows, T, f0, f1);
  const along = (e) => (e > 0 ? oneForm[e - 1] : -oneForm[-e - 1]);
  let magnitude = 0;
  for (let f = f0; f < f1; f++) {
    const i = T[3 * f], j = T[3 * f + 1], k = T[3 * f + 2];
    const a = 3 * i, b = 3 * j, c = 3 * k;
    // Edges opposite each corner (k + 1 to k + 2) and the unnormalized normal n (|n| = 2 area).
    const ax = P[c] - P[b], ay = P[c + 1] - P[b + 1], az = P[c + 2] - P[b + 2];
    const bx = P[a] - P[c], by = P[a + 1] - P[c + 1], bz = P[a + 2] - P[c + 2];
    const cx = P[b] - P[a], cy = P[b + 1] - P[a + 1], cz = P[b + 2] - P[a + 2];
    const nx = cz * by - cy * bz, ny = cx * bz - cz * bx, nz = cy * bx - cx * by;
    const n2 = nx * nx + ny * ny + nz * nz;
    const o = stride * f;
    if (!(n2 > 0)) {
      for (let d = 0; d < stride; d++) out[o + d] = 0; // a degenerate face has no field (the core refuses them)
      continue;
    }
    // ∇b_k = n × (edge opposite k) / |n|², with the 1-form's values folded in.
    const s = 1 / n2, w0 = along(FE[3 * f]) * s, w1 = along(FE[3 * f + 1]) * s, w2 = along(FE[3 * f + 2]) * s;
    const g0x = ny * az - nz * ay, g0y = nz * ax - nx * az, g0z = nx * ay - ny * ax;
    const g1x = ny * bz - nz * by, g1y = nz * bx - nx * bz, g1z = nx * by - ny * bx;
    const g2x = ny * cz - nz * cy, g2y = nz * cx - nx * cz, g2z = nx * cy - ny * cx;
    const x0 = w0 * g1x - w2 * g2x, y0 = w0 * g1y - w2 * g2y, z0 = w0 * g1z - w2 * g2z;
    const x1 = w1 * g2x - w0 * g0x, y1 = w1 * g2y - w0 * g0y, z1 = w1 * g2z - w0 * g0z;
    const x2 = w2 * g0x - w1 * g1x, y2 = w2 * g0y - w1 * g1y, z2 = w2 * g0z - w1 * g1z;
    out[o] = x0;
    out[o + 1] = y0;
    out[o + 2] = z0;
    out[o + step] = x1;
    out[o + step + 1] = y1;
    out[o + step + 2] = z1;
    out[o + 2 * step] = x2;
    out[o + 2 * step + 1] = y2;
    out[o + 2 * step + 2] = z2;
    const lengths =
      Math.sqrt(x0 * x0 + y0 * y0 + z0 * z0) +
      Math.sqrt(x1 * x1 + y1 * y1 + z1 * z1) +
      Math.sqrt(x2 * x2 + y2 * y2 + z2 * z2);
    magnitude += (lengths / 3) * 0.5 * Math.sqrt(n2);
  }
  return magnitude;
}
