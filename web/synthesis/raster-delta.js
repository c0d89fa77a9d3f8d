// SPDX-License-Identifier: GPL-2.0-or-later
// Which faces a new field must be rasterized again for, and where in the atlas (atlas-raster.js). After a stroke
// most of a mesh's field moves by a hair: the faces whose field stays within a small angle of the one their
// texels were drawn with keep it, so the Jacobian's full-screen pass (bunny00 at 1024²: 50 ms of an update with
// software GL) is drawn only round the faces that moved. The bound is per face and conservative: corners' field
// b_k against a_k drawn, d = max |b_k - a_k|; anywhere in the face the new field (projected into its plane) is at
// least m = |P mean b| - max |P (b_k - mean b)| long, so where d <= m sin ε the field at every texel of the face
// turned by at most ε and scaled by at most sin ε. Owns nothing; pure functions of flat arrays.

// A run that may be local (synthesizer.js localDegrees) draws the Jacobian again only for the faces whose field
// turned by more than this share of localDegrees since they were drawn; local-update.js makes again the texels
// whose drawn Jacobian moved by more than the rest of it, so that a kept texel follows the field within
// localDegrees.
export const RASTER_SHARE = 0.25;

export const TILE = 16; // texels a side of the blocks that moved faces and texels are gathered into
const BANDS = 8; // bands of block rows

// Per face, the texels its Jacobian reaches: its UVs' box (the atlas's `resolution`) widened by `margin` texels
// (the gutter's quads reach past a chart's edge: atlas-gutter.js gutterReach), as x0, y0, x1, y1 (exclusive).
export function faceBoxes(cornerUVs, resolution, margin) {
  const nF = cornerUVs.length / 6, R = resolution;
  const boxes = new Uint16Array(4 * nF);
  for (let f = 0; f < nF; f++) {
    const o = 6 * f, u0 = cornerUVs[o], u1 = cornerUVs[o + 2], u2 = cornerUVs[o + 4];
    const v0 = cornerUVs[o + 1], v1 = cornerUVs[o + 3], v2 = cornerUVs[o + 5];
    boxes[4 * f] = Math.max(0, Math.floor(Math.min(u0, u1, u2) * R) - margin);
    boxes[4 * f + 1] = Math.max(0, Math.floor(Math.min(v0, v1, v2) * R) - margin);
    boxes[4 * f + 2] = Math.min(R, Math.ceil(Math.max(u0, u1, u2) * R) + margin);
    boxes[4 * f + 3] = Math.min(R, Math.ceil(Math.max(v0, v1, v2) * R) + margin);
  }
  return boxes;
}

// Faces f0 .. f1 - 1's unit normals (3 a face) into `normals`, from the atlas's frames (atlas-corners.js: G1, G2,
// n, 4 floats each).
export function faceNormals(frames, normals, f0, f1) {
  for (let f = f0; f < f1; f++) for (let d = 0; d < 3; d++) normals[3 * f + d] = frames[12 * f + 8 + d];
}

// Whether face f's field in `next` (4 floats a corner, 12 a face) may differ from the one in `drawn` by more than
// the angle whose sine is sinTol anywhere in the face (see above). A face whose new field may vanish in it
// (m <= 0: a singularity, no field) has moved unless its corners are exactly as drawn.
export function faceMoved(next, drawn, normals, f, sinTol) {
  const o = 12 * f;
  let d2 = 0;
  for (let k = o; k < o + 12; k += 4) {
    const dx = next[k] - drawn[k], dy = next[k + 1] - drawn[k + 1], dz = next[k + 2] - drawn[k + 2];
    const e2 = dx * dx + dy * dy + dz * dz;
    if (e2 > d2) d2 = e2;
  }
  if (d2 === 0) return false;
  const nx = normals[3 * f], ny = normals[3 * f + 1], nz = normals[3 * f + 2];
  // Projected into the face's plane (P = I - n nᵀ): the corners' mean, and its farthest corner.
  let mx = 0, my = 0, mz = 0;
  for (let k = o; k < o + 12; k += 4) {
    mx += next[k];
    my += next[k + 1];
    mz += next[k + 2];
  }
  const sm = (mx * nx + my * ny + mz * nz) / 3;
  mx = mx / 3 - sm * nx;
  my = my / 3 - sm * ny;
  mz = mz / 3 - sm * nz;
  let spread2 = 0;
  for (let k = o; k < o + 12; k += 4) {
    const x = next[k], y = next[k + 1], z = next[k + 2], s = x * nx + y * ny + z * nz;
    const e2 = (x - s * nx - mx) ** 2 + (y - s * ny - my) ** 2 + (z - s * nz - mz) ** 2;
    if (e2 > spread2) spread2 = e2;
  }
  const least = Math.sqrt(mx * mx + my * my + mz * mz) - Math.sqrt(spread2);
  return !(least > 0) || d2 > sinTol * sinTol * least * least;
}

