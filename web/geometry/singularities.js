// Singular vertices of a face-constant tangent field, for the page's synchronous reads and the singularity
// view: the same index as the core's findSingularities (core/field/singularities.cpp), computed on the page
// from the face vectors it already holds, so that no edit has to wait for it in the worker.
//
// Index at an interior vertex v: (sum of the field's turning across the edges around v + angle defect) / 2π,
// rounded. The turning across an edge is the argument of the ratio of the two faces' vectors, each written as
// a complex number in the frame of the edge (real axis) and its face's normal: unfolding across the edge keeps
// that number, so the ratio is the rotation. Each interior edge is measured once and counted for both its
// ends with opposite signs (walked the other way round its other end). Vertices next to a face with a
// negligible vector have no defined index and are skipped, as in the core.
//
// An N-symmetric field (symmetry N ≥ 2) has one representative per face chosen arbitrarily among N: the
// turning across an edge is then the smallest rotation taking one face's set onto the other's (the jump
// reduced to (−π/N, π/N]), and the index is a multiple of 1/N.

import { symmetryOf } from './nfield.js';

const TWO_PI = 2 * Math.PI;

// surface: web/surface.js; faceVectors: 3 per face; symmetry: N (1 when absent). Returns [{vertex, index}] in
// vertex order.
export function findSingularities(surface, faceVectors, symmetry = 1) {
  const sym = symmetryOf(symmetry);
  const { positions: P, triangles: T, normals: N, neighbour, nV, nF } = surface;
  const F = faceVectors;
  let maxNorm2 = 0;
  for (let f = 0; f < nF; f++) maxNorm2 = Math.max(maxNorm2, F[3 * f] ** 2 + F[3 * f + 1] ** 2 + F[3 * f + 2] ** 2);
  if (!(maxNorm2 > 0)) return [];
  const tiny2 = 1e-20 * maxNorm2; // (1e-10 of the largest norm)²
  const turning = new Float64Array(nV);
  // 1: interior with every face around it defined; 0: boundary, isolated or next to a negligible vector.
  const counted = new Uint8Array(nV);
  for (let t = 0; t < 3 * nF; t++) counted[T[t]] = 1;
  for (let f = 0; f < nF; f++) {
    const ux = F[3 * f], uy = F[3 * f + 1], uz = F[3 * f + 2];
    const nx = N[3 * f], ny = N[3 * f + 1], nz = N[3 * f + 2];
    const small = !(ux * ux + uy * uy + uz * uz > tiny2);
    for (let k = 0; k < 3; k++) {
      const h = 3 * f + k;
      const a = T[h], b = T[3 * f + ((k + 1) % 3)];
      const other = neighbour[h];
      if (other < 0) counted[a] = counted[b] = 0;
      if (small) counted[a] = 0;
      if (other <= h) continue; // boundary, or measured from the other side
      const g = (other / 3) | 0;
      // Half-edge (a → b) of f is (b → a) of g: walking round b counter-clockwise goes from f to g, across the
      // edge vector a − b. Each face's vector u as (e · u, (e × u) · n).
      const ex = P[3 * a] - P[3 * b], ey = P[3 * a + 1] - P[3 * b + 1], ez = P[3 * a + 2] - P[3 * b + 2];
      const fr = ex * ux + ey * uy + ez * uz;
      const fi = (ey * uz - ez * uy) * nx + (ez * ux - ex * uz) * ny + (ex * uy - ey * ux) * nz;
      const vx = F[3 * g], vy = F[3 * g + 1], vz = F[3 * g + 2];
      const gr = ex * vx + ey * vy + ez * vz;
      const gi =
        (ey * vz - ez * vy) * N[3 * g] + (ez * vx - ex * vz) * N[3 * g + 1] + (ex * vy - ey * vx) * N[3 * g + 2];
      let jump = Math.atan2(gi * fr - gr * fi, gr * fr + gi * fi); // arg(g · conj(f))
      if (sym > 1) jump -= (TWO_PI / sym) * Math.round((sym * jump) / TWO_PI);
      turning[b] += jump;
      turning[a] -= jump;
    }
  }
  const defect = surface.angleDefects();
  const out = [];
  for (let v = 0; v < nV; v++) {
    if (!counted[v]) continue;
    const index =
      sym > 1
        ? Math.round((sym * (turning[v] + defect[v])) / TWO_PI) / sym
        : Math.round((turning[v] + defect[v]) / TWO_PI);
    if (index !== 0) out.push({ vertex: v, index });
  }
  return out;
}
