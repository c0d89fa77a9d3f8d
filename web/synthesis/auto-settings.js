// SPDX-License-Identifier: GPL-2.0-or-later
// The synthesis settings chosen for the user ('auto'): the atlas resolution from the face count, and the
// feature scale from the model's curvature and the atlas's texel density. Pure functions of the model, kept
// apart from the controller so the tests can check them against analytic shapes.

// Default feature size. Stripes read as following the field only where the field (and the surface it lies on)
// turns little over a stripe period; on a curved model the field turns with the surface, so the exemplar tile
// is sized from the model's curvature: tiles across sqrt(area) = TILES_PER_COMPLEXITY x the shape complexity
// (sqrt(area) x the area-mean |mean curvature|: 3.5 for a sphere, ~14 for the bunny, ~18 for homer, ~34 for a thin
// knotted tube), between MIN_TILES and MAX_TILES. Measured on exported GLBs (docs/texture-synthesis.md): on
// homer 6 tiles left 9.6° mean deviation, 12 tiles 5.8°, with the same synthesis. 0.66 (refined_elephant, c ≈ 19:
// 12.7 tiles) left the genus-3 elephant at 6.43° / 83 %; 0.84 (16 tiles) measured 5.19° / 90 %. A 2048² atlas at
// 12.7 tiles did not help (6.59° / 82 %): the feature size, not texels per face, was the limit.
const TILES_PER_COMPLEXITY = 0.84;
const MIN_TILES = 6;
const MAX_TILES = 16;
// Below this many atlas texels per exemplar pixel the synthesis resolves the exemplar's features with too few
// texels (a 16-pixel stripe period in fewer than 10 texels): the tile count gives way first.
const MIN_FEATURE_SCALE = 0.625;

// The atlas resolution a model gets by default: enough texels per face for the Jacobian to vary smoothly and for
// a stripe period to span ≥ 10 texels at the default feature size (≈ 16 texels per face at ~60 % coverage),
// between 256² and 1024².
export function defaultResolution(numFaces) {
  const want = Math.sqrt((numFaces * 16) / 0.6);
  let r = 256;
  while (r < want && r < 1024) r *= 2;
  return r;
}

// sqrt(area) x the area-mean |mean curvature|, from dihedral angles: sum over interior edges of |theta_e| l_e,
// over 2 x area (1 / radius on a sphere, so a sphere scores sqrt(4 pi) = 3.5). Scale-free. surface: the model's
// Surface (geometry/surface.js: positions, triangles, face normals and areas, the half-edge map `neighbour`);
// degenerate faces take no part.
export function shapeComplexity({ positions, triangles, normals, areas, neighbour }) {
  const nF = triangles.length / 3;
  let area = 0, bend = 0;
  for (let f = 0; f < nF; f++) area += areas[f];
  for (let h = 0; h < 3 * nF; h++) {
    const other = neighbour[h];
    if (other < h) continue; // a boundary, or the edge seen from its other side
    const f = Math.floor(h / 3), g = Math.floor(other / 3);
    if (!(areas[f] > 0 && areas[g] > 0)) continue;
    const i = 3 * triangles[h], j = 3 * triangles[3 * f + ((h + 1) % 3)];
    const d =
      normals[3 * f] * normals[3 * g] +
      normals[3 * f + 1] * normals[3 * g + 1] +
      normals[3 * f + 2] * normals[3 * g + 2];
    const len = Math.hypot(
      positions[i] - positions[j],
      positions[i + 1] - positions[j + 1],
      positions[i + 2] - positions[j + 2],
    );
    bend += Math.acos(Math.min(1, Math.max(-1, d))) * len;
  }
  return area > 0 ? (bend / (2 * area)) * Math.sqrt(area) : 0;
}

// The feature scale (atlas texels per exemplar pixel at the atlas's mean density) that makes one exemplar tile
// span sqrt(area) / tiles on the surface, tiles from the shape complexity (above): tile length
// m * featureScale * texelLength, with texelLength = sqrt(area / coverage) / R.
export function defaultFeatureScale(resolution, coverage, exemplarSize, complexity = MIN_TILES / TILES_PER_COMPLEXITY) {
  const tiles = Math.min(MAX_TILES, Math.max(MIN_TILES, TILES_PER_COMPLEXITY * complexity));
  const fs = (resolution * Math.sqrt(Math.max(coverage, 0.05))) / (tiles * exemplarSize);
  return Math.min(8, Math.max(MIN_FEATURE_SCALE, fs));
}