// The rectangles (finest-level texels, [{x, y, w, h}]) that hold the boxes of `faces` (their ids, `count` of
// them): the TILE-texel blocks they touch (blockMaskRects). Empty when no face is listed.
export function blockRects(boxes, faces, count, resolution) {
  const n = Math.ceil(resolution / TILE), blocks = new Uint8Array(n * n);
  for (let i = 0; i < count; i++) {
    const b = 4 * faces[i];
    const x0 = Math.floor(boxes[b] / TILE), y0 = Math.floor(boxes[b + 1] / TILE);
    const x1 = Math.ceil(boxes[b + 2] / TILE), y1 = Math.ceil(boxes[b + 3] / TILE);
    for (let y = y0; y < y1; y++) blocks.fill(1, y * n + x0, y * n + x1);
  }
  return blockMaskRects(blocks, n);
}

// A mask of TILE-texel blocks (n x n, 1 where set, row 0 first) as rectangles in texels: the rows in BANDS bands,
// each band drawn from its first to its last row with a block set, over each run of columns with one set (the
// raster's and the local update's, local-update.js). A band over all the columns between its first and last
// block drew the atlas's scattered charts whole.
export function blockMaskRects(set, n) {
  const rects = [], rows = Math.ceil(n / BANDS), cols = new Uint8Array(n);
  for (let b = 0; b * rows < n; b++) {
    let y0 = n, y1 = -1;
    cols.fill(0);
    for (let y = b * rows; y < Math.min(n, (b + 1) * rows); y++)
      for (let x = 0; x < n; x++) if (set[y * n + x]) (cols[x] = 1), (y0 = Math.min(y0, y)), (y1 = y);
    for (let x = 0; x < n && y1 >= 0; x++) {
      if (!cols[x]) continue;
      let end = x;
      while (end + 1 < n && cols[end + 1]) end++;
      rects.push({ x: TILE * x, y: TILE * y0, w: TILE * (end - x + 1), h: TILE * (y1 - y0 + 1) });
      x = end;
    }
  }
  return rects;
}

// Where each level's Jacobian was drawn since the local update last compared it with the one its texels were
// made with (local-update.js find): L.jacDrawn, rectangles in level texels, or null for anywhere (never compared,
// drawn whole, or too many rectangles to be worth it). rects: the finest level's rectangles of this draw (null:
// whole).
const MAX_DRAWN_RECTS = 512;
export function noteJacobianDrawn(levels, rects) {
  levels.forEach((L, k) => {
    if (!rects || !L.jacDrawn || L.jacDrawn.length + rects.length > MAX_DRAWN_RECTS) L.jacDrawn = null;
    else L.jacDrawn.push(...coarserRects(rects, k));
  });
}

// The blocks (TILE texels a side, in block units) that hold `rects` (level texels).
export const blocksOf = (rects) => coarserRects(rects, Math.log2(TILE));

// The same rectangles at the level `k` steps coarser (each texel there the mean of 2^k x 2^k finest ones): every
// texel whose children the finer rectangles hold.
export function coarserRects(rects, k) {
  const s = 1 << k;
  return rects.map(({ x, y, w, h }) => {
    const x0 = Math.floor(x / s), y0 = Math.floor(y / s);
    return { x: x0, y: y0, w: Math.ceil((x + w) / s) - x0, h: Math.ceil((y + h) / s) - y0 };
  });
}
