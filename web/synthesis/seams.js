// SPDX-License-Identifier: GPL-2.0-or-later
// Seam indirection (Lefebvre & Hoppe 2006, Sec. 6.2 "texture atlases"): synthesis neighbourhoods that reach past
// a chart's edge must read the texels on the other side of that edge on the surface, which lie in another chart
// (or elsewhere in the same one). For every texel outside all triangles (the gutter) next to a seam edge, this
// map names the texel that holds the same surface point in the neighbouring chart: the face across the edge is
// unfolded about the edge into the first face's plane, mapped with the first face's 3D-to-UV map, rasterized
// over the gutter, and each gutter texel centre inside it is sent through the face's own UVs.
// Coarser synthesis levels use the finest map at each coarse texel's centre.

import { halfEdgeNeighbours } from '../geometry/mesh-geometry.js';
import { rasterCoverage } from './atlas.js';
import { edgeUVsAgree } from './atlas-corners.js';

const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];

// Per face: vertex positions P[3], UVs Q[3], and the 3D->UV linear map M (2x3, rows) on the face plane.
function faceFrame(positions, triangles, cornerUVs, f) {
  const P = [0, 1, 2].map((k) => {
    const v = 3 * triangles[3 * f + k];
    return [positions[v], positions[v + 1], positions[v + 2]];
  });
  const Q = [0, 1, 2].map((k) => [cornerUVs[6 * f + 2 * k], cornerUVs[6 * f + 2 * k + 1]]);
  const e1 = sub(P[1], P[0]), e2 = sub(P[2], P[0]);
  const du1 = Q[1][0] - Q[0][0], dv1 = Q[1][1] - Q[0][1], du2 = Q[2][0] - Q[0][0], dv2 = Q[2][1] - Q[0][1];
  const det = du1 * dv2 - du2 * dv1;
  const n = cross(e1, e2);
  const nl = Math.hypot(...n);
  if (!(Math.abs(det) > 1e-14) || !(nl > 0)) return null;
  // G = [e1 e2] [[du1 du2] [dv1 dv2]]^-1 (3x2); M = (G^T G)^-1 G^T.
  const G1 = [0, 1, 2].map((k) => (e1[k] * dv2 - e2[k] * dv1) / det);
  const G2 = [0, 1, 2].map((k) => (e2[k] * du1 - e1[k] * du2) / det);
  const a = dot(G1, G1), b = dot(G1, G2), c = dot(G2, G2);
  const id = 1 / (a * c - b * b);
  const M = [
    [0, 1, 2].map((k) => id * (c * G1[k] - b * G2[k])),
    [0, 1, 2].map((k) => id * (-b * G1[k] + a * G2[k])),
  ];
  return { P, Q, M, n: n.map((x) => x / nl) };
}

