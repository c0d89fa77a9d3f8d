// SPDX-License-Identifier: GPL-2.0-or-later
// The fixed per-corner data the atlas raster draws (atlas-raster.js): a pure function of the mesh and its atlas,
// so the core's worker makes it with the atlas (atlas-prepared.js) and the page only uploads it. Imports nothing.

// Floats per corner: uv (2), G1 (3), G2 (3), unit normal (3). The field (3 per corner) has a buffer of its own,
// the only one a synthesis fills.
export const CORNER_FLOATS = 11;

// Per corner: UV, the face's 3D-to-UV frame G = [e1 e2] [[du1 du2] [dv1 dv2]]^-1 (columns G1, G2) and unit
// normal; faces degenerate in UV or in 3D keep zeros and draw nothing.
export function cornerData(positions, triangles, cornerUVs) {
  const nF = triangles.length / 3;
  const data = new Float32Array(3 * nF * CORNER_FLOATS);
  const faceArea = new Float64Array(nF);
  let area3 = 0, areaUV = 0, used = 0;
  for (let f = 0; f < nF; f++) {
    const a = 3 * triangles[3 * f], b = 3 * triangles[3 * f + 1], c = 3 * triangles[3 * f + 2];
    const e1 = [positions[b] - positions[a], positions[b + 1] - positions[a + 1], positions[b + 2] - positions[a + 2]];
    const e2 = [positions[c] - positions[a], positions[c + 1] - positions[a + 1], positions[c + 2] - positions[a + 2]];
    const u = cornerUVs.subarray(6 * f, 6 * f + 6);
    const du1 = u[2] - u[0], dv1 = u[3] - u[1], du2 = u[4] - u[0], dv2 = u[5] - u[1];
    const det = du1 * dv2 - du2 * dv1;
    const n = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]];
    const nl = Math.hypot(n[0], n[1], n[2]);
    faceArea[f] = nl / 2;
    if (!(Math.abs(det) > 1e-14) || !(nl > 0)) continue;
    used++;
    area3 += nl / 2;
    areaUV += Math.abs(det) / 2;
    const G1 = [0, 1, 2].map((k) => (e1[k] * dv2 - e2[k] * dv1) / det);
    const G2 = [0, 1, 2].map((k) => (e2[k] * du1 - e1[k] * du2) / det);
    for (let k = 0; k < 3; k++) {
      const o = (3 * f + k) * CORNER_FLOATS;
      data[o] = u[2 * k];
      data[o + 1] = u[2 * k + 1];
      data.set(G1, o + 2);
      data.set(G2, o + 5);
      data.set([n[0] / nl, n[1] / nl, n[2] / nl], o + 8);
    }
  }
  return { data, faceArea, used, area3, areaUV };
}

// Whether half-edge h (corner h -> the next corner of its face; corners index cornerUVs as 2 per corner) and its
// twin g (running the other way in the face across) have the same UVs at both ends: the edge lies inside a chart.
export function edgeUVsAgree(cornerUVs, h, g) {
  const next = (x) => (x % 3 === 2 ? x - 2 : x + 1);
  return cornerUVsMeet(cornerUVs, h, next(g)) && cornerUVsMeet(cornerUVs, next(h), g);
}

function cornerUVsMeet(uv, p, q) {
  return Math.hypot(uv[2 * p] - uv[2 * q], uv[2 * p + 1] - uv[2 * q + 1]) < 1e-7;
}
