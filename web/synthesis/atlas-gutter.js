// SPDX-License-Identifier: GPL-2.0-or-later
// The atlas's gutter as geometry: a thin quad outside every chart edge (an edge whose face across has other UVs,
// or none), drawn before the triangles so that the texels just past a chart take the edge's face's Jacobian with
// the field held at the edge. It replaces two full-screen dilation passes per raster, which shaded every texel of
// the atlas (98 of bunny00's 144 ms of raster on SwiftShader) to fill a ring a texel or two wide. A pure function
// of the mesh, its atlas and the gutter width: the core's worker makes it with the atlas (atlas-prepared.js).
// The raster draws the quads once per atlas, into its map of faces (atlas-raster.js). Imports only atlas-corners.js.
import { edgeUVsAgree, faceUsed } from './atlas-corners.js';

// The quads' reach past the edge in texels: the texels that bilinear filtering at the chart's edge reads (centres
// up to √2/2 + 1/2 away) and little more, so that a quad keeps to the border the packing gave its chart alone
// (core/texture/texture_atlas.cpp chartShape: every texel within 1.7 texels of the chart is its own); only the
// quads' square ends at a convex corner reach further, √2 times as far.
export function gutterReach(gutter) {
  return gutter > 0 ? Math.min(1.5, gutter) : 0;
}

// For each chart edge, four vertices (the edge's two ends moved `reach` texels outwards along it, and the same two
// moved `reach` texels away from the face) and two triangles. corners: cornerData()'s {frames}; neighbour: the
// half-edge map (geometry/mesh-geometry.js). Returns {uv: Float32Array (2 per vertex), source: Int32Array (per
// vertex, the corner 3f + k whose field it takes: the quad's texels take their face's frame and the field
// interpolated between the edge's two corners), indices: Uint32Array (6 per edge)}.
export function gutterQuads({ triangles, cornerUVs, corners, resolution, gutter, neighbour: twin }) {
  const reach = gutterReach(gutter) / resolution;
  const nF = triangles.length / 3;
  const used = new Uint8Array(nF);
  for (let f = 0; f < nF; f++) used[f] = faceUsed(corners.frames, f) ? 1 : 0;
  const edgeList = new Int32Array(3 * nF);
  let n = 0;
  for (let h = 0; reach > 0 && h < 3 * nF; h++) {
    if (!used[(h / 3) | 0]) continue;
    const g = twin[h];
    if (g >= 0 && used[(g / 3) | 0] && edgeUVsAgree(cornerUVs, h, g)) continue;
    edgeList[n++] = h;
  }
  const uv = new Float32Array(8 * n), source = new Int32Array(4 * n), indices = new Uint32Array(6 * n);
  for (let e = 0; e < n; e++) quad(edgeList[e], e);
  return { uv, source, indices };

  // Vertex i of edge e's quad: at (u, v), taking corner `corner`'s field.
  function vertex(e, i, corner, u, v) {
    const o = 2 * (4 * e + i);
    uv[o] = u;
    uv[o + 1] = v;
    source[4 * e + i] = corner;
  }

  function quad(h, e) {
    const f = (h / 3) | 0, k = h - 3 * f, ka = 3 * f + k, kb = 3 * f + ((k + 1) % 3), kc = 3 * f + ((k + 2) % 3);
    const ax = cornerUVs[2 * ka], ay = cornerUVs[2 * ka + 1], bx = cornerUVs[2 * kb], by = cornerUVs[2 * kb + 1];
    const len = Math.sqrt((bx - ax) * (bx - ax) + (by - ay) * (by - ay));
    const tx = len > 0 ? ((bx - ax) / len) * reach : 0, ty = len > 0 ? ((by - ay) / len) * reach : 0;
    // Outwards: away from the face's third corner.
    const side = -ty * (cornerUVs[2 * kc] - ax) + tx * (cornerUVs[2 * kc + 1] - ay);
    const nx = side > 0 ? ty : -ty, ny = side > 0 ? -tx : tx;
    vertex(e, 0, ka, ax - tx, ay - ty);
    vertex(e, 1, kb, bx + tx, by + ty);
    vertex(e, 2, kb, bx + tx + nx, by + ty + ny);
    vertex(e, 3, ka, ax - tx + nx, ay - ty + ny);
    const i = 6 * e, v = 4 * e;
    indices[i] = v;
    indices[i + 1] = v + 1;
    indices[i + 2] = v + 2;
    indices[i + 3] = v;
    indices[i + 4] = v + 2;
    indices[i + 5] = v + 3;
  }
}
