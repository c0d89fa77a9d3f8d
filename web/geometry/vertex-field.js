// The face vectors and the one-form of a field known by its vertex vectors: a preview's (core/preview/), which
// carries its vertex vectors alone so that a stroke's preview is on screen sooner; carrying the field to every
// face and edge of a 1.25M-edge mesh took the preview worker 55 of its 60 ms, for arrays only the read API and
// the singularity view ask for, on the page and when they ask (session/derived-field.js).
//
// Owns nothing. Imports nothing.

// surface: surface.js's (positions, triangles, normals, nF); V: 3 per vertex. Each face's vector: the mean of
// its corners' vectors, laid into the face's plane (the field at the face's barycentre, as the core's
// Whitney reconstruction gives it for a field that is linear over the face, and as the arrows draw it).
export function faceVectorsOfVertexField(surface, V) {
  const { triangles: T, normals: N, nF } = surface;
  const out = new Float64Array(3 * nF);
  for (let f = 0; f < nF; f++) {
    const a = 3 * T[3 * f], b = 3 * T[3 * f + 1], c = 3 * T[3 * f + 2];
    const x = (V[a] + V[b] + V[c]) / 3;
    const y = (V[a + 1] + V[b + 1] + V[c + 1]) / 3;
    const z = (V[a + 2] + V[b + 2] + V[c + 2]) / 3;
    const nx = N[3 * f], ny = N[3 * f + 1], nz = N[3 * f + 2];
    const d = x * nx + y * ny + z * nz;
    out[3 * f] = x - d * nx;
    out[3 * f + 1] = y - d * ny;
    out[3 * f + 2] = z - d * nz;
  }
  return out;
}

// surface: positions and edges (2 per edge, the core's order); V: 3 per vertex. The line integral of the field
// along each edge, the vectors taken as linear along it (exact for a field linear in space; the trapezoid
// rule). An N-field (symmetry ≥ 2) has no one-form: zeros, as the core gives.
export function oneFormOfVertexField(surface, V, symmetry = 1) {
  const { positions: P, edges: E } = surface;
  const nE = E.length / 2;
  const out = new Float64Array(nE);
  if (symmetry > 1) return out;
  for (let e = 0; e < nE; e++) {
    const i = 3 * E[2 * e], j = 3 * E[2 * e + 1];
    out[e] =
      0.5 *
      ((V[i] + V[j]) * (P[j] - P[i]) +
        (V[i + 1] + V[j + 1]) * (P[j + 1] - P[i + 1]) +
        (V[i + 2] + V[j + 2]) * (P[j + 2] - P[i + 2]));
  }
  return out;
}
