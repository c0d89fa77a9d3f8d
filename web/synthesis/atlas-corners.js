// SPDX-License-Identifier: GPL-2.0-or-later
// The fixed per-face data the atlas raster draws from (atlas-raster.js): a pure function of the mesh and its atlas,
// so the core's worker makes it with the atlas (atlas-prepared.js) and the page only uploads it. Imports nothing.

// Floats per face of the frames: G1, G2 and the unit normal, each as an RGBA texel (w unused): texels 3f, 3f + 1,
// 3f + 2 of the raster's per-corner textures, as the field's three corners are. RGBA, not RGB: GPUs without RGB32F
// images (SwiftShader's Vulkan among them) have ANGLE widen every upload on the CPU.
export const FRAME_FLOATS = 12;

// Per face: its UVs (6, as cornerUVs) and its 3D-to-UV frame G = [e1 e2] [[du1 du2] [dv1 dv2]]^-1 (columns G1,
// G2) with its unit normal; faces degenerate in UV or in 3D keep zeros in both (their UVs collapse to a point, so
// they draw nothing). Returns {uv, frames, faceArea, used, area3, areaUV}.
export function cornerData(positions, triangles, cornerUVs) {
  const nF = triangles.length / 3;
  const uv = new Float32Array(6 * nF);
  const frames = new Float32Array(FRAME_FLOATS * nF);
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
    uv.set(u, 6 * f);
    const o = FRAME_FLOATS * f;
    for (let k = 0; k < 3; k++) {
      frames[o + k] = (e1[k] * dv2 - e2[k] * dv1) / det;
      frames[o + 4 + k] = (e2[k] * du1 - e1[k] * du2) / det;
      frames[o + 8 + k] = n[k] / nl;
    }
  }
  return { uv, frames, faceArea, used, area3, areaUV };
}

// Whether face f has a frame (cornerData's `frames`): not degenerate in UV or in 3D.
export function faceUsed(frames, f) {
  const o = FRAME_FLOATS * f;
  return frames[o] !== 0 || frames[o + 1] !== 0 || frames[o + 2] !== 0;
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