// Gutter texel -> the same surface point across the seam at `resolution`, in texel units (continuous: texel i spans
// [i, i + 1), so floor() names the target texel and the fraction where inside it the point lies). mesh:
// {positions, triangles, neighbour?}, neighbour the half-edge map of geometry/mesh-geometry.js (the model's
// Surface has it; derived when absent). Returns Float32Array (4 per texel: target x, target y, 1 if
// redirected, and for a texel that borrowed a neighbour's target the neighbour's offset code
// 1 + (dx + 1) + 3 (dy + 1), else 0) and the number of redirected texels.
export function seamIndirection({ positions, triangles, neighbour = null }, cornerUVs, resolution) {
  const R = resolution;
  const nF = triangles.length / 3;
  const halfEdges = neighbour ?? halfEdgeNeighbours(triangles, positions.length / 3);
  const covered = rasterCoverage(cornerUVs, R);
  const out = new Float32Array(4 * R * R);
  const frames = new Array(nF);
  const frame = (f) =>
    frames[f] === undefined ? (frames[f] = faceFrame(positions, triangles, cornerUVs, f)) : frames[f];
  let redirected = 0, seamEdges = 0;
  // Each interior edge once, from its lower half-edge h (in face f), whose twin runs the other way in face g.
  for (let h = 0; h < 3 * nF; h++) {
    const other = halfEdges[h];
    if (other < h) continue;
    if (edgeUVsAgree(cornerUVs, h, other)) continue;
    const f = Math.floor(h / 3), g = Math.floor(other / 3);
    seamEdges++;
    // Both directions: g unfolded into f's chart, and f into g's.
    for (const [from, to] of [[f, g], [g, f]]) redirected += unfold(from, to);
  }
  if (seamEdges) redirected += fillFirstRing();
  return { map: out, redirected, seamEdges };

  // Gutter texels touching a chart that the unfolded faces missed (slivers across a seam cover few texels)
  // borrow the target of a redirected neighbour (within ~1 texel of the right one): the magnified rendering blends
  // these texels into the chart's edge, where the chart's own gutter synthesis would show as a seam.
  function fillFirstRing() {
    const add = [];
    const at = (x, y) => (x < 0 || y < 0 || x >= R || y >= R ? -1 : y * R + x);
    for (let y = 0; y < R; y++)
      for (let x = 0; x < R; x++) {
        const t = y * R + x;
        if (covered[t] || out[4 * t + 2]) continue;
        let touchesChart = false, from = -1;
        for (let dy = -1; dy <= 1; dy++)
          for (let dx = -1; dx <= 1; dx++) {
            const n = at(x + dx, y + dy);
            if (n < 0 || n === t) continue;
            if (covered[n]) touchesChart = true;
            else if (out[4 * n + 2] && (from < 0 || Math.abs(dx) + Math.abs(dy) === 1)) from = n;
          }
        if (touchesChart && from >= 0) add.push([t, from]);
      }
    // The neighbour's offset goes along: rendering continues the neighbour's resolved patch by it (SEAM_RESOLVE_FS).
    for (const [t, n] of add) {
      const dx = (n % R) - (t % R), dy = Math.floor(n / R) - Math.floor(t / R);
      out.set([out[4 * n], out[4 * n + 1], 1, 1 + (dx + 1) + 3 * (dy + 1)], 4 * t);
    }
    return add.length;
  }

  // Rasterizes face `to` unfolded about the shared edge into face `from`'s UV chart, over uncovered texels.
  function unfold(from, to) {
    const A = frame(from), B = frame(to);
    if (!A || !B) return 0;
    // Shared vertices and the opposite vertex of `to`.
    const tv = [0, 1, 2].map((k) => triangles[3 * to + k]);
    const fv = new Set([0, 1, 2].map((k) => triangles[3 * from + k]));
    const shared = tv.filter((v) => fv.has(v));
    if (shared.length !== 2) return 0;
    const opp = tv.find((v) => !fv.has(v));
    const kOf = (face, v) => [0, 1, 2].find((k) => triangles[3 * face + k] === v);
    const Xi = A.P[kOf(from, shared[0])], Xj = A.P[kOf(from, shared[1])];
    const Xo = B.P[kOf(to, opp)];
    const fOpp = A.P[[0, 1, 2].find((k) => !shared.includes(triangles[3 * from + k]))];
    const e = sub(Xj, Xi);
    const el = Math.hypot(...e);
    if (!(el > 0)) return 0;
    const eh = e.map((x) => x / el);
    const w = sub(Xo, Xi);
    const along = dot(w, eh);
    const off = sub(w, eh.map((x) => x * along));
    const h = Math.hypot(...off);
    let perp = cross(eh, A.n);
    if (dot(perp, sub(fOpp, Xi)) > 0) perp = perp.map((x) => -x);
    const Xu = [0, 1, 2].map((c) => Xi[c] + along * eh[c] + h * perp[c]);
    // Corners of the unfolded triangle in `from`'s UV, and their UVs in `to`'s own chart.
    const uvI = A.Q[kOf(from, shared[0])], uvJ = A.Q[kOf(from, shared[1])];
    const d = sub(Xu, Xi);
    const uvU = [uvI[0] + dot(A.M[0], d), uvI[1] + dot(A.M[1], d)];
    const src = [uvI, uvJ, uvU].map(([u, v]) => [u * R, v * R]);
    const dst = [B.Q[kOf(to, shared[0])], B.Q[kOf(to, shared[1])], B.Q[kOf(to, opp)]].map(([u, v]) => [u * R, v * R]);
    const [a, b, c] = src;
    const area = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
    if (!(Math.abs(area) > 1e-12)) return 0;
    const x0 = Math.max(0, Math.floor(Math.min(a[0], b[0], c[0]) - 0.5));
    const x1 = Math.min(R - 1, Math.ceil(Math.max(a[0], b[0], c[0]) - 0.5));
    const y0 = Math.max(0, Math.floor(Math.min(a[1], b[1], c[1]) - 0.5));
    const y1 = Math.min(R - 1, Math.ceil(Math.max(a[1], b[1], c[1]) - 0.5));
    let count = 0;
    for (let y = y0; y <= y1; y++)
      for (let x = x0; x <= x1; x++) {
        const t = y * R + x;
        if (covered[t] || out[4 * t + 2]) continue;
        const px = x + 0.5, py = y + 0.5;
        const l1 = ((c[0] - px) * (a[1] - py) - (a[0] - px) * (c[1] - py)) / area; // weight of b
        const l2 = ((a[0] - px) * (b[1] - py) - (b[0] - px) * (a[1] - py)) / area; // weight of c
        const l0 = 1 - l1 - l2;
        if (l0 < -1e-6 || l1 < -1e-6 || l2 < -1e-6) continue;
        const tx = l0 * dst[0][0] + l1 * dst[1][0] + l2 * dst[2][0];
        const ty = l0 * dst[0][1] + l1 * dst[1][1] + l2 * dst[2][1];
        out[4 * t] = Math.min(R - 0.5, Math.max(0, tx));
        out[4 * t + 1] = Math.min(R - 0.5, Math.max(0, ty));
        out[4 * t + 2] = 1;
        count++;
      }
    return count;
  }
}

// The map for the level whose texels are 2^k finest texels: each coarse texel uses the finest texel at its centre.
export function coarserIndirection(map, resolution, k) {
  const r = resolution >> k, s = 1 << k, half = s >> 1;
  const out = new Float32Array(4 * r * r);
  for (let y = 0; y < r; y++)
    for (let x = 0; x < r; x++) {
      const t = (y * s + half) * resolution + (x * s + half);
      if (!map[4 * t + 2]) continue;
      const o = 4 * (y * r + x);
      out[o] = Math.floor(map[4 * t] / s);
      out[o + 1] = Math.floor(map[4 * t + 1] / s);
      out[o + 2] = 1;
    }
  return out;
}
