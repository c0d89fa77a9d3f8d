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

// A face's frame, flat (no arrays per face: at 832k faces the seams' faces made 0.4 s of garbage): vertex
// positions P at 0..8, UVs Q at 9..14, the 3D->UV linear map M (2x3, rows) on the face plane at 15..20, the unit
// normal at 21..23. null where the face or its UVs are degenerate.
const P = 0, Q = 9, M = 15, N = 21;

function faceFrame(positions, triangles, cornerUVs, f) {
  const F = new Float64Array(24);
  for (let k = 0; k < 3; k++) {
    const v = 3 * triangles[3 * f + k];
    F[P + 3 * k] = positions[v], F[P + 3 * k + 1] = positions[v + 1], F[P + 3 * k + 2] = positions[v + 2];
    F[Q + 2 * k] = cornerUVs[6 * f + 2 * k], F[Q + 2 * k + 1] = cornerUVs[6 * f + 2 * k + 1];
  }
  const e1x = F[3] - F[0], e1y = F[4] - F[1], e1z = F[5] - F[2];
  const e2x = F[6] - F[0], e2y = F[7] - F[1], e2z = F[8] - F[2];
  const du1 = F[Q + 2] - F[Q], dv1 = F[Q + 3] - F[Q + 1], du2 = F[Q + 4] - F[Q], dv2 = F[Q + 5] - F[Q + 1];
  const det = du1 * dv2 - du2 * dv1;
  const nx = e1y * e2z - e1z * e2y, ny = e1z * e2x - e1x * e2z, nz = e1x * e2y - e1y * e2x;
  const nl = Math.hypot(nx, ny, nz);
  if (!(Math.abs(det) > 1e-14) || !(nl > 0)) return null;
  // G = [e1 e2] [[du1 du2] [dv1 dv2]]^-1 (3x2); M = (G^T G)^-1 G^T.
  const g1x = (e1x * dv2 - e2x * dv1) / det, g1y = (e1y * dv2 - e2y * dv1) / det, g1z = (e1z * dv2 - e2z * dv1) / det;
  const g2x = (e2x * du1 - e1x * du2) / det, g2y = (e2y * du1 - e1y * du2) / det, g2z = (e2z * du1 - e1z * du2) / det;
  const a = g1x * g1x + g1y * g1y + g1z * g1z, b = g1x * g2x + g1y * g2y + g1z * g2z;
  const c = g2x * g2x + g2y * g2y + g2z * g2z;
  const id = 1 / (a * c - b * b);
  F[M] = id * (c * g1x - b * g2x), F[M + 1] = id * (c * g1y - b * g2y), F[M + 2] = id * (c * g1z - b * g2z);
  F[M + 3] = id * (-b * g1x + a * g2x), F[M + 4] = id * (-b * g1y + a * g2y), F[M + 5] = id * (-b * g1z + a * g2z);
  F[N] = nx / nl, F[N + 1] = ny / nl, F[N + 2] = nz / nl;
  return F;
}

// The corner (0-2) of `face` at vertex v, or -1.
function cornerOf(triangles, face, v) {
  for (let k = 0; k < 3; k++) if (triangles[3 * face + k] === v) return k;
  return -1;
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
  const frames = new Map(); // only the seams' faces
  const frame = (f) => {
    if (!frames.has(f)) frames.set(f, faceFrame(positions, triangles, cornerUVs, f));
    return frames.get(f);
  };
  let redirected = 0, seamEdges = 0;
  // Each interior edge once, from its lower half-edge h (in face f), whose twin runs the other way in face g.
  for (let h = 0; h < 3 * nF; h++) {
    const other = halfEdges[h];
    if (other < h) continue;
    if (edgeUVsAgree(cornerUVs, h, other)) continue;
    const f = Math.floor(h / 3), g = Math.floor(other / 3);
    seamEdges++;
    // Both directions: g unfolded into f's chart, and f into g's.
    redirected += unfold(f, g) + unfold(g, f);
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
    // The shared vertices' corners (i, j in `from`; ti, tj in `to`), `to`'s opposite corner to3, `from`'s fo.
    let ti = -1, tj = -1, to3 = -1;
    for (let k = 0; k < 3; k++) {
      if (cornerOf(triangles, from, triangles[3 * to + k]) < 0) to3 = k;
      else if (ti < 0) ti = k;
      else tj = k;
    }
    if (tj < 0 || to3 < 0) return 0;
    const i = cornerOf(triangles, from, triangles[3 * to + ti]);
    const j = cornerOf(triangles, from, triangles[3 * to + tj]), fo = 3 - i - j;
    const Xi = 3 * i, Xj = 3 * j, Xo = 3 * to3, Fo = 3 * fo;
    const ex = A[Xj] - A[Xi], ey = A[Xj + 1] - A[Xi + 1], ez = A[Xj + 2] - A[Xi + 2];
    const el = Math.hypot(ex, ey, ez);
    if (!(el > 0)) return 0;
    const hx = ex / el, hy = ey / el, hz = ez / el;
    const wx = B[Xo] - A[Xi], wy = B[Xo + 1] - A[Xi + 1], wz = B[Xo + 2] - A[Xi + 2];
    const along = wx * hx + wy * hy + wz * hz;
    const h = Math.hypot(wx - hx * along, wy - hy * along, wz - hz * along);
    let px = hy * A[N + 2] - hz * A[N + 1], py = hz * A[N] - hx * A[N + 2], pz = hx * A[N + 1] - hy * A[N];
    if (px * (A[Fo] - A[Xi]) + py * (A[Fo + 1] - A[Xi + 1]) + pz * (A[Fo + 2] - A[Xi + 2]) > 0)
      (px = -px), (py = -py), (pz = -pz);
    const dx = A[Xi] + along * hx + h * px - A[Xi], dy = A[Xi + 1] + along * hy + h * py - A[Xi + 1];
    const dz = A[Xi + 2] + along * hz + h * pz - A[Xi + 2];
    // Corners of the unfolded triangle in `from`'s UV, and their UVs in `to`'s own chart.
    const ui = A[Q + 2 * i], vi = A[Q + 2 * i + 1];
    const uU = ui + (A[M] * dx + A[M + 1] * dy + A[M + 2] * dz);
    const vU = vi + (A[M + 3] * dx + A[M + 4] * dy + A[M + 5] * dz);
    const ax = ui * R, ay = vi * R, bx = A[Q + 2 * j] * R, by = A[Q + 2 * j + 1] * R, cx = uU * R, cy = vU * R;
    const d0x = B[Q + 2 * ti] * R, d0y = B[Q + 2 * ti + 1] * R, d1x = B[Q + 2 * tj] * R, d1y = B[Q + 2 * tj + 1] * R;
    const d2x = B[Q + 2 * to3] * R, d2y = B[Q + 2 * to3 + 1] * R;
    const area = (bx - ax) * (cy - ay) - (cx - ax) * (by - ay);
    if (!(Math.abs(area) > 1e-12)) return 0;
    const x0 = Math.max(0, Math.floor(Math.min(ax, bx, cx) - 0.5));
    const x1 = Math.min(R - 1, Math.ceil(Math.max(ax, bx, cx) - 0.5));
    const y0 = Math.max(0, Math.floor(Math.min(ay, by, cy) - 0.5));
    const y1 = Math.min(R - 1, Math.ceil(Math.max(ay, by, cy) - 0.5));
    let count = 0;
    for (let y = y0; y <= y1; y++)
      for (let x = x0; x <= x1; x++) {
        const t = y * R + x;
        if (covered[t] || out[4 * t + 2]) continue;
        const qx = x + 0.5, qy = y + 0.5;
        const l1 = ((cx - qx) * (ay - qy) - (ax - qx) * (cy - qy)) / area; // weight of b
        const l2 = ((ax - qx) * (by - qy) - (bx - qx) * (ay - qy)) / area; // weight of c
        const l0 = 1 - l1 - l2;
        if (l0 < -1e-6 || l1 < -1e-6 || l2 < -1e-6) continue;
        const tx = l0 * d0x + l1 * d1x + l2 * d2x;
        const ty = l0 * d0y + l1 * d1y + l2 * d2y;
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
